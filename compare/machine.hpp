#pragma once
// Where and with what a result was produced, for results.json.
#include "compare/files.hpp"  // write_file_atomically, which every writer of results uses

#include <filesystem>
#include <string>

namespace gacompare::compare {

struct MachineInfo {
  std::string cpu;       // /proc/cpuinfo "model name", or "unknown"
  std::string compiler;  // compiler id and version this binary was built with
  std::string date;      // UTC, ISO 8601
  std::string build_type;
};

MachineInfo machine_info();
std::string tool_version();

}  // namespace gacompare::compare
