#pragma once
// Text from files (scene, body and backend names, descriptions, error
// messages, a cell's settings) quoted in a report, escaped for the report's
// format, so that it stays text there: never markup, never a table's or a
// row's end, never a formula.
#include <string>
#include <string_view>

namespace gacompare::compare {

// Markdown (GitHub's): '&', '<' and '>' as HTML entities (no tag ever reaches
// a viewer that renders HTML), '|' and '\' with a backslash (a table keeps its
// columns), and every line break or other control character as a space (a
// table keeps its rows). compare/report_html.cpp's markdown_to_html reads these
// back as the characters they stand for.
std::string md_text(std::string_view text);

// One CSV field (RFC 4180): quoted when it holds a comma, a quote or a line
// break, quotes doubled; and a field that starts with '=', '+', '-', '@', a tab
// or a carriage return, which a spreadsheet would read as a formula, gets a
// leading apostrophe (and quotes). For text fields: numbers are written as
// numbers, a negative one's '-' included.
std::string csv_field(std::string_view text);

// JSON text placed inside an HTML <script> element: every '<', '>' and '&' as
// \u003c, \u003e and \u0026, which mean the same in a JSON string, so that no
// "</script>" or "<!--" in a name can end or derail the element. Valid JSON
// has these characters only inside strings.
std::string json_for_script(std::string_view json_text);

}  // namespace gacompare::compare
