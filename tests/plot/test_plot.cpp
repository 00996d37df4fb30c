// Each PNG writer produces a PNG cairo can read back at the documented size, and an unwritable path
// throws with the path in the message. Set SPREAD_PLOT_KEEP_DIR to keep the images for a look.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <limits>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <cairo.h>
#include <gtest/gtest.h>

#include "libspread/core/unit_uniform.hpp"
#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/analysis/plot/plot.hpp"

namespace sm = spread::metrics;
namespace sp = spread::plot;

namespace {

std::string output_path(const std::string& name) {
  const char* keep = std::getenv("SPREAD_PLOT_KEEP_DIR");
  const std::filesystem::path dir = keep ? std::filesystem::path(keep) : std::filesystem::path(::testing::TempDir());
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

void expect_png(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  ASSERT_TRUE(in) << path;
  unsigned char signature[8] = {};
  in.read(reinterpret_cast<char*>(signature), 8);
  const unsigned char expected[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  for (int i = 0; i < 8; ++i) EXPECT_EQ(signature[i], expected[i]) << path << " byte " << i;
  cairo_surface_t* s = cairo_image_surface_create_from_png(path.c_str());
  ASSERT_EQ(cairo_surface_status(s), CAIRO_STATUS_SUCCESS) << path;
  EXPECT_EQ(cairo_image_surface_get_width(s), sp::kImageWidth_px);
  EXPECT_EQ(cairo_image_surface_get_height(s), sp::kImageHeight_px);
  cairo_surface_destroy(s);
}

// A plausible left-disc throw: landings on a ring sector behind and to the left of the disc.
struct Landings {
  std::vector<double> x, y, m;
};
Landings synthetic_landings() {
  std::mt19937_64 rng(42);
  auto uniform = [&rng] { return spread::unit_uniform(rng()); };
  Landings l;
  for (int i = 0; i < 4000; ++i) {
    const double r = 9.0 + 4.0 * (uniform() + uniform() + uniform() - 1.5);
    const double a = (150.0 + 100.0 * (uniform() + uniform()) / 2.0 + 20.0 * (uniform() - 0.5)) * 3.14159265358979 / 180.0;
    l.x.push_back(r * std::cos(a));
    l.y.push_back(r * std::sin(a));
    l.m.push_back(2e-4);
  }
  return l;
}

void expect_throws_naming(const std::string& path, const std::function<void()>& write) {
  try {
    write();
    FAIL() << "no exception for " << path;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

// Pixels of `path` whose colour is within `tolerance` (0-255 per channel) of (r, g, b), counted inside
// the rectangle [x0, x1) × [y0, y1) (clamped to the image).
int count_pixels_near(const std::string& path, int r, int g, int b, int tolerance, int x0, int y0, int x1, int y1) {
  cairo_surface_t* s = cairo_image_surface_create_from_png(path.c_str());
  EXPECT_EQ(cairo_surface_status(s), CAIRO_STATUS_SUCCESS) << path;
  const int width = cairo_image_surface_get_width(s), height = cairo_image_surface_get_height(s);
  const int stride = cairo_image_surface_get_stride(s);
  const unsigned char* data = cairo_image_surface_get_data(s);
  int count = 0;
  for (int y = std::max(0, y0); y < std::min(height, y1); ++y) {
    const auto* row = reinterpret_cast<const std::uint32_t*>(data + static_cast<std::ptrdiff_t>(y) * stride);
    for (int x = std::max(0, x0); x < std::min(width, x1); ++x) {
      const int pr = static_cast<int>((row[x] >> 16) & 0xff), pg = static_cast<int>((row[x] >> 8) & 0xff),
                pb = static_cast<int>(row[x] & 0xff);
      if (std::abs(pr - r) <= tolerance && std::abs(pg - g) <= tolerance && std::abs(pb - b) <= tolerance) ++count;
    }
  }
  cairo_surface_destroy(s);
  return count;
}

const std::string kBadPath = "/nonexistent-dir-for-spread-tests/sub/plot.png";

}  // namespace

TEST(Plot, GroundPatternPng) {
  const Landings l = synthetic_landings();
  const sm::MachineLayout twin{2, 0.9};
  const sm::GroundPattern g = sm::ground_pattern(l.x, l.y, l.m, twin, 0.25);
  const std::string path = output_path("ground_pattern.png");
  sp::write_ground_pattern_png(g, path, "Ground pattern (synthetic twin disc)", twin);
  expect_png(path);
  expect_throws_naming(kBadPath, [&] { sp::write_ground_pattern_png(g, kBadPath, "x", twin); });
  EXPECT_THROW(sp::write_ground_pattern_png(sm::GroundPattern{}, path, "empty"), std::invalid_argument);
  // Mass fractions instead of kilograms.
  std::vector<double> fractions(l.m.size(), 1.0 / static_cast<double>(l.m.size()));
  const sm::GroundPattern gf = sm::ground_pattern(l.x, l.y, fractions, twin, 0.25);
  const std::string fpath = output_path("ground_pattern_fraction.png");
  sp::write_ground_pattern_png(gf, fpath, "Ground pattern (fractions)", twin, sp::MassUnits::kFraction);
  expect_png(fpath);
}

TEST(Plot, TransversePng) {
  const Landings l = synthetic_landings();
  const sm::MachineLayout twin{2, 0.9};
  const sm::TrayLayout trays = sm::tray_layout_covering(15.0, 0.5);
  std::vector<double> tray(static_cast<std::size_t>(trays.tray_count), 0.0);
  sm::accumulate_transverse(l.x, l.m, twin, trays, tray);
  std::vector<double> measured(tray);
  for (std::size_t k = 0; k < measured.size(); ++k) measured[k] *= 1.0 + 0.1 * std::sin(0.7 * static_cast<double>(k));

  const std::string plain = output_path("transverse.png");
  sp::write_transverse_png(tray, trays, plain, "Transverse distribution");
  expect_png(plain);

  sp::TransverseOptions options;
  options.second_tray_mass_kg = measured;
  options.bout_width_m = sm::effective_working_width(tray, trays, sm::Overlap::kToAndFro, 0.15);
  ASSERT_GT(options.bout_width_m, 0.0);
  const std::string full = output_path("transverse_overlap.png");
  sp::write_transverse_png(tray, trays, full, "Transverse distribution and overlap", options);
  expect_png(full);

  options.units = sp::MassUnits::kFraction;
  std::vector<double> share(tray), measured_share(measured);
  double total = 0.0;
  for (double v : tray) total += v;
  for (double& v : share) v /= total;
  for (double& v : measured_share) v /= total;
  options.second_tray_mass_kg = measured_share;
  const std::string fractions = output_path("transverse_fraction.png");
  sp::write_transverse_png(share, trays, fractions, "Transverse distribution (fractions)", options);
  expect_png(fractions);

  expect_throws_naming(kBadPath, [&] { sp::write_transverse_png(tray, trays, kBadPath, "x"); });
  std::vector<double> wrong(3);
  EXPECT_THROW(sp::write_transverse_png(wrong, trays, plain, "x"), std::invalid_argument);
}

// A tray without a reading: a cross on the axis, and the overlapped line has a gap over it instead of
// dropping towards 0 there (the CV leaves it out, so the line must too).
TEST(Plot, MissingTrayIsAGapInTheOverlappedLine) {
  const sm::TrayLayout trays{0.5, 21};
  std::vector<double> mass(21);
  for (int k = 0; k < 21; ++k) mass[static_cast<std::size_t>(k)] = 1e-3 * (11.0 - std::abs(k - 10.0));
  const std::size_t gone = 11;  // the tray at +0.5 m, inside the 4 m bout
  mass[gone] = 0.0;
  sp::TransverseOptions options;
  options.bout_width_m = 4.0;
  const std::string dropped = output_path("transverse_missing_as_zero.png");
  sp::write_transverse_png(mass, trays, dropped, "missing tray as 0", options);
  options.missing_trays.assign(21, false);
  options.missing_trays[gone] = true;
  const std::string gap = output_path("transverse_missing_gap.png");
  sp::write_transverse_png(mass, trays, gap, "missing tray as a gap", options);
  expect_png(gap);
  // The cross (red) just above the x axis (the axes end at y = 565 px): where the tray is.
  int x_lo = sp::kImageWidth_px, x_hi = -1;
  cairo_surface_t* image = cairo_image_surface_create_from_png(gap.c_str());
  ASSERT_EQ(cairo_surface_status(image), CAIRO_STATUS_SUCCESS);
  const int stride = cairo_image_surface_get_stride(image);
  const unsigned char* data = cairo_image_surface_get_data(image);
  for (int y = 545; y < 565; ++y) {
    const auto* row = reinterpret_cast<const std::uint32_t*>(data + static_cast<std::ptrdiff_t>(y) * stride);
    for (int x = 110; x < 960; ++x) {
      const int r = static_cast<int>((row[x] >> 16) & 0xff), g = static_cast<int>((row[x] >> 8) & 0xff),
                b = static_cast<int>(row[x] & 0xff);
      if (std::abs(r - 204) <= 50 && std::abs(g - 26) <= 50 && std::abs(b - 26) <= 50) {
        x_lo = std::min(x_lo, x);
        x_hi = std::max(x_hi, x);
      }
    }
  }
  cairo_surface_destroy(image);
  ASSERT_GE(x_hi, x_lo) << "no cross drawn for the missing tray";
  EXPECT_LT(x_hi - x_lo, 30) << "one cross, a tray wide at most";
  EXPECT_EQ(count_pixels_near(dropped, 204, 26, 26, 50, 110, 545, 960, 565), 0) << "a cross without a missing tray";
  // The overlapped line's green over the cross's columns, below the legend: there without the flag, none with it.
  const int mid = (x_lo + x_hi) / 2;
  EXPECT_GT(count_pixels_near(dropped, 25, 153, 64, 30, mid - 4, 250, mid + 5, 565), 0);
  EXPECT_EQ(count_pixels_near(gap, 25, 153, 64, 30, mid - 4, 250, mid + 5, 565), 0);
  // A flag per layout tray, or none.
  options.missing_trays.assign(3, false);
  EXPECT_THROW(sp::write_transverse_png(mass, trays, gap, "x", options), std::invalid_argument);
}

TEST(Plot, CvCurvePng) {
  const Landings l = synthetic_landings();
  const sm::TrayLayout trays = sm::tray_layout_covering(15.0, 0.5);
  std::vector<double> tray(static_cast<std::size_t>(trays.tray_count), 0.0);
  sm::accumulate_transverse(l.x, l.m, sm::MachineLayout{2, 0.9}, trays, tray);
  std::vector<double> widths;
  for (int n = 2; n <= trays.tray_count; ++n) widths.push_back(0.5 * n);
  std::vector<double> tf(widths.size()), rt(widths.size());
  sm::cv_curve(tray, trays, widths, sm::Overlap::kToAndFro, tf);
  sm::cv_curve(tray, trays, widths, sm::Overlap::kRacetrack, rt);
  const std::string path = output_path("cv_curve.png");
  sp::write_cv_curve_png(widths, tf, rt, 0.15, path, "CV against bout width");
  expect_png(path);
  // One curve only, and infinite CVs (empty bouts) are drawable.
  std::vector<double> with_inf(tf);
  with_inf.back() = std::numeric_limits<double>::infinity();
  const std::string one = output_path("cv_curve_one.png");
  sp::write_cv_curve_png(widths, with_inf, {}, 0.1, one, "to-and-fro only");
  expect_png(one);
  expect_throws_naming(kBadPath, [&] { sp::write_cv_curve_png(widths, tf, rt, 0.15, kBadPath, "x"); });
  std::vector<double> short_cv(2);
  EXPECT_THROW(sp::write_cv_curve_png(widths, short_cv, rt, 0.15, path, "x"), std::invalid_argument);
}

TEST(Plot, DiscMarkersStayInsideTheAxesWhenThePatternLiesBehind) {
  // Every landing 1-12 m behind the machine: no grid cell at y = 0, where the disc centres are. The
  // markers (red ring, 217/26/26) must still show, inside the plot area (top edge >= 55 px), never in
  // the title band above it.
  Landings l = synthetic_landings();
  for (double& y : l.y) y = -1.0 - std::abs(y) * 0.8;
  const sm::MachineLayout twin{2, 0.9};
  const sm::GroundPattern g = sm::ground_pattern(l.x, l.y, l.m, twin, 0.25);
  ASSERT_LT(g.y0_m + g.ny * g.cell_m, 0.0) << "the grid must not reach y = 0 for this test";
  const std::string path = output_path("ground_pattern_behind.png");
  sp::write_ground_pattern_png(g, path, "Ground pattern behind the machine", twin);
  expect_png(path);
  const int red_in_title_band = count_pixels_near(path, 217, 26, 26, 30, 0, 0, sp::kImageWidth_px, 54);
  const int red_below = count_pixels_near(path, 217, 26, 26, 30, 0, 54, sp::kImageWidth_px, sp::kImageHeight_px);
  EXPECT_EQ(red_in_title_band, 0);
  EXPECT_GT(red_below, 40);  // two rings (and the legend's marker)
}

TEST(Plot, WorkingWidthLabelAtTheRightEdgeIsNotCut) {
  // CV 0 at every width: the working width is the largest W plotted (20 m, on the right frame edge at
  // 960 px). Its value label ("20.0 m", to-and-fro colour 64/115/191) must be drawn inside the axes,
  // left of the frame, in the label rows just above the x axis (bottom edge 565 px).
  std::vector<double> widths, zeros;
  for (int n = 1; n <= 40; ++n) widths.push_back(0.5 * n);
  zeros.assign(widths.size(), 0.0);
  const std::string path = output_path("cv_curve_edge.png");
  sp::write_cv_curve_png(widths, zeros, {}, 0.15, path, "uniform: CV 0 everywhere");
  expect_png(path);
  const int label_pixels = count_pixels_near(path, 64, 115, 191, 40, 890, 530, 958, 560);
  EXPECT_GT(label_pixels, 15);
}

namespace {

// CV(W) that is small up to 8 m, crosses 15 % near 8.5 m and is far off the CV axis (500 %) from 10.5 m
// on: a pattern that lives within about 10 m on a layout 40 m wide.
void narrow_pattern_curve(std::vector<double>& widths, std::vector<double>& cv) {
  for (int n = 1; n <= 80; ++n) {
    const double w = 0.5 * n;
    widths.push_back(w);
    cv.push_back(w <= 8.0 ? 0.05 : w <= 10.0 ? 0.05 + 0.25 * (w - 8.0) / 2.0 : 5.0);
  }
}

}  // namespace

TEST(Plot, CvCurveAxisEndsWhereThePatternLives) {
  // The W axis ends one width after the last point on the CV axis (10.5 m), so the curve's rise from 8 m
  // spans the right half of the plot (x 530-958 px): to-and-fro blue (64/115/191) there. Over the whole
  // layout (40 m) everything right of 10.5 m would be off the top, and the right half blank.
  std::vector<double> widths, cv;
  narrow_pattern_curve(widths, cv);
  const std::string path = output_path("cv_curve_narrow.png");
  sp::write_cv_curve_png(widths, cv, {}, 0.15, path, "narrow pattern");
  expect_png(path);
  EXPECT_GT(count_pixels_near(path, 64, 115, 191, 40, 530, 60, 958, 560), 200);
}

TEST(Plot, CvCurveLegendShowsTheWorkingWidthDot) {
  // The working width is marked by a dot on the curve; the legend's entry is the line with the same dot:
  // blue pixels above the legend swatch's line (the line is 2.5 px at y 80, the dot 5 px in radius). The
  // legend sits top left (its swatch from x 116 px).
  std::vector<double> widths, cv;
  narrow_pattern_curve(widths, cv);
  const std::string path = output_path("cv_curve_legend_dot.png");
  sp::write_cv_curve_png(widths, cv, {}, 0.15, path, "legend with the marker");
  EXPECT_GT(count_pixels_near(path, 64, 115, 191, 60, 124, 74, 137, 78), 4);
  // No width meets a 1 % target: no dot on the curve, none in the legend.
  const std::string none = output_path("cv_curve_legend_no_dot.png");
  sp::write_cv_curve_png(widths, cv, {}, 0.01, none, "no working width");
  EXPECT_EQ(count_pixels_near(none, 64, 115, 191, 60, 124, 74, 137, 78), 0);
}

TEST(Plot, CvCurveWithASecondCurveInOneFigure) {
  // Calibrated and measured in one figure: the second (grey, 77/77/77) curve is drawn and in the legend.
  std::vector<double> widths, cv;
  narrow_pattern_curve(widths, cv);
  std::vector<double> measured(cv);
  for (double& v : measured) v = std::min(v * 1.3, 5.0);
  sp::CvCurveOptions options;
  options.series_label = "calibrated";
  options.second_to_and_fro = measured;
  const std::string path = output_path("cv_curve_two.png");
  sp::write_cv_curve_png(widths, cv, {}, 0.15, path, "calibrated and measured", options);
  const int grey = count_pixels_near(path, 77, 77, 77, 20, 100, 60, 960, 565);
  const std::string alone = output_path("cv_curve_alone.png");
  sp::write_cv_curve_png(widths, cv, {}, 0.15, alone, "calibrated and measured");
  EXPECT_GT(grey, count_pixels_near(alone, 77, 77, 77, 20, 100, 60, 960, 565) + 300);
  std::vector<double> short_cv(3);
  options.second_to_and_fro = short_cv;
  EXPECT_THROW(sp::write_cv_curve_png(widths, cv, {}, 0.15, path, "x", options), std::invalid_argument);
}
