#include "compare/machine.hpp"

#include "core/error.hpp"

#include <chrono>
#include <cstring>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <dlfcn.h>
#include <gnu/libc-version.h>
#include <sched.h>
#include <stdlib.h>
#include <thread>

#ifndef GACOMPARE_VERSION
#define GACOMPARE_VERSION "unknown"
#endif
#ifndef GACOMPARE_BUILD_TYPE
#define GACOMPARE_BUILD_TYPE "unknown"
#endif
#ifndef GACOMPARE_CXX_FLAGS
#define GACOMPARE_CXX_FLAGS "unknown"
#endif

namespace gacompare::compare {

std::string tool_version() { return GACOMPARE_VERSION; }

namespace {
// Asked of the running process, not of the build: the executables link
// tcmalloc (CMakeLists.txt), the tests and sanitized builds do not.
std::string allocator() {
  using Version = const char* (*)(int*, int*, const char**);
  if (void* symbol = dlsym(RTLD_DEFAULT, "tc_version")) {
    Version version;
    std::memcpy(&version, &symbol, sizeof version);
    int major = 0, minor = 0;
    const char* patch = nullptr;
    return std::string("tcmalloc (") + version(&major, &minor, &patch) + ")";
  }
  return std::string("system (glibc ") + gnu_get_libc_version() + ")";
}
}  // namespace

MachineInfo machine_info() {
  MachineInfo m;
  m.cpu = "unknown";
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) m.cpu = line.substr(line.find_first_not_of(' ', colon + 1));
      break;
    }
  }
#if defined(__clang__)
  m.compiler = "clang " __clang_version__;
#elif defined(__GNUC__)
  m.compiler = "gcc " __VERSION__;
#else
  m.compiler = "unknown";
#endif
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &utc);
  m.date = buf;
  m.build_type = GACOMPARE_BUILD_TYPE;
  m.flags = GACOMPARE_CXX_FLAGS;
  m.allocator = allocator();
  m.logical_cpus = static_cast<int>(std::thread::hardware_concurrency());
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) m.usable_cpus = CPU_COUNT(&set);
  m.build = build_info();
  m = finished(m);
  m.load_average = m.load_average_end;
  return m;
}

MachineInfo finished(MachineInfo m) {
  double load[3];
  if (getloadavg(load, 3) == 3) m.load_average_end = {load[0], load[1], load[2]};
  return m;
}

}  // namespace gacompare::compare
