// `--report OUT.pdf` end to end: the PDF the CLI writes is rendered with poppler's pdftoppm and read
// with pdftotext (Debian poppler-utils, installed by tools/setup.sh), and checked for what a technician
// looks at — one page, a chart that is drawn, the material, and CVs equal to those of --json.
#include <cairo.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const std::string kSpread = SPREAD_CLI;
const std::string kLookupBuilder = SPREAD_LOOKUP_BUILDER;
const std::string kExample = std::string(SPREAD_SOURCE_DIR) + "/scenes/field/tray_test_3passes.csv";
// 2025-11-24 16:00 UTC: every report in these tests carries this date.
const std::string kEpoch = "SOURCE_DATE_EPOCH=1764000000 ";

fs::path work_dir() {
  const fs::path dir = fs::path(SPREAD_TEST_WORK_DIR);
  fs::create_directories(dir);
  return dir;
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

struct CommandRun {
  int exit_code = -1;
  std::string out, err;
};

// Runs a shell command line, capturing stdout and stderr.
CommandRun run(const std::string& command) {
  // ctest runs each test in its own process, two at a time: the process id keeps their files apart.
  static int counter = 0;
  const std::string name = "run" + std::to_string(getpid()) + "_" + std::to_string(++counter);
  const fs::path out = work_dir() / (name + ".out");
  const fs::path err = work_dir() / (name + ".err");
  const int status = std::system((command + " > '" + out.string() + "' 2> '" + err.string() + "'").c_str());
  CommandRun r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

bool have_poppler() { return std::system("command -v pdftoppm > /dev/null && command -v pdftotext > /dev/null") == 0; }

std::string tray_command(const std::string& extra, const std::string& width = "3.5") {
  return kEpoch + "'" + kSpread + "' calibrate tray '" + kExample + "' --width " + width +
         " --machine 'Twin disc, narrow inlet' --material Urea --rpm 600 --speed 12 --tray-area 0.25 "
         "--rate-kg-ha 850 " + extra;
}

// Fractions of a rendered page's pixels in a region (fractions of the page) that are dark, and that are
// the bars' blue.
struct Ink {
  double dark = 0.0, blue = 0.0;
};
Ink ink(const fs::path& png, double top, double bottom) {
  cairo_surface_t* image = cairo_image_surface_create_from_png(png.c_str());
  EXPECT_EQ(cairo_surface_status(image), CAIRO_STATUS_SUCCESS) << png;
  const int width = cairo_image_surface_get_width(image), height = cairo_image_surface_get_height(image);
  const int stride = cairo_image_surface_get_stride(image);
  const unsigned char* data = cairo_image_surface_get_data(image);
  Ink out;
  double pixels = 0, dark = 0, blue = 0;
  for (int y = static_cast<int>(top * height); y < static_cast<int>(bottom * height); ++y) {
    for (int x = static_cast<int>(0.07 * width); x < static_cast<int>(0.93 * width); ++x) {
      const auto* p = reinterpret_cast<const std::uint32_t*>(data + y * stride) + x;
      const int r = (*p >> 16) & 0xff, g = (*p >> 8) & 0xff, b = *p & 0xff;
      pixels += 1.0;
      dark += (r + g + b) / 3 < 128 ? 1.0 : 0.0;
      blue += b > 150 && r < 120 && g < 160 ? 1.0 : 0.0;
    }
  }
  cairo_surface_destroy(image);
  if (pixels > 0) {
    out.dark = dark / pixels;
    out.blue = blue / pixels;
  }
  return out;
}

// Renders `pdf` at 50 dpi; returns the number of pages rendered (PREFIX-N.png files).
int render(const fs::path& pdf, const fs::path& prefix) {
  for (int page = 1; page <= 9; ++page) fs::remove(prefix.string() + "-" + std::to_string(page) + ".png");
  const CommandRun r = run("pdftoppm -png -r 50 '" + pdf.string() + "' '" + prefix.string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  int pages = 0;
  while (fs::exists(prefix.string() + "-" + std::to_string(pages + 1) + ".png")) ++pages;
  return pages;
}

std::string pdf_text(const fs::path& pdf) {
  const CommandRun r = run("pdftotext -layout '" + pdf.string() + "' -");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return r.out;
}

std::string one_decimal(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", value);
  return text;
}

// Rows "W m  a %  b %" of a report's CV table, each checked against the JSON's cv_curve; returns how many.
int expect_cv_rows_as_json(const std::string& text, const json& j) {
  const std::regex row(R"(^\s*(\d+\.\d) m(?: \(driven\))?\s+(\d+\.\d) %\s+(\d+\.\d) %\s*$)");
  int rows = 0;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (!std::regex_match(line, m, row)) continue;
    const double width_m = std::stod(m[1]);
    bool found = false;
    for (const json& point : j["cv_curve"]) {
      if (std::abs(point["bout_width_m"].get<double>() - width_m) > 1e-9) continue;
      found = true;
      EXPECT_EQ(m[2].str(), one_decimal(point["cv_to_and_fro_percent"].get<double>())) << line;
      EXPECT_EQ(m[3].str(), one_decimal(point["cv_racetrack_percent"].get<double>())) << line;
    }
    EXPECT_TRUE(found) << "no cv_curve point at " << width_m << " m";
    ++rows;
  }
  return rows;
}

// A small analytic table (Urea, the narrow Case 1 inlet, 256 samples per run, 450-750 rpm), made once per
// `name` (one per test: tests run in parallel processes).
fs::path small_table(const std::string& name) {
  const fs::path table = work_dir() / (name + ".sqlite");
  static std::set<std::string> made;
  if (made.insert(name).second) {
    fs::remove(table);
    const CommandRun r = run("'" + kLookupBuilder + "' '" + SPREAD_SOURCE_DIR + "/scenes/default.toml' --output '" +
                             table.string() + "' --set sweep.source=analytic --set 'sweep.materials=[\"Urea\"]' " +
                             "--set sweep.samples_per_run=256 --set inlet.radius_m=0.0145 --set inlet.offset_m=0.1 " +
                             "--set inlet.angle_rad=1.0");
    EXPECT_EQ(r.exit_code, 0) << r.err;
  }
  return table;
}

class ReportCli : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(have_poppler()) << "pdftoppm/pdftotext not found: install poppler-utils (tools/setup.sh does)";
  }
};

}  // namespace

namespace {

// The page's text lines (pdftotext -layout), blank lines dropped.
std::vector<std::string> text_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.find_first_not_of(" \t\f") != std::string::npos) lines.push_back(line);
  }
  return lines;
}

// Index of the first line holding `needle`; -1 when none does.
int line_of(const std::vector<std::string>& lines, const std::string& needle) {
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].find(needle) != std::string::npos) return static_cast<int>(i);
  }
  return -1;
}

// Fraction of the pixels in the band [top, bottom] (fractions of the page height) near a colour.
double colour_share(const fs::path& png, double top, double bottom, int r0, int g0, int b0) {
  cairo_surface_t* image = cairo_image_surface_create_from_png(png.c_str());
  const int width = cairo_image_surface_get_width(image), height = cairo_image_surface_get_height(image);
  const int stride = cairo_image_surface_get_stride(image);
  const unsigned char* data = cairo_image_surface_get_data(image);
  double pixels = 0, near = 0;
  for (int y = static_cast<int>(top * height); y < static_cast<int>(bottom * height); ++y) {
    for (int x = 0; x < width; ++x) {
      const auto* p = reinterpret_cast<const std::uint32_t*>(data + y * stride) + x;
      const int r = (*p >> 16) & 0xff, g = (*p >> 8) & 0xff, b = *p & 0xff;
      pixels += 1.0;
      near += std::abs(r - r0) + std::abs(g - g0) + std::abs(b - b0) < 90 ? 1.0 : 0.0;
    }
  }
  cairo_surface_destroy(image);
  return pixels > 0 ? near / pixels : 0.0;
}

// The verdict colours of report_pdf.cpp at 8 bits.
constexpr int kRed[3] = {191, 0, 0}, kGreen[3] = {0, 115, 0}, kAmber[3] = {204, 115, 0};

}  // namespace

TEST_F(ReportCli, TrayReportIsOnePageWithItsChartDrawn) {
  const fs::path pdf = work_dir() / "tray.pdf";
  fs::remove(pdf);
  const CommandRun r = run(tray_command("--report '" + pdf.string() + "'"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("wrote " + pdf.string()), std::string::npos) << r.out;
  ASSERT_EQ(render(pdf, work_dir() / "tray"), 1);
  // The chart sits between about 27 % and 62 % of the page's height (under the verdicts): bars (blue) and
  // lines (dark) there. A page without the chart has no blue and only a few axis labels.
  const Ink chart = ink(work_dir() / "tray-1.png", 0.27, 0.62);
  EXPECT_GT(chart.blue, 0.01) << "the tray bars are not drawn";
  EXPECT_GT(chart.dark, 0.02) << "the chart's frame, profile and labels are not drawn";
}

TEST_F(ReportCli, TrayReportTextMatchesTheJson) {
  const fs::path pdf = work_dir() / "tray_text.pdf";
  const CommandRun made = run(tray_command("--report '" + pdf.string() + "'"));
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const CommandRun as_json = run(tray_command("--json"));
  ASSERT_EQ(as_json.exit_code, 0) << as_json.err;
  const json j = json::parse(as_json.out);
  const std::string text = pdf_text(pdf);
  EXPECT_NE(text.find("Material: Urea"), std::string::npos) << text;
  EXPECT_NE(text.find("Machine: Twin disc, narrow inlet"), std::string::npos) << text;
  EXPECT_NE(text.find("Disc speed: 600 rpm"), std::string::npos) << text;
  EXPECT_NE(text.find("Forward speed: 12.0 km/h"), std::string::npos) << text;
  EXPECT_NE(text.find("date 2025-11-24"), std::string::npos) << text;
  // With --tray-area the chart's bars are a rate, as the technician sets it.
  EXPECT_NE(text.find("tray mass / tray area (kg/ha)"), std::string::npos) << text;

  // Every row of the CV table equals the JSON's cv_curve at that width (to 0.1 %, as printed): the five
  // widths fitting the pattern and the 3.5 m bout driven, marked.
  EXPECT_EQ(expect_cv_rows_as_json(text, j), 6) << text;
  EXPECT_TRUE(std::regex_search(text, std::regex(R"(3\.5 m \(driven\)\s+15\.1 %\s+14\.8 %)"))) << text;
  // The example's 12.5 m throw: widths fitting it, 2 to 10 m; the numbers docs/field-calibration.md quotes.
  EXPECT_TRUE(std::regex_search(text, std::regex(R"(2\.0 m\s+8\.1 %\s+7\.5 %)"))) << text;
  EXPECT_TRUE(std::regex_search(text, std::regex(R"(6\.0 m\s+23\.1 %\s+23\.0 %)"))) << text;
  EXPECT_TRUE(std::regex_search(text, std::regex(R"(10\.0 m\s+138\.8 %\s+138\.8 %)"))) << text;
  EXPECT_NE(text.find("871.4 kg/ha"), std::string::npos) << text;
  EXPECT_TRUE(std::regex_search(text, std::regex(R"(PASS\s+Rate \(EN 13739-2\): the trays caught 871\.4 kg/ha, 102\.5 %)")))
      << text;

  // The rate and its check, as the JSON has them.
  const json& rate = j["rate"];
  ASSERT_TRUE(rate.is_object()) << j.dump(2);
  EXPECT_NE(text.find(one_decimal(rate["rate_kg_ha"].get<double>()) + " kg/ha"), std::string::npos) << text;
  const std::string verdict = rate["rate_check"]["pass"].get<bool>() ? "PASS" : "FAIL";
  EXPECT_TRUE(std::regex_search(text, std::regex(verdict + R"(\s+Rate \(EN 13739-2\))"))) << text;
  EXPECT_NE(text.find(one_decimal(rate["rate_check"]["caught_percent"].get<double>()) + " %"), std::string::npos);
}

TEST_F(ReportCli, MissingFolderStillPrintsTheReportAndExitsTwo) {
  const fs::path pdf = work_dir() / "no-such-folder" / "tray.pdf";
  const CommandRun r = run(tray_command("--report '" + pdf.string() + "'"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find("at W = 3.50 m: CV 15.1 % to-and-fro"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("--report " + pdf.string() + ": the folder '" + pdf.parent_path().string() + "' does not exist"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(pdf));
}

TEST_F(ReportCli, SourceDateEpochMakesTheSameFile) {
  const fs::path a = work_dir() / "same_a.pdf", b = work_dir() / "same_b.pdf";
  ASSERT_EQ(run(tray_command("--report '" + a.string() + "'")).exit_code, 0);
  ASSERT_EQ(run(tray_command("--report '" + b.string() + "'")).exit_code, 0);
  // The footer names the command line, which differs in the file name only: compare without it.
  std::string first = pdf_text(a), second = pdf_text(b);
  EXPECT_EQ(first.substr(0, first.find("made by")), second.substr(0, second.find("made by")));
  const CommandRun bad = run("SOURCE_DATE_EPOCH=yesterday '" + kSpread + "' calibrate tray '" + kExample +
                      "' --report '" + a.string() + "'");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("SOURCE_DATE_EPOCH 'yesterday'"), std::string::npos) << bad.err;
}

TEST_F(ReportCli, PredictReportMatchesTheJson) {
  const fs::path pdf = work_dir() / "predict.pdf";
  const std::string predict = kEpoch + "'" + kSpread + "' predict --tables '" + small_table("urea_predict").string() +
                              "' --material Urea --rpm 600 --speed 12 ";
  const CommandRun made = run(predict + "--report '" + pdf.string() + "'");
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const CommandRun as_json = run(predict + "--json");
  ASSERT_EQ(as_json.exit_code, 0) << as_json.err;
  const json j = json::parse(as_json.out);
  ASSERT_EQ(render(pdf, work_dir() / "predict"), 1);
  EXPECT_GT(ink(work_dir() / "predict-1.png", 0.27, 0.62).blue, 0.01) << "the tray bars are not drawn";
  const std::string text = pdf_text(pdf);
  EXPECT_NE(text.find("Material: Urea"), std::string::npos) << text;
  EXPECT_NE(text.find("Forward speed: 12.0 km/h"), std::string::npos) << text;
  EXPECT_GE(expect_cv_rows_as_json(text, j), 3) << text;
  // The CV at the bout width with its 95 % interval, as the text report prints it.
  char cv[64];
  std::snprintf(cv, sizeof cv, "CV %.1f %% ± %.2f to-and-fro", j["cv_to_and_fro_percent"].get<double>(),
                1.96 * j["cv_to_and_fro_se_percent"].get<double>());
  EXPECT_NE(text.find(cv), std::string::npos) << cv << "\n" << text;
}

TEST_F(ReportCli, PatternReportShowsMeasuredAndPredicted) {
  const fs::path pdf = work_dir() / "pattern.pdf", output = work_dir() / "calibrated.sqlite";
  fs::remove(output);
  const CommandRun r = run(kEpoch + "'" + kSpread + "' calibrate pattern --tables '" + small_table("urea_pattern").string() +
                           "' --material Urea --rpm 600 --trays '" + kExample + "' --output '" + output.string() +
                           "' --fit friction,drag --samples 128 --width 3.5 --tray-area 0.25 --rate-kg-ha 850 --report '" +
                           pdf.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  ASSERT_EQ(render(pdf, work_dir() / "pattern"), 1);
  const std::string text = pdf_text(pdf);
  EXPECT_NE(text.find("predicted, calibrated"), std::string::npos) << text;
  // Each fitted value with its ± as the text report prints it; the values the fit kept marked fixed.
  std::smatch friction;
  ASSERT_TRUE(std::regex_search(r.out, friction, std::regex(R"(friction on vanes\s+(\d\.\d{4}) ± (\d\.\d{4}))"))) << r.out;
  EXPECT_NE(text.find("friction on vanes " + friction[1].str() + " ± " + friction[2].str()), std::string::npos) << text;
  EXPECT_NE(text.find("fixed at the table's values: launch-angle offset 0.00 deg"), std::string::npos) << text;
  EXPECT_NE(text.find("CV at the 3.50 m bout, to-and-fro"), std::string::npos) << text;
  EXPECT_TRUE(std::regex_search(text, std::regex(R"(PASS\s+Rate \(EN 13739-2\))"))) << text;
}

TEST_F(ReportCli, ChartPicksTheLowestCvAndPrintsItsPage) {
  const fs::path table = small_table("urea_chart"), pdf = work_dir() / "chart.pdf";
  const std::string chart = kEpoch + "'" + kSpread + "' chart --tables '" + table.string() +
                            "' --material Urea --widths 3,4,12 ";
  const CommandRun as_json = run(chart + "--json");
  ASSERT_EQ(as_json.exit_code, 0) << as_json.err;
  const json j = json::parse(as_json.out);
  ASSERT_EQ(j["rows"].size(), 3u);
  for (int k = 0; k < 2; ++k) {
    const json& row = j["rows"][k];
    ASSERT_TRUE(row["reachable"].get<bool>()) << row.dump();
    const double rpm = row["rpm"].get<double>();
    EXPECT_GE(rpm, 450.0);
    EXPECT_LE(rpm, 750.0);
    EXPECT_GT(row["cv_to_and_fro_se_percent"].get<double>(), 0.0);
    // `spread predict` (the C API) at that setting and width gives that CV.
    char setting_text[96];
    std::snprintf(setting_text, sizeof setting_text, "--rpm %.9f --drop-point-turn %.12f", rpm,
                  row["drop_point_turn_deg"].get<double>());
    const CommandRun predicted = run("'" + kSpread + "' predict --tables '" + table.string() +
                                     "' --material Urea --json " + setting_text + " --width " +
                                     std::to_string(row["width_m"].get<double>()));
    ASSERT_EQ(predicted.exit_code, 0) << predicted.err;
    EXPECT_NEAR(json::parse(predicted.out)["cv_to_and_fro_percent"].get<double>(),
                row["cv_to_and_fro_percent"].get<double>(), 1e-6)
        << row.dump();
  }
  // The numbers docs/field-calibration.md quotes for this table.
  EXPECT_NEAR(j["rows"][0]["rpm"].get<double>(), 682.0, 1.0);
  EXPECT_NEAR(j["rows"][0]["drop_point_turn_deg"].get<double>(), 70.0, 0.1);
  EXPECT_NEAR(j["rows"][1]["rpm"].get<double>(), 734.0, 1.0);
  EXPECT_NEAR(j["rows"][1]["drop_point_turn_deg"].get<double>(), 5.0, 0.1);
  EXPECT_FALSE(j["rows"][2]["reachable"].get<bool>());
  EXPECT_EQ(j["rows"][2]["reach"], "not_reached");

  const CommandRun made = run(chart + "--report '" + pdf.string() + "'");
  ASSERT_EQ(made.exit_code, 0) << made.err;
  ASSERT_EQ(render(pdf, work_dir() / "chart"), 1);
  const std::string text = pdf_text(pdf);
  EXPECT_NE(text.find("Spread chart"), std::string::npos) << text;
  char rpm_cell[32];
  std::snprintf(rpm_cell, sizeof rpm_cell, "%.0f rpm", j["rows"][0]["rpm"].get<double>());
  EXPECT_NE(text.find(rpm_cell), std::string::npos) << rpm_cell << "\n" << text;
  EXPECT_NE(text.find("not reachable"), std::string::npos) << text;
  // Columns as wide as their cells: no cell runs into the next (the spans were cut over two lines and
  // the last two headers ran together when every column had a fifth of the page).
  EXPECT_TRUE(std::regex_search(text, std::regex(R"(CV racetrack\s+CV within target at)"))) << text;
  // The widths by their verdict, first under the header: 3 m reached at 95 %, 4 m marginal, 12 m not.
  const std::vector<std::string> lines = text_lines(text);
  const int pass = line_of(lines, "3.0 m: the best setting keeps the CV within 15 %");
  const int marginal = line_of(lines, "4.0 m: the best setting's 95 % interval reaches over 15 %");
  const int fail = line_of(lines, "12.0 m: no setting searched keeps the CV within 15 %");
  ASSERT_GE(pass, 0) << text;
  EXPECT_NE(lines[pass].find("PASS"), std::string::npos) << lines[pass];
  EXPECT_NE(lines[marginal].find("MARGINAL"), std::string::npos) << text;
  EXPECT_NE(lines[fail].find("FAIL"), std::string::npos) << text;
  EXPECT_LT(fail, line_of(lines, "Disc speed per working width")) << text;
  EXPECT_TRUE(std::regex_search(text, std::regex(R"(0\.4 % ± 13\.9\s+501-527 rpm, 629-750 rpm)"))) << text;
  for (const char* line : {"3.0 m    682 rpm, +70.0 deg   0.4 % ± 13.9      0.4 % ± 13.9      501-527 rpm, 629-750 rpm",
                           "4.0 m    735 rpm, +5.0 deg    2.1 % ± 13.5      2.1 % ± 13.5      500-521 rpm, 679-750 rpm",
                           "12.0 m   not reachable"}) {
    EXPECT_NE(made.out.find(line), std::string::npos) << line << "\n" << made.out;
  }
}


// The example at 6 m is a 23.1 % CV (the table above): the page's first lines after the header say FAIL
// for the CV, in red, with the rate's own verdict beside it — before the summary, chart and table.
TEST_F(ReportCli, TrayReportStatesTheCvVerdictFirst) {
  // At 6 m a pass's 152.5 g on 0.25 m² trays is 508.3 kg/ha: set 500 kg/ha, so the rate passes.
  const std::string command = kEpoch + "'" + kSpread + "' calibrate tray '" + kExample +
                              "' --width 6 --material Urea --rpm 600 --tray-area 0.25 --rate-kg-ha 500 ";
  const fs::path pdf = work_dir() / "verdict_fail.pdf";
  const CommandRun made = run(command + "--report '" + pdf.string() + "'");
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const CommandRun as_json = run(command + "--json");
  ASSERT_EQ(as_json.exit_code, 0) << as_json.err;
  const json j = json::parse(as_json.out);
  EXPECT_EQ(j["cv_verdict"]["verdict"], "fail") << j["cv_verdict"].dump();
  EXPECT_TRUE(j["rate"]["rate_check"]["pass"].get<bool>()) << j["rate"].dump();
  const std::string text = pdf_text(pdf);
  const std::vector<std::string> lines = text_lines(text);
  const int cv_line = line_of(lines, "CV at the 6.00 m bout, to-and-fro");
  const int rate_line = line_of(lines, "Rate (EN 13739-2)");
  ASSERT_GE(cv_line, 0) << text;
  ASSERT_GT(rate_line, cv_line) << text;
  // First after the header (title, date, the two lines of fields, the data file): nothing else before.
  EXPECT_LE(cv_line, 5) << text;
  EXPECT_LT(rate_line, line_of(lines, "trays of 0.50 m"));
  EXPECT_LT(rate_line, line_of(lines, "CV per working width"));
  std::string cv_verdict;  // the CV's verdict, over the lines it wraps to
  for (int i = cv_line; i < rate_line; ++i) cv_verdict += lines[static_cast<std::size_t>(i)] + " ";
  EXPECT_NE(lines[cv_line].find("FAIL"), std::string::npos) << lines[cv_line];
  EXPECT_NE(cv_verdict.find("23.1 %"), std::string::npos) << cv_verdict;
  EXPECT_NE(cv_verdict.find("above the target 15 %"), std::string::npos) << cv_verdict;
  EXPECT_NE(lines[rate_line].find("PASS"), std::string::npos) << lines[rate_line];
  // In colour: the verdict words sit in the top fifth of the page, FAIL red and PASS green.
  ASSERT_EQ(render(pdf, work_dir() / "verdict_fail"), 1);
  const fs::path png = work_dir() / "verdict_fail-1.png";
  EXPECT_GT(colour_share(png, 0.0, 0.2, kRed[0], kRed[1], kRed[2]), 1e-4);
  EXPECT_GT(colour_share(png, 0.0, 0.2, kGreen[0], kGreen[1], kGreen[2]), 1e-4);
  EXPECT_EQ(colour_share(png, 0.0, 0.2, kAmber[0], kAmber[1], kAmber[2]), 0.0);
}

// The rule at the example's 3.5 m bout (15.1 %, the target 15 %): the repeatability interval of its three
// passes decides between MARGINAL (it straddles 15 %) and FAIL (it lies above); never PASS, and the
// page and the JSON agree.
TEST_F(ReportCli, TrayReportAtTheTargetIsMarginalOrFailByTheInterval) {
  const fs::path pdf = work_dir() / "verdict_15.pdf";
  ASSERT_EQ(run(tray_command("--report '" + pdf.string() + "'")).exit_code, 0);
  const CommandRun as_json = run(tray_command("--json"));
  ASSERT_EQ(as_json.exit_code, 0) << as_json.err;
  const json verdict = json::parse(as_json.out)["cv_verdict"];
  ASSERT_TRUE(verdict["interval_percent"].is_array()) << verdict.dump();
  const double low = verdict["interval_percent"][0].get<double>(), high = verdict["interval_percent"][1].get<double>();
  EXPECT_LT(low, 15.1);
  EXPECT_GT(high, 15.1);
  const std::string expected = low > 15.0 ? "fail" : "marginal";
  EXPECT_EQ(verdict["verdict"], expected) << verdict.dump();
  const std::vector<std::string> lines = text_lines(pdf_text(pdf));
  const int cv_line = line_of(lines, "CV at the 3.50 m bout, to-and-fro");
  ASSERT_GE(cv_line, 0);
  EXPECT_LE(cv_line, 5);
  EXPECT_NE(lines[cv_line].find(expected == "fail" ? "FAIL" : "MARGINAL"), std::string::npos) << lines[cv_line];
  EXPECT_EQ(lines[cv_line].find("PASS"), std::string::npos) << lines[cv_line];
}

// A long material name wraps inside its half of the header instead of running off the page.
TEST_F(ReportCli, LongNamesWrap) {
  const fs::path pdf = work_dir() / "long_name.pdf";
  const std::string name = "KAS 27 % N granulated, batch 2025-11 from the northern silo, delivered 2025-11-20 in big bags";
  const CommandRun made = run(kEpoch + "'" + kSpread + "' calibrate tray '" + kExample + "' --width 3.5 --material '" +
                              name + "' --machine 'Twin disc spreader with a long model name, serial 12345' --report '" +
                              pdf.string() + "'");
  ASSERT_EQ(made.exit_code, 0) << made.err;
  // Above the footer, which quotes the command line (and with it the names) in full.
  const std::string text = pdf_text(pdf);
  const std::string page = text.substr(0, text.find("made by"));
  for (const char* tail : {"big bags", "serial 12345"}) EXPECT_NE(page.find(tail), std::string::npos) << tail << "\n" << text;
}

// The quick check's page opens with its verdict (five trays at 10.2 %: the interval 6.1-30.4 % holds the
// target, MARGINAL) and says nothing a farmer cannot act on: no file paths of the docs, no step numbers.
TEST_F(ReportCli, QuickCheckPageStatesItsVerdictInPlainWords) {
  const fs::path pdf = work_dir() / "quick.pdf";
  const CommandRun made = run(kEpoch + "'" + kSpread + "' calibrate tray '" + SPREAD_SOURCE_DIR +
                              "/scenes/field/quick_check_5trays.csv' --quick-check --tray-area 0.25 --rate-kg-ha 400 "
                              "--report '" + pdf.string() + "'");
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const std::string text = pdf_text(pdf);
  const std::vector<std::string> lines = text_lines(text);
  const int cv_line = line_of(lines, "CV of the bout from 5 trays");
  ASSERT_GE(cv_line, 0) << text;
  EXPECT_LE(cv_line, 5) << text;
  EXPECT_NE(lines[cv_line].find("MARGINAL"), std::string::npos) << lines[cv_line];
  EXPECT_NE(lines[cv_line].find("6.1-30.4 %"), std::string::npos) << lines[cv_line];
  const int rate_line = line_of(lines, "Rate (EN 13739-2)");
  ASSERT_GT(rate_line, cv_line) << text;
  EXPECT_NE(lines[rate_line].find("PASS"), std::string::npos) << lines[rate_line];
  EXPECT_LT(rate_line, line_of(lines, "trays read"));
  EXPECT_EQ(text.find("docs/"), std::string::npos) << text;
  EXPECT_EQ(text.find(".md"), std::string::npos) << text;
  EXPECT_EQ(text.find("step 2"), std::string::npos) << text;
}
