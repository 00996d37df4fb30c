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

std::string tray_command(const std::string& extra) {
  return kEpoch + "'" + kSpread + "' calibrate tray '" + kExample +
         "' --width 3.5 --machine 'Twin disc, narrow inlet' --material Urea --rpm 600 --speed 12 --tray-area 0.25 "
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
  const std::regex row(R"(^\s*(\d+\.\d) m\s+(\d+\.\d) %\s+(\d+\.\d) %\s*$)");
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

TEST_F(ReportCli, TrayReportIsOnePageWithItsChartDrawn) {
  const fs::path pdf = work_dir() / "tray.pdf";
  fs::remove(pdf);
  const CommandRun r = run(tray_command("--report '" + pdf.string() + "'"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("wrote " + pdf.string()), std::string::npos) << r.out;
  ASSERT_EQ(render(pdf, work_dir() / "tray"), 1);
  // The chart sits between about 20 % and 55 % of the page's height: bars (blue) and lines (dark) there.
  // A page without the chart has no blue and only a few axis labels.
  const Ink chart = ink(work_dir() / "tray-1.png", 0.20, 0.55);
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

  // Every row of the CV table equals the JSON's cv_curve at that width (to 0.1 %, as printed).
  EXPECT_EQ(expect_cv_rows_as_json(text, j), 5) << text;
  // The example's 12.5 m throw: widths fitting it, 2 to 10 m; the numbers docs/field-calibration.md quotes.
  EXPECT_TRUE(std::regex_search(text, std::regex(R"(2\.0 m\s+8\.1 %\s+7\.5 %)"))) << text;
  EXPECT_TRUE(std::regex_search(text, std::regex(R"(6\.0 m\s+23\.1 %\s+23\.0 %)"))) << text;
  EXPECT_TRUE(std::regex_search(text, std::regex(R"(10\.0 m\s+138\.8 %\s+138\.8 %)"))) << text;
  EXPECT_NE(text.find("871.4 kg/ha"), std::string::npos) << text;
  EXPECT_NE(text.find("EN 13739-2 rate check: PASS — the trays caught 102.5 %"), std::string::npos) << text;

  // The rate and its check, as the JSON has them.
  const json& rate = j["rate"];
  ASSERT_TRUE(rate.is_object()) << j.dump(2);
  EXPECT_NE(text.find(one_decimal(rate["rate_kg_ha"].get<double>()) + " kg/ha"), std::string::npos) << text;
  const std::string verdict = rate["rate_check"]["pass"].get<bool>() ? "PASS" : "FAIL";
  EXPECT_NE(text.find("EN 13739-2 rate check: " + verdict), std::string::npos) << text;
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
  EXPECT_GT(ink(work_dir() / "predict-1.png", 0.20, 0.55).blue, 0.01) << "the tray bars are not drawn";
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
                           "' --fit friction,drag --samples 128 --tray-area 0.25 --rate-kg-ha 1200 --report '" +
                           pdf.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  ASSERT_EQ(render(pdf, work_dir() / "pattern"), 1);
  const std::string text = pdf_text(pdf);
  EXPECT_NE(text.find("predicted, calibrated"), std::string::npos) << text;
  EXPECT_NE(text.find("EN 13739-2 rate check: PASS"), std::string::npos) << text;
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
  for (const char* line : {"3.0 m    682 rpm, +70.0 deg   0.4 % ± 13.9      0.4 % ± 13.9      501-527 rpm, 629-750 rpm",
                           "4.0 m    734 rpm, +5.0 deg    2.1 % ± 13.8      2.1 % ± 13.8      501-521 rpm, 679-750 rpm",
                           "12.0 m   not reachable"}) {
    EXPECT_NE(made.out.find(line), std::string::npos) << line << "\n" << made.out;
  }
}
