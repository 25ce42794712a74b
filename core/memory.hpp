#pragma once
// How the process keeps memory it frees: called once at the start of every
// tool that runs scenes (gacompare, gacompare-state-hash, the tables in
// bench/).
//
// Why: glibc gives the top of its heap back to the system whenever the free
// memory there passes its trim threshold (128 KiB at first), and a later
// allocation takes it back page by page. A contact solve builds and frees its
// matrices at every step, so a stack's run kept shrinking and growing the
// heap: on a 10-layer wall pyramid 16 % of the run was the kernel's page
// faults and TLB flushes (perf), and the run took 1.4-1.9 s per simulated
// second against 0.93 s with trimming off, the same answers bit for bit and
// the same peak memory (13 MB). So freed memory stays with the process (up to
// 1 GiB at the heap's top), and blocks up to 32 MiB (glibc's largest mmap
// threshold) come from the heap rather than from a mapping of their own made
// and unmade each time.
namespace gacompare::core {

void keep_freed_memory();

}  // namespace gacompare::core
