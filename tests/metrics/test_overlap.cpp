// Overlap, CV(W) and effective working width (docs/design.md §3, docs/metrics.md).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "libspread/core/unit_uniform.hpp"
#include "libspread/analysis/metrics/metrics.hpp"
#include "tests/metrics/test_patterns.hpp"

namespace sm = spread::metrics;

namespace {

using spread::metrics::testing::layout;
using spread::metrics::testing::random_pattern;

// Independent reference: the overlapped distribution on the pattern's own tray grid over one whole
// period, 2n consecutive trays starting at an arbitrary grid index (racetrack repeats every n trays,
// to-and-fro every 2n), brute force over passes. Two periods of racetrack and one of to-and-fro hold each
// bout tray value twice, so CV = sqrt(SS_2n / 2 / (n − 1)) / mean — no weights, no bout placement.
double reference_cv(const std::vector<double>& p, int n, sm::Overlap overlap, int start = 3) {
  const int t = static_cast<int>(p.size());
  std::vector<double> period(static_cast<std::size_t>(2 * n), 0.0);
  const int reach = (t + 2 * n + std::abs(start)) / n + 3;
  for (int k = -reach; k <= reach; ++k) {
    const bool mirrored = overlap == sm::Overlap::kToAndFro && (k % 2 != 0);
    for (int i = 0; i < t; ++i) {
      const int g = i + k * n - start;
      if (g < 0 || g >= 2 * n) continue;
      period[static_cast<std::size_t>(g)] += mirrored ? p[static_cast<std::size_t>(t - 1 - i)] : p[static_cast<std::size_t>(i)];
    }
  }
  double mean = 0.0;
  for (double b : period) mean += b;
  mean /= 2 * n;
  if (!(mean > 0.0)) return std::numeric_limits<double>::infinity();
  if (n == 1) return 0.0;
  double ss = 0.0;
  for (double b : period) ss += (b - mean) * (b - mean);
  return std::sqrt(ss / 2.0 / (n - 1)) / mean;
}

// Mass (kg) of a hat of half-width `half_width_m` and peak 1 kg/m over [a, b] (exact integral).
double hat_mass(double a, double b, double half_width_m) {
  auto primitive = [half_width_m](double x) {
    const double c = std::clamp(x, -half_width_m, half_width_m);
    return c >= 0.0 ? c - c * c / (2.0 * half_width_m) : c + c * c / (2.0 * half_width_m);
  };
  return primitive(b) - primitive(a);
}

}  // namespace

TEST(Overlap, UniformStripIsFlatAtEveryWholeTrayWidth) {
  // A uniform strip of a whole number of bouts tiles the ground exactly under racetrack, wherever it
  // sits on the grid: CV = 0 for every bout of n trays, even and odd layouts (half-tray offsets).
  for (int layout_trays : {120, 121}) {
    for (int n = 1; n <= 60; ++n) {
      const int strip = n * (100 / n);
      std::vector<double> p(static_cast<std::size_t>(layout_trays), 0.0);
      const int first = (layout_trays - strip) / 2;
      for (int i = first; i < first + strip; ++i) p[static_cast<std::size_t>(i)] = 2.5;
      EXPECT_NEAR(sm::cv_at_width(p, layout(layout_trays), n * 0.5, sm::Overlap::kRacetrack), 0.0, 1e-12)
          << "T=" << layout_trays << " n=" << n;
      // To-and-fro tiles too when the strip is centred on x = 0 (its mirror image is itself); an
      // off-centre strip's mirror image is shifted by a tray and the alternating passes do not tile.
      if ((layout_trays - strip) % 2 == 0) {
        EXPECT_NEAR(sm::cv_at_width(p, layout(layout_trays), n * 0.5, sm::Overlap::kToAndFro), 0.0, 1e-12)
            << "T=" << layout_trays << " n=" << n;
      }
    }
  }
}

TEST(Overlap, UniformOverWholeLayoutIsFlatWhenBoutDividesIt) {
  const std::vector<double> p(24, 1.0);
  for (int n : {1, 2, 3, 4, 6, 8, 12, 24}) {
    EXPECT_NEAR(sm::cv_at_width(p, layout(24), n * 0.5, sm::Overlap::kRacetrack), 0.0, 1e-12) << n;
    EXPECT_NEAR(sm::cv_at_width(p, layout(24), n * 0.5, sm::Overlap::kToAndFro), 0.0, 1e-12) << n;
  }
}

TEST(Overlap, MatchesWholePeriodReferenceOnRandomPatterns) {
  for (int t : {1, 2, 7, 8, 24, 25}) {
    const std::vector<double> p = random_pattern(t, 1000u + static_cast<std::uint64_t>(t));
    for (int n = 1; n <= 2 * t + 3; ++n) {
      for (auto overlap : {sm::Overlap::kRacetrack, sm::Overlap::kToAndFro}) {
        const double expected = reference_cv(p, n, overlap);
        EXPECT_NEAR(sm::cv_at_width(p, layout(t), n * 0.5, overlap), expected, 1e-12 * (1.0 + expected))
            << "T=" << t << " n=" << n;
      }
    }
  }
}

TEST(Overlap, VeryWideBoutsTakeTheGatherPathWithTheSameResult) {
  // Bouts wider than kStackBoutTrays are gathered tray by tray instead of scattered into the stack
  // buffer, unless the caller gives a scratch span: all three paths give the reference CV, and the two
  // scatter paths the same bits.
  const std::vector<double> p = random_pattern(2101, 77);
  std::vector<double> scratch(4400);
  constexpr int kStack = sm::kStackBoutTrays;
  for (int n : {kStack - 2, kStack - 1, kStack, kStack + 1, 2047, 2048, 2049, 2100, 2101, 2102, 4300}) {
    for (auto overlap : {sm::Overlap::kRacetrack, sm::Overlap::kToAndFro}) {
      const double expected = reference_cv(p, n, overlap);
      EXPECT_NEAR(sm::cv_at_width(p, layout(2101), n * 0.5, overlap), expected, 1e-12 * (1.0 + expected)) << n;
      EXPECT_NEAR(sm::cv_at_trays(p, layout(2101), n, overlap, scratch), expected, 1e-12 * (1.0 + expected)) << n;
      if (n <= kStack - 1) {
        EXPECT_EQ(sm::cv_at_trays(p, layout(2101), n, overlap, scratch), sm::cv_at_trays(p, layout(2101), n, overlap));
      }
    }
  }
}

TEST(Overlap, SymmetricPatternGivesSameCvForBothOverlaps) {
  for (int t : {20, 21}) {
    std::vector<double> p = random_pattern(t, 7);
    for (int i = 0; i < t / 2; ++i) p[static_cast<std::size_t>(t - 1 - i)] = p[static_cast<std::size_t>(i)];
    for (int n = 1; n <= t + 5; ++n) {
      EXPECT_NEAR(sm::cv_at_width(p, layout(t), n * 0.5, sm::Overlap::kToAndFro),
                  sm::cv_at_width(p, layout(t), n * 0.5, sm::Overlap::kRacetrack), 1e-12)
          << "T=" << t << " n=" << n;
    }
  }
}

TEST(Overlap, MirroredInputLeavesToAndFroCvUnchanged) {
  // Mirroring the pattern mirrors the to-and-fro bout profile (docs/metrics.md), and the bout's
  // trays are symmetric about x = 0, so the CV is the same.
  for (int t : {30, 31}) {
    const std::vector<double> p = random_pattern(t, 11);
    const std::vector<double> mirrored(p.rbegin(), p.rend());
    for (int n = 1; n <= t + 5; ++n) {
      const double cv = sm::cv_at_width(p, layout(t), n * 0.5, sm::Overlap::kToAndFro);
      EXPECT_NEAR(sm::cv_at_width(mirrored, layout(t), n * 0.5, sm::Overlap::kToAndFro), cv, 1e-12 * (1 + cv));
      // And racetrack of the mirror is the mirror of racetrack: also unchanged.
      const double cv_rt = sm::cv_at_width(p, layout(t), n * 0.5, sm::Overlap::kRacetrack);
      EXPECT_NEAR(sm::cv_at_width(mirrored, layout(t), n * 0.5, sm::Overlap::kRacetrack), cv_rt,
                  1e-12 * (1 + cv_rt));
    }
  }
}

TEST(Overlap, TriangleOfHalfWidthWOverlapsFlatAtW) {
  // Hats of half-width W at spacing W sum to a constant: racetrack CV = 0 at W. Tray masses are the
  // exact integrals, so this holds on the tray grid too (also with the half-tray offset of an odd layout).
  for (int layout_trays : {24, 25}) {
    const sm::TrayLayout trays = layout(layout_trays);
    const double w_m = 6.0;
    std::vector<double> p(static_cast<std::size_t>(layout_trays));
    for (int i = 0; i < layout_trays; ++i) {
      const double a = trays.left_edge_m() + i * trays.tray_width_m;
      p[static_cast<std::size_t>(i)] = hat_mass(a, a + trays.tray_width_m, w_m);
    }
    EXPECT_NEAR(sm::cv_at_width(p, trays, w_m, sm::Overlap::kRacetrack), 0.0, 1e-12);
    EXPECT_NEAR(sm::cv_at_width(p, trays, w_m, sm::Overlap::kToAndFro), 0.0, 1e-12);
    EXPECT_GT(sm::cv_at_width(p, trays, w_m + 1.0, sm::Overlap::kRacetrack), 0.01);
  }
}

TEST(Overlap, HandWorkedEvenLayout) {
  // Trays (0.5 m) at [-1,-0.5], [-0.5,0], [0,0.5], [0.5,1] hold 1, 2, 3, 4 kg; W = 1 m: bout trays
  // [-0.5,0] and [0,0.5].
  // Racetrack: [-0.5,0] gets own 2 + tray [0.5,1] of the pass at -1 m (4) = 6;
  //            [0,0.5]  gets own 3 + tray [-1,-0.5] of the pass at +1 m (1) = 4.
  //   mean 5, s = sqrt((1 + 1)/1) = √2, CV = √2/5.
  // To-and-fro: the passes at ±1 m are mirrored (values 4,3,2,1 left to right):
  //   [-0.5,0] = 2 + 1 = 3, [0,0.5] = 3 + 4 = 7; mean 5, s = sqrt((4 + 4)/1) = 2√2, CV = 2√2/5.
  const std::vector<double> p{1, 2, 3, 4};
  EXPECT_NEAR(sm::cv_at_width(p, layout(4), 1.0, sm::Overlap::kRacetrack), std::sqrt(2.0) / 5.0, 1e-15);
  EXPECT_NEAR(sm::cv_at_width(p, layout(4), 1.0, sm::Overlap::kToAndFro), 2.0 * std::sqrt(2.0) / 5.0, 1e-15);
  std::vector<double> bout(2);
  sm::overlapped_profile(p, layout(4), 1.0, sm::Overlap::kRacetrack, bout);
  EXPECT_DOUBLE_EQ(bout[0], 6.0);
  EXPECT_DOUBLE_EQ(bout[1], 4.0);
  sm::overlapped_profile(p, layout(4), 1.0, sm::Overlap::kToAndFro, bout);
  EXPECT_DOUBLE_EQ(bout[0], 3.0);
  EXPECT_DOUBLE_EQ(bout[1], 7.0);
}

TEST(Overlap, HandWorkedCutEdgeTrays) {
  // Trays [-0.75,-0.25], [-0.25,0.25], [0.25,0.75] hold 1, 2, 3 kg; W = 1 m (n = 2 trays, T = 3: n - T odd).
  // The bout [-0.5, 0.5] touches grid trays 0, 1, 2; trays 0 and 2 are cut in half by the bout edges.
  // Racetrack (passes every 2 trays): P0 = 1 + 3 (pass at -1 m) = 4, P1 = 2, P2 = 3 + 1 (pass at +1 m) = 4:
  //   weights 1/2, 1, 1/2: mean = (2 + 2 + 2)/2 = 3, SS = (1/2 + 1 + 1/2)·1 = 2, s = √2, CV = √2/3
  //   (the field repeats 4, 2, 4, 2, ...: a sample CV over one period of two trays gives the same).
  // To-and-fro (odd passes mirrored, 3 2 1): P0 = 1 + 1 = 2, P1 = 2, P2 = 3 + 3 = 6:
  //   mean = (1 + 2 + 3)/2 = 3, SS = 1/2 + 1 + 9/2 = 6, CV = √6/3.
  // Splitting the trays between bout trays instead would give racetrack CV 0: a moving average.
  const std::vector<double> p{1, 2, 3};
  EXPECT_NEAR(sm::cv_at_width(p, layout(3), 1.0, sm::Overlap::kRacetrack), std::sqrt(2.0) / 3.0, 1e-15);
  EXPECT_NEAR(sm::cv_at_width(p, layout(3), 1.0, sm::Overlap::kToAndFro), std::sqrt(6.0) / 3.0, 1e-15);
  const sm::BoutTrays bout = sm::bout_trays(layout(3), 2);
  EXPECT_TRUE(bout.cut_edges);
  EXPECT_EQ(bout.first_tray, 0);
  EXPECT_EQ(bout.grid_trays, 3);
  std::vector<double> profile(3);
  sm::overlapped_profile(p, layout(3), 1.0, sm::Overlap::kToAndFro, profile);
  EXPECT_DOUBLE_EQ(profile[0], 2.0);
  EXPECT_DOUBLE_EQ(profile[1], 2.0);
  EXPECT_DOUBLE_EQ(profile[2], 6.0);
}

TEST(Overlap, ProfileConservesMassOfOnePass) {
  // Each tray of the pattern lands in the bout once over all passes (the bout is one period), cut edge
  // trays counting half.
  const std::vector<double> p = random_pattern(25, 3);
  double total = 0.0;
  for (double v : p) total += v;
  for (int n = 1; n <= 40; ++n) {
    for (auto overlap : {sm::Overlap::kRacetrack, sm::Overlap::kToAndFro}) {
      const sm::BoutTrays bout = sm::bout_trays(layout(25), n);
      ASSERT_EQ(bout.grid_trays, n % 2 == 25 % 2 ? n : n + 1);
      std::vector<double> profile(static_cast<std::size_t>(bout.grid_trays));
      sm::overlapped_profile(p, layout(25), n * 0.5, overlap, profile);
      double sum = 0.0;
      for (std::size_t j = 0; j < profile.size(); ++j) {
        sum += (bout.cut_edges && (j == 0 || j + 1 == profile.size()) ? 0.5 : 1.0) * profile[j];
      }
      EXPECT_NEAR(sum, total, 1e-12) << n;
    }
  }
}

TEST(Overlap, GradientMatchesFiniteDifferences) {
  for (int t : {20, 21}) {
    const std::vector<double> p = random_pattern(t, 31);
    for (int n : {3, 4, 9, 20, 27}) {
      for (auto overlap : {sm::Overlap::kRacetrack, sm::Overlap::kToAndFro}) {
        std::vector<double> grad(p.size());
        sm::cv_gradient(p, layout(t), n, overlap, grad);
        for (std::size_t i = 0; i < p.size(); ++i) {
          std::vector<double> up = p, down = p;
          const double h = 1e-6;
          up[i] += h;
          down[i] -= h;
          const double numeric = (sm::cv_at_trays(up, layout(t), n, overlap) - sm::cv_at_trays(down, layout(t), n, overlap)) / (2 * h);
          EXPECT_NEAR(grad[i], numeric, 1e-7) << "T=" << t << " n=" << n << " i=" << i;
        }
      }
    }
  }
}

TEST(Overlap, WidthIsRoundedToWholeTrays) {
  const std::vector<double> p = random_pattern(20, 5);
  EXPECT_EQ(sm::bout_tray_count(layout(20), 3.1), 6);
  EXPECT_EQ(sm::bout_tray_count(layout(20), 0.1), 1);
  EXPECT_EQ(sm::bout_tray_count(layout(20), 0.0), 1);
  EXPECT_DOUBLE_EQ(sm::cv_at_width(p, layout(20), 3.1, sm::Overlap::kToAndFro),
                   sm::cv_at_width(p, layout(20), 3.0, sm::Overlap::kToAndFro));
}

TEST(Overlap, CurveMatchesPointwise) {
  const std::vector<double> p = random_pattern(30, 9);
  std::vector<double> widths, cv(20);
  for (int i = 0; i < 20; ++i) widths.push_back(1.0 + 0.5 * i);
  sm::cv_curve(p, layout(30), widths, sm::Overlap::kRacetrack, cv);
  for (std::size_t i = 0; i < widths.size(); ++i) {
    EXPECT_EQ(cv[i], sm::cv_at_width(p, layout(30), widths[i], sm::Overlap::kRacetrack));
  }
}

TEST(Overlap, EdgeCases) {
  // Zero mass: the bout is empty → +inf (fails any target); no effective width.
  const std::vector<double> zeros(10, 0.0);
  EXPECT_EQ(sm::cv_at_width(zeros, layout(10), 2.0, sm::Overlap::kToAndFro),
            std::numeric_limits<double>::infinity());
  EXPECT_EQ(sm::effective_working_width(zeros, layout(10), sm::Overlap::kToAndFro, 0.15), 0.0);
  // No trays at all.
  const std::vector<double> none;
  EXPECT_EQ(sm::cv_at_width(none, layout(0), 2.0, sm::Overlap::kRacetrack), std::numeric_limits<double>::infinity());
  EXPECT_EQ(sm::effective_working_width(none, layout(0), sm::Overlap::kRacetrack, 0.15), 0.0);
  // One-tray bout: no spread.
  const std::vector<double> ones(4, 1.0);
  EXPECT_EQ(sm::cv_at_width(random_pattern(4, 1), layout(4), 0.5, sm::Overlap::kRacetrack), 0.0);
  // W wider than the layout: 4 full trays in a bout of 8 (passes at ±4 m do not reach):
  // values 0,0,1,1,1,1,0,0 → mean 0.5, s = sqrt(8·0.25/7), CV = 2·sqrt(2/7).
  EXPECT_NEAR(sm::cv_at_width(ones, layout(4), 4.0, sm::Overlap::kRacetrack), 2.0 * std::sqrt(2.0 / 7.0), 1e-15);
  // Programming errors name the input.
  try {
    sm::cv_at_width(ones, layout(5), 2.0, sm::Overlap::kRacetrack);
    FAIL() << "size mismatch not detected";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("tray_mass_kg"), std::string::npos) << e.what();
  }
  EXPECT_THROW(sm::cv_at_width(ones, layout(4), -1.0, sm::Overlap::kRacetrack), std::invalid_argument);
  EXPECT_THROW(sm::cv_at_width(ones, layout(4), std::nan(""), sm::Overlap::kRacetrack), std::invalid_argument);
  EXPECT_THROW(sm::cv_at_width(ones, layout(4, 0.0), 1.0, sm::Overlap::kRacetrack), std::invalid_argument);
  std::vector<double> wrong(3);
  EXPECT_THROW(sm::overlapped_profile(ones, layout(4), 1.0, sm::Overlap::kRacetrack, wrong), std::invalid_argument);
}

TEST(EffectiveWorkingWidth, StripWithHandComputedCurve) {
  // A uniform strip of 20 trays (10 m, [-5, 5] m) centred in 40 trays (20 m). Passes tile exactly at
  // n = 20 (CV 0). For n > 20 trays only the machine's own pass reaches the bout, leaving empty trays:
  //   n = 21 (n - T odd: the bout edges cut grid trays 9 and 30, both empty, weight 1/2; 20 full trays):
  //          mean 20/21, SS = 20·(1/21)² + 2·(1/2)(20/21)², s² = SS/20 → CV = 0.2291;
  //   n = 22: 1 × 0, 20 × 1, 1 × 0: mean 10/11, s² = (20·(1/11)² + 2·(10/11)²)/21 → CV = 0.3237.
  // For n < 20 the passes overlap to 1s and 2s, CV > 0 unless n divides 20: n = 19 puts a doubled
  // cut edge tray at each end (weight 1/2) holding 2, mean 20/19,
  // CV = sqrt((18·(1/19)² + (18/19)²)/18)/(20/19) = 0.2179.
  std::vector<double> p(40, 0.0);
  for (int i = 10; i < 30; ++i) p[static_cast<std::size_t>(i)] = 1.0;
  const sm::TrayLayout trays = layout(40);
  const double cv21 = std::sqrt((20.0 / 441.0 + 400.0 / 441.0) / 20.0) * 21.0 / 20.0;
  const double cv22 = std::sqrt((20.0 / 121.0 + 2.0 * 100.0 / 121.0) / 21.0) * 11.0 / 10.0;
  const double cv19 = std::sqrt((18.0 / 361.0 + 324.0 / 361.0) / 18.0) * 19.0 / 20.0;
  EXPECT_NEAR(sm::cv_at_width(p, trays, 10.5, sm::Overlap::kRacetrack), cv21, 1e-12);
  EXPECT_NEAR(sm::cv_at_width(p, trays, 11.0, sm::Overlap::kRacetrack), cv22, 1e-12);
  EXPECT_NEAR(sm::cv_at_width(p, trays, 9.5, sm::Overlap::kRacetrack), cv19, 1e-12);
  EXPECT_NEAR(cv21, 0.2291, 1e-4);
  EXPECT_NEAR(cv22, 0.3237, 1e-4);
  EXPECT_NEAR(cv19, 0.2179, 1e-4);
  for (auto overlap : {sm::Overlap::kRacetrack, sm::Overlap::kToAndFro}) {
    // The strip's own zig-zag (n that do not divide 20) rises above 15 % well before 10 m and comes back
    // to 0 at 10 m: the first band ends early, the widest ends between 20 trays (CV 0) and 21 (cv21),
    // which is where a 10 m strip is driven.
    const sm::WorkingWidth at15 = sm::working_width(p, trays, overlap, 0.15);
    ASSERT_GE(at15.band_count, 2);
    EXPECT_LT(at15.first_band_upper_m(), 10.0);
    EXPECT_EQ(at15.trays_below, 20);
    EXPECT_NEAR(at15.width_m, 10.0 + 0.5 * 0.15 / cv21, 1e-12);
    EXPECT_EQ(at15.bands[at15.stored_bands() - 1].lowest_cv_trays, 20);
    EXPECT_NEAR(at15.bands[at15.stored_bands() - 1].lowest_cv, 0.0, 1e-12);
    EXPECT_GE(at15.crossings, 3);
    EXPECT_FALSE(at15.limited_by_layout);
  }
}

TEST(EffectiveWorkingWidth, HatCrossingIsInterpolatedBetweenWholeTrayWidths) {
  // A hat of half-width 6 m overlaps flat at W = 6 m and below; wider bouts leave a dip between passes,
  // so CV(W) rises once. The working width lies between the two whole-tray widths around the crossing,
  // linear in CV.
  for (int layout_trays : {40, 41}) {
    const sm::TrayLayout trays = layout(layout_trays);
    std::vector<double> p(static_cast<std::size_t>(layout_trays));
    for (int i = 0; i < layout_trays; ++i) {
      const double a = trays.left_edge_m() + i * trays.tray_width_m;
      p[static_cast<std::size_t>(i)] = hat_mass(a, a + trays.tray_width_m, 6.0);
    }
    for (auto overlap : {sm::Overlap::kRacetrack, sm::Overlap::kToAndFro}) {
      const sm::WorkingWidth w = sm::working_width(p, trays, overlap, 0.15);
      ASSERT_GT(w.trays_below, 12) << layout_trays;
      EXPECT_EQ(w.crossings, 1);
      const double below = sm::cv_at_trays(p, trays, w.trays_below, overlap);
      const double above = sm::cv_at_trays(p, trays, w.trays_below + 1, overlap);
      EXPECT_LE(below, 0.15);
      EXPECT_GT(above, 0.15);
      EXPECT_DOUBLE_EQ(w.cv_below, below);
      EXPECT_DOUBLE_EQ(w.cv_above, above);
      EXPECT_NEAR(w.width_m, 0.5 * (w.trays_below + (0.15 - below) / (above - below)), 1e-12);
      EXPECT_DOUBLE_EQ(sm::effective_working_width(p, trays, overlap, 0.15), w.width_m);
    }
  }
}

TEST(EffectiveWorkingWidth, TheSameRuleOnASampledCurve) {
  // The plots and the tray tests read the working width off a curve they already hold: the same numbers.
  const std::vector<double> p = random_pattern(36, 21);
  std::vector<double> widths;
  for (int n = 2; n <= 36; ++n) widths.push_back(0.5 * n);
  for (double target : {0.05, 0.1, 0.15, 0.3}) {
    for (auto overlap : {sm::Overlap::kRacetrack, sm::Overlap::kToAndFro}) {
      std::vector<double> cv(widths.size());
      sm::cv_curve(p, layout(36), widths, overlap, cv);
      const sm::WorkingWidth direct = sm::working_width(p, layout(36), overlap, target);
      const sm::WorkingWidth on_curve = sm::working_width_on_curve(widths, cv, target);
      EXPECT_DOUBLE_EQ(on_curve.width_m, direct.width_m) << target;
      EXPECT_EQ(on_curve.crossings, direct.crossings) << target;
      EXPECT_EQ(on_curve.limited_by_layout, direct.limited_by_layout) << target;
    }
  }
  // A hand-made zig-zag: 2 m 10 %, 3 m 12 %, 4 m 20 %, 5 m 12 %: the first band ends between 3 and 4 m
  // at 15 %: 3 + (15 − 12)/(20 − 12) = 3.375 m; the second starts at 4 + (20 − 15)/(20 − 12) = 4.625 m
  // and runs to the end of the curve, 5 m: the working width.
  const sm::WorkingWidth zig = sm::working_width_on_curve(std::vector<double>{2, 3, 4, 5},
                                                          std::vector<double>{0.10, 0.12, 0.20, 0.12}, 0.15);
  EXPECT_DOUBLE_EQ(zig.width_m, 5.0);
  EXPECT_TRUE(zig.limited_by_layout);
  EXPECT_EQ(zig.crossings, 2);
  ASSERT_EQ(zig.band_count, 2);
  EXPECT_DOUBLE_EQ(zig.bands[0].lower_m, 2.0);
  EXPECT_DOUBLE_EQ(zig.bands[0].upper_m, 3.375);
  EXPECT_DOUBLE_EQ(zig.bands[0].lowest_cv, 0.10);
  EXPECT_DOUBLE_EQ(zig.bands[1].lower_m, 4.625);
  EXPECT_DOUBLE_EQ(zig.bands[1].upper_m, 5.0);
  EXPECT_DOUBLE_EQ(zig.first_band_upper_m(), 3.375);
  // A curve that starts above the target has its first band where it dips under.
  const sm::WorkingWidth late = sm::working_width_on_curve(std::vector<double>{2, 3, 4},
                                                           std::vector<double>{0.30, 0.10, 0.20}, 0.15);
  ASSERT_EQ(late.band_count, 1);
  EXPECT_DOUBLE_EQ(late.bands[0].lower_m, 2.0 + 15.0 / 20.0);
  EXPECT_DOUBLE_EQ(late.width_m, 3.5);
  EXPECT_THROW(sm::working_width_on_curve(std::vector<double>{2, 2}, std::vector<double>{0.1, 0.1}, 0.15),
               std::invalid_argument);
  EXPECT_THROW(sm::working_width_on_curve(std::vector<double>{2}, std::vector<double>{0.1, 0.1}, 0.15),
               std::invalid_argument);
}

TEST(EffectiveWorkingWidth, BandsAreTheRunsWithinTheTarget) {
  // Every run of whole-tray widths with CV <= target is one band, found by brute force here; the working
  // width ends the widest run.
  const std::vector<double> p = random_pattern(36, 21);
  for (double target : {0.05, 0.1, 0.15, 0.3}) {
    for (auto overlap : {sm::Overlap::kRacetrack, sm::Overlap::kToAndFro}) {
      const sm::WorkingWidth w = sm::working_width(p, layout(36), overlap, target);
      std::vector<std::pair<int, int>> runs;  // first and last tray count within the target
      int crossings = 0;
      bool before = false;
      for (int n = 2; n <= 36; ++n) {
        const bool now = sm::cv_at_trays(p, layout(36), n, overlap) <= target;
        if (n > 2 && now != before) ++crossings;
        if (now && !before) runs.emplace_back(n, n);
        if (now) runs.back().second = n;
        before = now;
      }
      EXPECT_EQ(w.crossings, crossings) << target;
      ASSERT_EQ(w.band_count, static_cast<int>(runs.size())) << target;
      if (runs.empty()) {
        EXPECT_EQ(w.width_m, 0.0);
        continue;
      }
      for (int b = 0; b < w.stored_bands(); ++b) {
        const auto [first, last] = runs[static_cast<std::size_t>(b)];
        const sm::WidthBand& band = w.bands[b];
        EXPECT_EQ(band.trays_below, last) << target << " band " << b;
        EXPECT_GE(band.upper_m, last * 0.5);
        EXPECT_LE(band.upper_m, (last + 1) * 0.5);
        EXPECT_LE(band.lower_m, first * 0.5);
        EXPECT_GE(band.lower_m, first == 2 ? 1.0 : (first - 1) * 0.5);
        double lowest = std::numeric_limits<double>::infinity();
        for (int n = first; n <= last; ++n) lowest = std::min(lowest, sm::cv_at_trays(p, layout(36), n, overlap));
        EXPECT_DOUBLE_EQ(band.lowest_cv, lowest);
        EXPECT_DOUBLE_EQ(sm::cv_at_trays(p, layout(36), band.lowest_cv_trays, overlap), lowest);
      }
      EXPECT_EQ(w.trays_below, runs.back().second);
      if (runs.back().second == 36) {
        EXPECT_TRUE(w.limited_by_layout);
        EXPECT_DOUBLE_EQ(w.width_m, 18.0);
      }
    }
  }
}

namespace {

// working_widths (FFT correlations, O(T log T)) must give exactly working_width's results (O(T²)).
void expect_same_widths(const std::vector<double>& p, const sm::TrayLayout& trays, double target,
                        const std::string& what) {
  std::vector<double> scratch(sm::working_widths_scratch_size(trays.tray_count));
  const sm::WorkingWidths fast = sm::working_widths(p, trays, target, scratch);
  const sm::WorkingWidth* got[] = {&fast.to_and_fro, &fast.racetrack};
  const sm::Overlap overlaps[] = {sm::Overlap::kToAndFro, sm::Overlap::kRacetrack};
  for (int k = 0; k < 2; ++k) {
    const sm::WorkingWidth want = sm::working_width(p, trays, overlaps[k], target);
    const std::string where = what + (k == 0 ? " to-and-fro" : " racetrack") + " target " + std::to_string(target);
    EXPECT_EQ(got[k]->width_m, want.width_m) << where;  // bit for bit
    EXPECT_EQ(got[k]->crossings, want.crossings) << where;
    EXPECT_EQ(got[k]->trays_below, want.trays_below) << where;
    EXPECT_EQ(got[k]->cv_below, want.cv_below) << where;
    EXPECT_EQ(got[k]->cv_above, want.cv_above) << where;
    EXPECT_EQ(got[k]->limited_by_layout, want.limited_by_layout) << where;
    ASSERT_EQ(got[k]->band_count, want.band_count) << where;
    for (int b = 0; b < want.stored_bands(); ++b) {
      EXPECT_EQ(got[k]->bands[b].lower_m, want.bands[b].lower_m) << where << " band " << b;
      EXPECT_EQ(got[k]->bands[b].upper_m, want.bands[b].upper_m) << where << " band " << b;
      // The band's lowest point is ranked by the FFT's CVs: a tie within their rounding may pick the other.
      EXPECT_NEAR(got[k]->bands[b].lowest_cv, want.bands[b].lowest_cv, 1e-9) << where << " band " << b;
    }
  }
}

}  // namespace

TEST(WorkingWidths, FastSearchEqualsTheWholeTrayScan) {
  for (int t : {2, 3, 7, 36, 41, 120, 401}) {
    for (double target : {0.01, 0.05, 0.15, 0.3, 2.0}) {
      expect_same_widths(random_pattern(t, 500u + static_cast<std::uint64_t>(t)), layout(t), target,
                         "random " + std::to_string(t));
    }
  }
  // Spreader-like patterns: a hat and a skewed double hump with empty trays around them (the hump is
  // where the crossing is), odd and even tray counts, and the strip whose CV(W) zig-zags across 15 %.
  for (int t : {80, 81, 600}) {
    const sm::TrayLayout trays = layout(t, 0.25);
    std::vector<double> hat(static_cast<std::size_t>(t)), humps(static_cast<std::size_t>(t));
    for (int i = 0; i < t; ++i) {
      const double a = trays.left_edge_m() + i * trays.tray_width_m;
      hat[static_cast<std::size_t>(i)] = hat_mass(a, a + trays.tray_width_m, 0.3 * t * trays.tray_width_m);
      const double x = trays.centre_m(i) / (0.5 * t * trays.tray_width_m);
      humps[static_cast<std::size_t>(i)] =
          std::max(0.0, 1.0 - 9.0 * (x - 0.35) * (x - 0.35)) + 0.6 * std::max(0.0, 1.0 - 16.0 * (x + 0.4) * (x + 0.4));
    }
    for (double target : {0.05, 0.1, 0.15, 0.25}) {
      expect_same_widths(hat, trays, target, "hat " + std::to_string(t));
      expect_same_widths(humps, trays, target, "humps " + std::to_string(t));
    }
  }
  std::vector<double> strip(40, 0.0);
  for (int i = 10; i < 30; ++i) strip[static_cast<std::size_t>(i)] = 1.0;
  for (double target : {0.1, 0.15, 0.22, 0.3}) expect_same_widths(strip, layout(40), target, "strip");
}

TEST(WorkingWidths, DegenerateInputsAsTheScan) {
  expect_same_widths(std::vector<double>(10, 0.0), layout(10), 0.15, "zeros");
  std::vector<double> negative = random_pattern(30, 3);
  negative[4] = -0.5;  // not a tray mass: falls back to the scan
  expect_same_widths(negative, layout(30), 0.15, "negative");
  std::vector<double> one(20, 0.0);
  one[7] = 1.0;
  expect_same_widths(one, layout(20), 0.15, "one tray");
  expect_same_widths(random_pattern(12, 9), layout(12), -1.0, "negative target");
  std::vector<double> scratch(3);
  EXPECT_THROW(sm::working_widths(random_pattern(12, 9), layout(12), 0.15, scratch), std::invalid_argument);
}
