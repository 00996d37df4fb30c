// Tray-test CSV reader: passes averaged, layout about the centre line, and errors naming the line.
#include <gtest/gtest.h>

#include <string>

#include "libspread/analysis/calibration/tray_csv.hpp"

namespace cal = spread::calibration;

namespace {

// The message of the TrayCsvError the text raises ("" when it parses).
std::string error_of(const std::string& text, int* line = nullptr) {
  try {
    cal::parse_tray_csv(text, "t.csv");
  } catch (const cal::TrayCsvError& e) {
    if (line != nullptr) *line = e.line();
    return e.what();
  }
  return "";
}

}  // namespace

TEST(TrayCsv, AveragesPassesAndConvertsGrams) {
  const cal::TrayTest t = cal::parse_tray_csv(
      "# tray test 2026-05-01\n"
      "tray,position_m,pass1_g,pass2_g\n"
      "1,-1.0,1,3   # left end\n"
      "\n"
      "2,-0.5,2,4\n"
      "3,0.0,3,5\n"
      "4,0.5,4,6\n"
      "5,1.0,5,7\n",
      "t.csv");
  ASSERT_EQ(t.mass_kg.size(), 5u);
  EXPECT_EQ(t.mass_columns, (std::vector<std::string>{"pass1_g", "pass2_g"}));
  EXPECT_NEAR(t.mass_kg[0], 2e-3, 1e-15);
  EXPECT_NEAR(t.mass_kg[4], 6e-3, 1e-15);
  EXPECT_NEAR(t.tray_width_m, 0.5, 1e-12);
  EXPECT_EQ(t.layout.tray_count, 5);
  EXPECT_EQ(t.padded_trays, 0);
  EXPECT_NEAR(t.total_mass_kg(), 20e-3, 1e-15);
}

TEST(TrayCsv, OneSidedRowIsPaddedToSymmetricLayout) {
  // Trays from the centre line to the right only: the left side is added empty.
  const cal::TrayTest t = cal::parse_tray_csv(
      "position_m;mass_kg\n0.25;0.001\n0.75;0.002\n1.25;0.003\n1.75;0.004\n2.25;0.005\n", "t.csv");
  EXPECT_EQ(t.layout.tray_count, 10);
  EXPECT_EQ(t.padded_trays, 5);
  EXPECT_NEAR(t.layout.left_edge_m(), -2.5, 1e-12);
  EXPECT_EQ(t.layout_mass_kg[4], 0.0);
  EXPECT_NEAR(t.layout_mass_kg[5], 0.001, 1e-15);  // centre 0.25
  EXPECT_NEAR(t.layout_mass_kg[9], 0.005, 1e-15);
}

TEST(TrayCsv, ErrorsNameTheLine) {
  const std::string header = "position_m,pass1_g,pass2_g\n";
  const std::string good = "-1.0,1,1\n-0.5,1,1\n0.0,1,1\n0.5,1,1\n1.0,1,1\n";
  int line = -1;

  EXPECT_NE(error_of(header + "-1.0,1,1\n-0.5,1,-2\n0.0,1,1\n0.5,1,1\n1.0,1,1\n", &line)
                .find("t.csv:3: pass2_g: negative mass -2"),
            std::string::npos);
  EXPECT_EQ(line, 3);
  EXPECT_NE(error_of(header + "-1.0,1,1\n-0.5,1\n0.0,1,1\n0.5,1,1\n1.0,1,1\n").find("t.csv:3: expected 3 cells"),
            std::string::npos);
  EXPECT_NE(error_of("# c\n" + header + "-1.0,1,1\n-0.5,x1,1\n0.0,1,1\n0.5,1,1\n1.0,1,1\n")
                .find("t.csv:4: pass1_g: 'x1' is not a number"),
            std::string::npos);
  EXPECT_NE(error_of("mass_g,pass2_g\n1,2\n").find("t.csv:1: missing column position_m"), std::string::npos);
  EXPECT_NE(error_of("position_m,tray\n1,2\n").find("t.csv:1: missing mass column"), std::string::npos);
  EXPECT_NE(error_of(header + "-1.0,1,1\n-0.5,1,1\n0.0,1,1\n").find("too few trays: 3"), std::string::npos);
  EXPECT_NE(error_of(header + "-1.0,1,1\n-0.5,1,1\n0.0,1,1\n1.0,1,1\n1.5,1,1\n")
                .find("t.csv:5: non-uniform tray spacing"),
            std::string::npos);
  EXPECT_NE(error_of(header + "-1.0,1,1\n-0.5,1,1\n-0.5,1,1\n0.0,1,1\n0.5,1,1\n").find("t.csv:4: position_m"),
            std::string::npos);
  EXPECT_NE(error_of(header + "-0.9,1,1\n-0.4,1,1\n0.1,1,1\n0.6,1,1\n1.1,1,1\n").find("t.csv:2: tray centres are not"),
            std::string::npos);
  EXPECT_NE(error_of(header + "-1.0,0,0\n-0.5,0,0\n0.0,0,0\n0.5,0,0\n1.0,0,0\n").find("no mass"), std::string::npos);
  EXPECT_NE(error_of(header + "-1.0,nan,1\n-0.5,1,1\n0.0,1,1\n0.5,1,1\n1.0,1,1\n").find("t.csv:2:"),
            std::string::npos);
  EXPECT_EQ(error_of(header + good), "");
  EXPECT_THROW(cal::read_tray_csv("/nonexistent/tray.csv"), cal::TrayCsvError);
}

TEST(TrayCsv, QuotedCellsAsSpreadsheetsExportThem) {
  // RFC 4180 quoting: quoted numbers and names, a separator and a '#' inside quotes, "" for a quote.
  const cal::TrayTest t = cal::parse_tray_csv(
      "\"tray \"\"#\"\"\",\"position_m\",\"pass1_g\", \"pass2_g\"\n"
      "\"a, left\",\"-1.0\",\"1\",3\n"
      "b,-0.5, \"2\" ,4  # comment after quoted cells\n"
      "c,0.0,3,5\n"
      "d,0.5,4,6\n"
      "e,1.0,5,\"7\"\n",
      "t.csv");
  ASSERT_EQ(t.mass_kg.size(), 5u);
  EXPECT_EQ(t.mass_columns, (std::vector<std::string>{"pass1_g", "pass2_g"}));
  EXPECT_NEAR(t.mass_kg[0], 2e-3, 1e-15);
  EXPECT_NEAR(t.mass_kg[1], 3e-3, 1e-15);
  EXPECT_NEAR(t.mass_kg[4], 6e-3, 1e-15);
}

TEST(TrayCsv, DecimalCommaWithSemicolonSeparator) {
  const cal::TrayTest t = cal::parse_tray_csv(
      "position_m;mass_g\n\"-1,0\";\"0,5\"\n-0,5;1,5\n0;2\n0,5;2,5\n1,0;3\n", "t.csv");
  ASSERT_EQ(t.mass_kg.size(), 5u);
  EXPECT_NEAR(t.position_m[0], -1.0, 1e-15);
  EXPECT_NEAR(t.mass_kg[0], 0.5e-3, 1e-15);
  EXPECT_NEAR(t.mass_kg[4], 3e-3, 1e-15);
}

TEST(TrayCsv, BadQuotingNamesTheLine) {
  const std::string header = "position_m,mass_g\n";
  const std::string rows = "-0.5,1\n0.0,1\n0.5,1\n1.0,1\n";
  int line = -1;
  EXPECT_NE(error_of(header + "-1.0,\"1\n" + rows, &line).find("t.csv:2: unterminated quote in cell 2"),
            std::string::npos);
  EXPECT_EQ(line, 2);
  EXPECT_NE(error_of(header + rows + "\"1.5\"x,1\n").find("t.csv:6: cell 1: text after the closing quote"),
            std::string::npos);
  EXPECT_NE(error_of(header + "-1.0,1\"2\n" + rows).find("t.csv:2: cell 2: a quote inside an unquoted cell"),
            std::string::npos);
  // A quoted number is still checked as a number; a decimal comma with ',' separators gets a hint.
  EXPECT_NE(error_of(header + "-1.0,\"x\"\n" + rows).find("t.csv:2: mass_g: 'x' is not a number"),
            std::string::npos);
  EXPECT_NE(error_of(header + "-1.0,\"1,5\"\n" + rows).find("decimal commas only in files separated by"),
            std::string::npos);
  EXPECT_NE(error_of("\"position_m,mass_g\n" + rows).find("t.csv:1: header: unterminated quote"), std::string::npos);
}

TEST(TrayCsv, Utf8ByteOrderMarkIsSkipped) {
  // "CSV UTF-8" from a spreadsheet starts with EF BB BF: invisible, and before this the header was refused.
  const cal::TrayTest t = cal::parse_tray_csv(
      "\xEF\xBB\xBFposition_m,mass_g\n-1.0,1\n-0.5,2\n0.0,3\n0.5,2\n1.0,1\n", "bom.csv");
  EXPECT_EQ(t.mass_kg.size(), 5u);
  EXPECT_NE(error_of(std::string("\xFF\xFE", 2) + "position_m,mass_g\n").find("UTF-16"), std::string::npos);
}

TEST(TrayCsv, DecimalCommaHintInUnquotedCells) {
  // With ',' separators an unquoted 0,5 splits into two cells: the row has more cells than the header.
  const std::string rows = "-0.5,1\n0.0,1\n0.5,1\n1.0,1\n";
  const std::string message = error_of("position_m,mass_g\n-1,0,0,5\n" + rows);
  EXPECT_NE(message.find("t.csv:2: expected 2 cells as in the header, found 4 (decimal commas?"), std::string::npos)
      << message;
  // Fewer cells is a short row, not a decimal comma.
  EXPECT_EQ(error_of("position_m,mass_g,pass2_g\n-1.0,1\n" + rows).find("decimal commas"), std::string::npos);
}
