// The PDF report's parts: the stamped date (SOURCE_DATE_EPOCH), the widths and rows of the CV table, and
// the writer's errors. The rendered report is checked end to end in tests/tools/test_report_cli.cpp.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "libspread/analysis/plot/cv_table.hpp"
#include "libspread/analysis/plot/report_date.hpp"
#include "libspread/analysis/plot/report_pdf.hpp"

namespace sp = spread::plot;

namespace {

// Page objects: "/Type /Page" not followed by "s" (the page tree is "/Type /Pages").
std::size_t page_count(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string a(std::istreambuf_iterator<char>(in), {});
  std::size_t pages = 0;
  for (std::size_t at = a.find("/Type /Page"); at != std::string::npos; at = a.find("/Type /Page", at + 1)) {
    pages += at + 11 < a.size() && a[at + 11] != 's' ? 1 : 0;
  }
  return pages;
}

std::vector<double> curve_widths(double tray_m, int trays) {
  std::vector<double> widths;
  for (int n = 2; n <= trays; ++n) widths.push_back(n * tray_m);
  return widths;
}

}  // namespace

TEST(ReportDate, SourceDateEpochFixesTheDate) {
  EXPECT_EQ(sp::report_time_s(nullptr, 42), 42);
  EXPECT_EQ(sp::report_time_s("", 42), 42);
  EXPECT_EQ(sp::report_time_s("1764000000", 42), 1764000000);
  EXPECT_EQ(sp::utc_date(1764000000), "2025-11-24");
  EXPECT_EQ(sp::utc_date_time(1764000000), "2025-11-24 16:00 UTC");
  EXPECT_EQ(sp::utc_date(0), "1970-01-01");
}

TEST(ReportDate, MalformedSourceDateEpochIsRefusedNamingIt) {
  for (const char* bad : {"-1", "17e8", "2025-11-24", " 1", "99999999999999"}) {
    try {
      sp::report_time_s(bad, 0);
      ADD_FAILURE() << bad << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("SOURCE_DATE_EPOCH"), std::string::npos) << e.what();
    }
  }
}

TEST(CvTable, StandardWidthsWhenTheThrowReachesThem) {
  const std::vector<double> widths = curve_widths(0.5, 80);  // up to 40 m
  EXPECT_EQ(sp::cv_table_widths_m(36.0, widths), (std::vector<double>{12.0, 15.0, 18.0, 21.0, 24.0}));
  // Three standard widths within the throw are enough; those beyond the curve are dropped.
  EXPECT_EQ(sp::cv_table_widths_m(18.5, curve_widths(0.5, 40)), (std::vector<double>{12.0, 15.0, 18.0}));
}

TEST(CvTable, WidthsFitTheThrowOfANarrowPattern) {
  // A 12.5 m throw (the example tray test): a sixth is 2.08 m, on 0.5 m trays 2 m: 2, 4, ..., 10 m.
  EXPECT_EQ(sp::cv_table_widths_m(12.5, curve_widths(0.5, 72)), (std::vector<double>{2.0, 4.0, 6.0, 8.0, 10.0}));
  // A throw narrower than six trays: one tray per step, starting at the curve's first width (2 trays).
  EXPECT_EQ(sp::cv_table_widths_m(1.5, curve_widths(0.5, 10)), (std::vector<double>{1.0, 1.5, 2.0, 2.5}));
  EXPECT_TRUE(sp::cv_table_widths_m(10.0, {}).empty());
}

TEST(CvTable, RowsAreTheCurvePointsAtThoseWidths) {
  const std::vector<double> widths = curve_widths(0.5, 10);
  std::vector<double> tf, rt;
  for (double w : widths) {
    tf.push_back(w / 100.0);
    rt.push_back(w / 50.0);
  }
  tf[2] = std::numeric_limits<double>::infinity();
  const std::vector<double> asked{1.0, 2.0, 2.25, 3.0};
  const auto rows = sp::cv_table(asked, widths, tf, rt);  // 2.25 m is not a curve point
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].bout_width_m, 1.0);
  EXPECT_EQ(rows[0].cv_to_and_fro, 0.01);
  EXPECT_EQ(rows[0].cv_racetrack, 0.02);
  EXPECT_TRUE(std::isinf(rows[1].cv_to_and_fro));  // 2 m = curve index 2
  EXPECT_EQ(rows[2].bout_width_m, 3.0);
  EXPECT_THROW(sp::cv_table(asked, widths, tf, std::vector<double>{}), std::invalid_argument);
}

TEST(ReportPdf, UnwritablePathNamesIt) {
  sp::TablePage page;
  page.columns = {"a", "b"};
  page.rows = {{"1", "2"}};
  const std::string path = "/nonexistent-folder-for-spread-tests/report.pdf";
  try {
    sp::write_report_pdf(path, nullptr, &page);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  page.rows = {{"1"}};
  EXPECT_THROW(sp::write_report_pdf(::testing::TempDir() + "/bad_row.pdf", nullptr, &page), std::invalid_argument);
  EXPECT_THROW(sp::write_report_pdf(::testing::TempDir() + "/none.pdf", nullptr, nullptr), std::invalid_argument);
}

TEST(ReportPdf, TwoPagesAndTheSameFileForTheSameData) {
  // A pattern page (triangle of trays, overlapped at 2 m) and a table page: a PDF of two pages,
  // byte-identical when written twice with the same time stamp.
  sp::PatternReport pattern;
  pattern.header.material = "Urea";
  pattern.header.time_s = 1764000000;
  pattern.trays = {0.5, 8};
  pattern.tray_mass_kg = {0.0, 0.001, 0.002, 0.003, 0.003, 0.002, 0.001, 0.0};
  pattern.chart.bout_width_m = 2.0;
  pattern.cv_table = {{2.0, 0.05, 0.06}};
  sp::TablePage table;
  table.header = pattern.header;
  table.columns = {"width", "rpm"};
  table.rows = {{"12 m", "600"}};
  const std::string first = ::testing::TempDir() + "/report_a.pdf", second = ::testing::TempDir() + "/report_b.pdf";
  sp::write_report_pdf(first, &pattern, &table);
  sp::write_report_pdf(second, &pattern, &table);
  auto bytes = [](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string a = bytes(first);
  ASSERT_GT(a.size(), 1000u);
  EXPECT_EQ(a.substr(0, 5), "%PDF-");
  EXPECT_EQ(a, bytes(second));
  // Two page objects.
  std::size_t pages = 0;
  for (std::size_t at = a.find("/Type /Page\n"); at != std::string::npos; at = a.find("/Type /Page\n", at + 1)) ++pages;
  for (std::size_t at = a.find("/Type /Page "); at != std::string::npos; at = a.find("/Type /Page ", at + 1)) ++pages;
  EXPECT_EQ(pages, 2u);
}

// Notes never run over the footer: a few long ones shrink to fit the page, many more continue on a page
// of their own (a calibration report with the rate and the guidance ran its notes into the footer).
TEST(ReportPdf, NotesFitAboveTheFooterOrContinue) {
  sp::PatternReport pattern;
  pattern.header.time_s = 1764000000;
  pattern.header.made_by = "spread calibrate pattern --report notes.pdf";
  pattern.verdicts = {{sp::ReportVerdict::Level::kFail, "FAIL", "CV at the 8.00 m bout: 22.0 %, above the target 15 %"},
                      {sp::ReportVerdict::Level::kPass, "PASS", "Rate (EN 13739-2): 99.4 % of the set rate"}};
  pattern.trays = {0.5, 8};
  pattern.tray_mass_kg = {0.0, 0.001, 0.002, 0.003, 0.003, 0.002, 0.001, 0.0};
  pattern.chart.bout_width_m = 2.0;
  pattern.cv_table = {{2.0, 0.05, 0.06}, {3.0, 0.07, 0.08}, {4.0, 0.09, 0.1}, {5.0, 0.11, 0.12}, {6.0, 0.13, 0.14}};
  sp::ReportRate rate;
  rate.tray_area_m2 = 0.25;
  rate.bout_width_m = 2.0;
  rate.rate_kg_ha = 380.0;
  pattern.rate = rate;
  const std::string note(150, 'n');
  for (int i = 0; i < 6; ++i) pattern.notes.push_back("note " + std::to_string(i) + ": a setting to change, " + note);
  const std::string fits = ::testing::TempDir() + "/notes_fit.pdf";
  sp::write_report_pdf(fits, &pattern);
  EXPECT_EQ(page_count(fits), 1u);
  for (int i = 0; i < 30; ++i) pattern.notes.push_back("more " + std::to_string(i) + ": " + note);
  const std::string continued = ::testing::TempDir() + "/notes_continued.pdf";
  sp::write_report_pdf(continued, &pattern);
  EXPECT_EQ(page_count(continued), 2u);
}
