// compare/escape.hpp: text quoted in a report stays text in its format, and
// reads back as what it was (markdown through markdown_to_html, CSV through an
// RFC 4180 reader, JSON in a script element through a JSON parser).
#include "compare/escape.hpp"
#include "compare/report.hpp"

#include "csv_fields.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace {
using namespace gacompare::compare;

TEST(Escape, MarkdownKeepsTagsTablesAndRowsOut) {
  EXPECT_EQ(md_text("<script>a|b\\c\nd&e\r"), "&lt;script&gt;a\\|b\\\\c d&amp;e ");
  EXPECT_EQ(md_text("cube_drop_flat"), "cube_drop_flat");
  // In a table row it is one cell, and the page shows the text as written (a
  // line break as a space), escaped for HTML once.
  const std::string name = "<img src=x onerror=alert(1)>|x\\|&lt;";
  const std::string html = markdown_to_html("| a | b |\n|---|---|\n| " + md_text(name) + " | 2 |\n");
  EXPECT_NE(html.find("<td>" + html_escape(name) + "</td><td>2</td>"), std::string::npos) << html;
  EXPECT_EQ(html.find("<img"), std::string::npos);
}

TEST(Escape, CsvFieldsAreQuotedAndFormulasNeutralised) {
  EXPECT_EQ(csv_field("plain name"), "plain name");
  EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_field("say \"hi\"\nthere"), "\"say \"\"hi\"\"\nthere\"");
  for (const std::string f : {"=1+2", "+1", "-2+3", "@SUM(A1)", "\tx"}) EXPECT_EQ(csv_field(f), "\"'" + f + "\"");
  const std::string row = csv_field("=1+2,x,\"y\"") + "," + csv_field("b") + "\n";
  const auto rows = csv_rows(row);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0], (std::vector<std::string>{"'=1+2,x,\"y\"", "b"}));
}

TEST(Escape, JsonInAScriptHoldsNoAngleBracketAndReadsBack) {
  const std::string name = "<!--<script></script>&";
  const std::string text = json_for_script(nlohmann::json{{"name", name}}.dump());
  EXPECT_EQ(text.find_first_of("<>&"), std::string::npos) << text;
  EXPECT_EQ(nlohmann::json::parse(text)["name"], name);
}

}  // namespace
