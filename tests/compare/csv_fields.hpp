#pragma once
// One line of a CSV split at its commas (the harness's CSVs quote no field the
// tests read). Shared by cli_test.cpp and replay_test.cpp.
#include <string>
#include <vector>

inline std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> out(1);
  for (char c : line) {
    if (c == ',') out.emplace_back();
    else out.back().push_back(c);
  }
  return out;
}
