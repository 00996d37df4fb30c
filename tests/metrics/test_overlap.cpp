// Overlap, CV(W) and effective working width (DESIGN.md §3, docs/metrics.md).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "libspread/core/unit_uniform.hpp"
#include "libspread/metrics/metrics.hpp"

namespace sm = spread::metrics;

namespace {

sm::TrayLayout layout(int count, double width_m = 0.5) {
  sm::TrayLayout trays;
  trays.tray_width_m = width_m;
  trays.tray_count = count;
  return trays;
}

// Deterministic pseudo-random pattern in [0.1, 1.1) kg per tray (own mapping from the raw 64-bit draws,
// independent of the standard library's distributions).
std::vector<double> random_pattern(int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<double> p(static_cast<std::size_t>(count));
  for (double& v : p) v = 0.1 + spread::unit_uniform(rng());
  return p;
}

// Independent reference: everything on a grid of half trays. Pattern tray i covers half cells
// 2i - T and 2i - T + 1 (units of w/2 from x = 0), each with half its mass; pass k adds 2kn; the bout
// is half cells [-n, n) and bout tray j = (h + n) / 2.
double reference_cv(const std::vector<double>& p, int n, sm::Overlap overlap) {
  const int t = static_cast<int>(p.size());
  std::vector<double> bout(static_cast<std::size_t>(n), 0.0);
  const int reach = (t + n) / n + 3;
  for (int k = -reach; k <= reach; ++k) {
    const bool mirrored = overlap == sm::Overlap::kToAndFro && (k % 2 != 0);
    for (int i = 0; i < t; ++i) {
      const double m = mirrored ? p[static_cast<std::size_t>(t - 1 - i)] : p[static_cast<std::size_t>(i)];
      for (int half = 0; half < 2; ++half) {
        const int h = 2 * i - t + half + 2 * k * n;
        if (h >= -n && h < n) bout[static_cast<std::size_t>((h + n) / 2)] += 0.5 * m;
      }
    }
  }
  double mean = 0.0;
  for (double b : bout) mean += b;
  mean /= n;
  if (!(mean > 0.0)) return std::numeric_limits<double>::infinity();
  if (n == 1) return 0.0;
  double ss = 0.0;
  for (double b : bout) ss += (b - mean) * (b - mean);
  return std::sqrt(ss / (n - 1)) / mean;
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

TEST(Overlap, MatchesHalfTrayReferenceOnRandomPatterns) {
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
  // Bouts wider than 2048 trays are gathered tray by tray instead of scattered into a stack buffer.
  const std::vector<double> p = random_pattern(2101, 77);
  for (int n : {2047, 2048, 2049, 2100, 2101, 2102, 4300}) {
    for (auto overlap : {sm::Overlap::kRacetrack, sm::Overlap::kToAndFro}) {
      const double expected = reference_cv(p, n, overlap);
      EXPECT_NEAR(sm::cv_at_width(p, layout(2101), n * 0.5, overlap), expected, 1e-12 * (1.0 + expected)) << n;
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

TEST(Overlap, HandWorkedHalfTrayOffset) {
  // Trays [-0.75,-0.25], [-0.25,0.25], [0.25,0.75] hold 1, 2, 3 kg; W = 1 m, bout trays [-0.5,0], [0,0.5]:
  // every tray straddles two bout trays and gives half its mass to each.
  // Racetrack: [-0.5,0] = 1/2 + 2/2 + (pass at -1 m: tray 3 at [-0.75,-0.25]) 3/2 = 3;
  //            [0,0.5]  = 2/2 + 3/2 + (pass at +1 m: tray 1 at [0.25,0.75]) 1/2 = 3  → CV 0.
  // To-and-fro (neighbours 3,2,1): [-0.5,0] = 1.5 + 1/2 = 2, [0,0.5] = 2.5 + 3/2 = 4;
  //   mean 3, s = √2, CV = √2/3.
  const std::vector<double> p{1, 2, 3};
  EXPECT_NEAR(sm::cv_at_width(p, layout(3), 1.0, sm::Overlap::kRacetrack), 0.0, 1e-15);
  EXPECT_NEAR(sm::cv_at_width(p, layout(3), 1.0, sm::Overlap::kToAndFro), std::sqrt(2.0) / 3.0, 1e-15);
}

TEST(Overlap, ProfileConservesMassOfOnePass) {
  // Each tray of the pattern lands in the bout once over all passes (the bout is one period).
  const std::vector<double> p = random_pattern(25, 3);
  double total = 0.0;
  for (double v : p) total += v;
  for (int n = 1; n <= 40; ++n) {
    std::vector<double> bout(static_cast<std::size_t>(sm::bout_tray_count(layout(25), n * 0.5)));
    ASSERT_EQ(bout.size(), static_cast<std::size_t>(n));
    sm::overlapped_profile(p, layout(25), n * 0.5, sm::Overlap::kToAndFro, bout);
    double sum = 0.0;
    for (double v : bout) sum += v;
    EXPECT_NEAR(sum, total, 1e-12);
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
  //   n = 21 (bout [-5.25, 5.25]: half-tray offset, the end trays are half covered):
  //          0.5, 19 × 1, 0.5: mean 20/21, s² = (19·(1/21)² + 2·(19/42)²)/20 → CV = 0.1579;
  //   n = 22: 1 × 0, 20 × 1, 1 × 0: mean 10/11, s² = (20·(1/11)² + 2·(10/11)²)/21 → CV = 0.3237;
  //   n = 23: 0, 0.5, 19 × 1, 0.5, 0 → CV = 0.356; larger n are worse still.
  // For n < 20 the passes overlap to 1s and 2s, CV > 0 unless n divides 20.
  std::vector<double> p(40, 0.0);
  for (int i = 10; i < 30; ++i) p[static_cast<std::size_t>(i)] = 1.0;
  const sm::TrayLayout trays = layout(40);
  const double cv21 = std::sqrt((19.0 / 441.0 + 2.0 * 361.0 / 1764.0) / 20.0) * 21.0 / 20.0;
  const double cv22 = std::sqrt((20.0 / 121.0 + 2.0 * 100.0 / 121.0) / 21.0) * 11.0 / 10.0;
  EXPECT_NEAR(sm::cv_at_width(p, trays, 10.5, sm::Overlap::kRacetrack), cv21, 1e-12);
  EXPECT_NEAR(sm::cv_at_width(p, trays, 11.0, sm::Overlap::kRacetrack), cv22, 1e-12);
  EXPECT_NEAR(cv21, 0.1579, 1e-4);
  EXPECT_NEAR(cv22, 0.3237, 1e-4);
  for (auto overlap : {sm::Overlap::kRacetrack, sm::Overlap::kToAndFro}) {
    EXPECT_DOUBLE_EQ(sm::effective_working_width(p, trays, overlap, 0.15), 10.0);
    EXPECT_DOUBLE_EQ(sm::effective_working_width(p, trays, overlap, 1e-9), 10.0);
    EXPECT_DOUBLE_EQ(sm::effective_working_width(p, trays, overlap, 0.16), 10.5);
    EXPECT_DOUBLE_EQ(sm::effective_working_width(p, trays, overlap, 0.33), 11.0);
  }
}

TEST(EffectiveWorkingWidth, IsTheLargestWidthMeetingTheTarget) {
  const std::vector<double> p = random_pattern(36, 21);
  for (double target : {0.05, 0.1, 0.15, 0.3}) {
    const double w = sm::effective_working_width(p, layout(36), sm::Overlap::kToAndFro, target);
    for (int n = 36; n >= 2; --n) {
      const double cv = sm::cv_at_width(p, layout(36), n * 0.5, sm::Overlap::kToAndFro);
      if (n * 0.5 > w) {
        EXPECT_GT(cv, target) << n;
      } else if (n * 0.5 == w) {
        EXPECT_LE(cv, target) << n;
      }
    }
  }
}
