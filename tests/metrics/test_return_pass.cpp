// To-and-fro with a return pass of its own (metrics.hpp "To-and-fro with a return pass of its own"): in
// wind the way back meets the wind from the other side, so the odd passes are not the outgoing pattern
// mirrored. Checked against a brute-force field laid out pass by pass, against the one-pattern functions
// where the two must agree, and the FFT search against the whole-tray scan.
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "libspread/analysis/metrics/metrics.hpp"
#include "tests/metrics/test_patterns.hpp"
#include "libspread/core/unit_uniform.hpp"

namespace sm = spread::metrics;

namespace {

using spread::metrics::testing::layout;
using spread::metrics::testing::random_pattern;

std::vector<double> mirrored(const std::vector<double>& p) { return {p.rbegin(), p.rend()}; }

// Independent reference: the field laid out pass by pass on the tray grid (pass k at k·n trays, the
// outgoing pattern on even k, the return pattern mirrored on odd k), one whole period of 2n trays from
// an arbitrary start, CV with the variance pooled over the two bouts: SS_2n / (2(n − 1)).
double field_cv(const std::vector<double>& out, const std::vector<double>& back, int n, int start = 5) {
  const int t = static_cast<int>(out.size());
  std::vector<double> period(static_cast<std::size_t>(2 * n), 0.0);
  const int reach = (t + 2 * n + start) / n + 3;
  for (int k = -reach; k <= reach; ++k) {
    const bool odd = k % 2 != 0;
    for (int i = 0; i < t; ++i) {
      const int g = i + k * n - start;
      if (g < 0 || g >= 2 * n) continue;
      period[static_cast<std::size_t>(g)] += odd ? back[static_cast<std::size_t>(t - 1 - i)] : out[static_cast<std::size_t>(i)];
    }
  }
  double mean = 0.0;
  for (double b : period) mean += b;
  mean /= 2 * n;
  if (n == 1) return 0.0;
  double ss = 0.0;
  for (double b : period) ss += (b - mean) * (b - mean);
  return std::sqrt(ss / (2.0 * (n - 1))) / mean;
}

double two_way_cv(const std::vector<double>& out, const std::vector<double>& back, int n) {
  return sm::cv_at_trays(out, back, layout(static_cast<int>(out.size())), n, {});
}

}  // namespace

TEST(ReturnPass, MatchesTheFieldLaidOutPassByPass) {
  for (int t : {12, 13, 40, 41}) {
    const std::vector<double> out = random_pattern(t, 7u + static_cast<std::uint64_t>(t));
    const std::vector<double> back = random_pattern(t, 900u + static_cast<std::uint64_t>(t));
    for (int n = 1; n <= t + 3; ++n) {
      EXPECT_NEAR(two_way_cv(out, back, n), field_cv(out, back, n), 1e-12) << "T=" << t << " n=" << n;
      // Scratch too small for two bouts: the bout is gathered tray by tray, with the same result.
      std::vector<double> small(1);
      EXPECT_NEAR(sm::cv_at_trays(out, back, layout(t), n, small), field_cv(out, back, n), 1e-12);
    }
  }
}

TEST(ReturnPass, TheOutgoingPatternAgainIsTheOneBoutToAndFro) {
  for (int t : {30, 31}) {
    const std::vector<double> p = random_pattern(t, 11);
    const std::vector<double> copy = p;  // another address: the two-bout window
    for (int n : {2, 5, 12, 29, 40}) {
      const double one = sm::cv_at_trays(p, layout(t), n, sm::Overlap::kToAndFro);
      EXPECT_NEAR(two_way_cv(p, copy, n), one, 1e-12 * one) << "T=" << t << " n=" << n;
      EXPECT_EQ(sm::cv_at_trays(p, p, layout(t), n, {}), one) << "the same span is the one-pattern function";
    }
  }
}

TEST(ReturnPass, AReturnPassThatIsTheOutgoingMirroredIsTheRacetrack) {
  // A machine whose pattern in a wind from the right is its pattern in a wind from the left mirrored:
  // the return pass, mirrored onto the field, lies down exactly as the outgoing one — racetrack.
  for (int t : {24, 25}) {
    const std::vector<double> p = random_pattern(t, 23);
    const std::vector<double> back = mirrored(p);
    for (int n : {2, 6, 13, 24}) {
      const double racetrack = sm::cv_at_trays(p, layout(t), n, sm::Overlap::kRacetrack);
      EXPECT_NEAR(two_way_cv(p, back, n), racetrack, 1e-12 * std::max(racetrack, 1e-3)) << "T=" << t << " n=" << n;
    }
  }
}

TEST(ReturnPass, GradientMatchesFiniteDifferencesForBothPatterns) {
  for (int t : {20, 21}) {
    const std::vector<double> out = random_pattern(t, 31), back = random_pattern(t, 32);
    for (int n : {3, 4, 9, 20, 27}) {
      std::vector<double> grad_out(out.size()), grad_back(back.size()), scratch(2 * (static_cast<std::size_t>(n) + 1));
      sm::cv_gradient(out, back, layout(t), n, grad_out, grad_back, scratch);
      std::vector<double> grad_out_alone(out.size());
      sm::cv_gradient(out, back, layout(t), n, grad_out_alone, {}, {});  // gathered tray by tray, return left out
      for (std::size_t i = 0; i < out.size(); ++i) {
        const double h = 1e-6;
        std::vector<double> up = out, down = out;
        up[i] += h;
        down[i] -= h;
        EXPECT_NEAR(grad_out[i], (two_way_cv(up, back, n) - two_way_cv(down, back, n)) / (2 * h), 1e-7) << "out i=" << i;
        EXPECT_NEAR(grad_out_alone[i], grad_out[i], 1e-12);
        up = back;
        down = back;
        up[i] += h;
        down[i] -= h;
        EXPECT_NEAR(grad_back[i], (two_way_cv(out, up, n) - two_way_cv(out, down, n)) / (2 * h), 1e-7) << "back i=" << i;
      }
    }
  }
}

TEST(ReturnPass, FastSearchEqualsTheWholeTrayScan) {
  // Spreader-like outgoing and return patterns: a hump pushed one way by the wind on the way out and the
  // other way (a little less far) on the way back, so the field repeats every two bouts.
  for (int t : {60, 61, 400}) {
    const sm::TrayLayout trays = layout(t, 0.25);
    std::vector<double> out(static_cast<std::size_t>(t)), back(static_cast<std::size_t>(t));
    for (int i = 0; i < t; ++i) {
      const double x = trays.centre_m(i) / (0.5 * t * trays.tray_width_m);
      out[static_cast<std::size_t>(i)] = std::max(0.0, 1.0 - 2.2 * (x - 0.12) * (x - 0.12));
      back[static_cast<std::size_t>(i)] = 0.9 * std::max(0.0, 1.0 - 2.6 * (x + 0.05) * (x + 0.05));
    }
    std::vector<double> scratch(sm::working_widths_scratch_size(t));
    for (double target : {0.03, 0.08, 0.15, 0.3}) {
      const sm::WorkingWidths fast = sm::working_widths(out, back, trays, target, scratch);
      const sm::WorkingWidth scan = sm::working_width(out, back, trays, target);
      const std::string where = "T=" + std::to_string(t) + " target=" + std::to_string(target);
      ASSERT_EQ(fast.to_and_fro.band_count, scan.band_count) << where;
      EXPECT_EQ(fast.to_and_fro.width_m, scan.width_m) << where;
      EXPECT_EQ(fast.to_and_fro.crossings, scan.crossings) << where;
      EXPECT_EQ(fast.to_and_fro.trays_below, scan.trays_below) << where;
      for (int b = 0; b < scan.stored_bands(); ++b) {
        EXPECT_EQ(fast.to_and_fro.bands[b].lower_m, scan.bands[b].lower_m) << where << " band " << b;
        EXPECT_EQ(fast.to_and_fro.bands[b].lowest_cv_trays, scan.bands[b].lowest_cv_trays) << where << " band " << b;
      }
      const sm::WorkingWidth racetrack = sm::working_width(out, trays, sm::Overlap::kRacetrack, target);
      EXPECT_EQ(fast.racetrack.width_m, racetrack.width_m) << where;
    }
  }
  // Random patterns, every width: the FFT's CV² against the exact one at each width.
  for (int t : {7, 36, 41, 120}) {
    const std::vector<double> out = random_pattern(t, 40u + static_cast<std::uint64_t>(t));
    const std::vector<double> back = random_pattern(t, 80u + static_cast<std::uint64_t>(t));
    std::vector<double> scratch(sm::working_widths_scratch_size(t));
    for (double target : {0.05, 0.15, 0.4}) {
      EXPECT_EQ(sm::working_widths(out, back, layout(t), target, scratch).to_and_fro.width_m,
                sm::working_width(out, back, layout(t), target).width_m) << "T=" << t << " target=" << target;
    }
  }
}

TEST(ReturnPass, ProfileHoldsBothBouts) {
  const int t = 21, n = 8;
  const std::vector<double> out = random_pattern(t, 3), back = random_pattern(t, 4);
  const sm::BoutTrays bout = sm::bout_trays(layout(t), n);
  std::vector<double> window(2 * static_cast<std::size_t>(bout.grid_trays));
  sm::overlapped_profile(out, back, layout(t), n * 0.5, window);
  // Weighted (half for the cut trays) the window holds one outgoing and one return pass's mass.
  double held = 0.0, passes = 0.0;
  for (std::size_t j = 0; j < window.size(); ++j) {
    const std::size_t in_bout = j % static_cast<std::size_t>(bout.grid_trays);
    const bool cut = bout.cut_edges && (in_bout == 0 || in_bout + 1 == static_cast<std::size_t>(bout.grid_trays));
    held += (cut ? 0.5 : 1.0) * window[j];
  }
  for (int i = 0; i < t; ++i) passes += out[static_cast<std::size_t>(i)] + back[static_cast<std::size_t>(i)];
  EXPECT_NEAR(held, passes, 1e-12 * passes);
  std::vector<double> one(static_cast<std::size_t>(bout.grid_trays));
  sm::overlapped_profile(out, layout(t), n * 0.5, sm::Overlap::kToAndFro, one);
  // Around an outgoing pass the two-way window's first bout differs from the mirrored-pattern bout only
  // through the return passes.
  EXPECT_NE(window[1], one[1]);
}

TEST(ReturnPass, RefusesAReturnPatternOfAnotherLayout) {
  const std::vector<double> out = random_pattern(10, 1), back = random_pattern(9, 2);
  try {
    sm::cv_at_trays(out, back, layout(10), 4, {});
    FAIL() << "a 9-tray return pattern on a 10-tray layout was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("return_tray_mass_kg"), std::string::npos) << e.what();
  }
  std::vector<double> scratch(sm::working_widths_scratch_size(10));
  EXPECT_THROW(sm::working_widths(out, back, layout(10), 0.15, scratch), std::invalid_argument);
}
