#pragma once
// Where and with what a result was produced, for results.json.
#include <array>
#include "compare/files.hpp"  // write_file_atomically, which every writer of results uses

#include <filesystem>
#include <string>

namespace gacompare::compare {

// What the source tree was when this binary was built (compare/build_info.cmake
// records it at every build): the commit, or "unknown" outside a git checkout,
// and "yes", "no" or "unknown" for whether the tree differed from it.
struct BuildInfo {
  std::string commit, dirty;
};
BuildInfo build_info();

struct MachineInfo {
  std::string cpu;       // /proc/cpuinfo "model name", or "unknown"
  std::string compiler;  // compiler id and version this binary was built with
  std::string date;      // UTC, ISO 8601
  std::string build_type;
  // From here on with default initialisers, so MachineInfo{cpu, compiler, date,
  // build_type} stays free of missing-initialiser warnings.
  std::string flags{};   // the C++ flags of this build (CMAKE_CXX_FLAGS and the build type's)
  std::string allocator{};  // the malloc this process runs on: "tcmalloc (gperftools 2.10)" or "system (glibc 2.36)"
  int logical_cpus = 0;  // online (std::thread::hardware_concurrency), 0 when unknown
  int usable_cpus = 0;   // in this process's affinity mask (what a run may use), 0 when unknown
  // The 1, 5 and 15 minute load averages (getloadavg) when this record was
  // taken; a run takes one at its start (before it adds its own load) and
  // one at its end (which includes it: about 1 on an otherwise idle machine).
  std::array<double, 3> load_average{-1, -1, -1};
  std::array<double, 3> load_average_end{-1, -1, -1};
  BuildInfo build{};
};

// Taken now: the date, the load averages (both) and everything else.
MachineInfo machine_info();
// The same record with its end load average taken now.
MachineInfo finished(MachineInfo m);
std::string tool_version();

}  // namespace gacompare::compare
