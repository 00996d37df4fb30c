// `--report OUT.pdf` end to end: the PDF the CLI writes is rendered with poppler's pdftoppm and read
// with pdftotext (Debian poppler-utils, installed by tools/setup.sh), and checked for what a technician
// looks at — one page, a chart that is drawn, the material, and CVs equal to those of --json.
#include <cairo.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const std::string kSpread = SPREAD_CLI;
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
  static int counter = 0;
  const fs::path out = work_dir() / ("run" + std::to_string(++counter) + ".out");
  const fs::path err = work_dir() / ("run" + std::to_string(counter) + ".err");
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

  // Every row of the CV table equals the JSON's cv_curve at that width (to 0.1 %, as printed).
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
  EXPECT_EQ(rows, 5) << text;
  // The example's 12.5 m throw: widths fitting it, 2 to 10 m.
  EXPECT_NE(text.find("10.0 m"), std::string::npos);

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
