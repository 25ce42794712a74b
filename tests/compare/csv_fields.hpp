#pragma once
// CSV read back in tests. csv_fields: one line split at its commas (the
// harness's CSVs quote no field those tests read). csv_rows: a whole document
// by RFC 4180 (quoted fields, doubled quotes, line breaks inside quotes), as a
// spreadsheet reads it. Shared by cli_test.cpp, replay_test.cpp and the
// reliability tests.
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

// Rows of fields; a quote that is not where RFC 4180 allows one makes the
// document malformed: then the result is empty.
inline std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> row(1);
  bool quoted = false, was_quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c != '"') row.back() += c;
      else if (i + 1 < text.size() && text[i + 1] == '"') row.back() += '"', ++i;
      else quoted = false;
    } else if (c == '"') {
      if (!row.back().empty() || was_quoted) return {};
      quoted = was_quoted = true;
    } else if (c == ',') {
      row.emplace_back();
      was_quoted = false;
    } else if (c == '\n') {
      rows.push_back(row);
      row.assign(1, "");
      was_quoted = false;
    } else if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') {
      continue;
    } else {
      if (was_quoted) return {};
      row.back() += c;
    }
  }
  if (quoted) return {};
  if (row.size() > 1 || !row.back().empty()) rows.push_back(row);
  return rows;
}
