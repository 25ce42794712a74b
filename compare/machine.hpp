#pragma once
// Where and with what a result was produced, for results.json.
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

// Writes `text` to `path` through a temporary file in the same folder and a
// rename, so an interrupted run never leaves half a file. Throws run_error.
void write_file_atomically(const std::filesystem::path& path, const std::string& text);

}  // namespace gacompare::compare
