// A material's size as a sieve analysis: the size guide number and uniformity index read on the
// cumulative curve, the number distribution that feeds granules reproducing the sheet's mass fractions,
// and the scene keys (errors naming the field, the lognormal keys refused beside them, the inputs text).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "libspread/core/sieve_analysis.hpp"
#include "libspread/core/unit_uniform.hpp"
#include "libspread/io/scene/scene.hpp"

namespace spread {
namespace {

// Four intervals 1–2–3.15–4–5 mm: 10, 40, 40, 10 % of the mass.
SieveAnalysis four_intervals() { return {{1.0, 2.0, 3.15, 4.0, 5.0}, {10.0, 40.0, 40.0, 10.0}}; }

TEST(SieveAnalysis, SizeGuideNumberAndUniformityIndexOnTheCumulativeCurve) {
  const SieveAnalysis s = four_intervals();
  EXPECT_EQ(sieve_problem(s), "");
  // Passing: 0, 10, 50, 90, 100 % at 1, 2, 3.15, 4, 5 mm. d50 = 3.15 mm, d90 = 4 mm, d5 halfway up the
  // first interval (1.5 mm), d30 halfway up the second.
  EXPECT_NEAR(sieve_passing_size_mm(s, 50.0), 3.15, 1e-12);
  EXPECT_NEAR(sieve_passing_size_mm(s, 30.0), 2.575, 1e-12);
  EXPECT_NEAR(size_guide_number(s), 315.0, 1e-9);
  EXPECT_NEAR(uniformity_index(s), 100.0 * 1.5 / 4.0, 1e-9);
  // Fractions summing to 99.6 % (rounded sheet values) are taken relative to their sum.
  const SieveAnalysis rounded{{1.0, 2.0, 3.0}, {49.8, 49.8}};
  EXPECT_EQ(sieve_problem(rounded), "");
  EXPECT_NEAR(sieve_passing_size_mm(rounded, 50.0), 2.0, 1e-12);
  // An empty interval is skipped: the curve is flat across it.
  const SieveAnalysis gap{{1.0, 2.0, 3.0, 4.0}, {50.0, 0.0, 50.0}};
  EXPECT_NEAR(sieve_passing_size_mm(gap, 75.0), 3.5, 1e-12);
}

TEST(SieveAnalysis, BadSheetsNameTheField) {
  auto problem = [](SieveAnalysis s) { return sieve_problem(s); };
  EXPECT_EQ(problem({{2.0}, {}}).rfind("sieve_mm: needs at least 2", 0), 0u);
  EXPECT_EQ(problem({{1.0, 3.0, 2.0}, {50.0, 50.0}}).rfind("sieve_mm[2]: sieve sizes must increase, got 2 after 3", 0), 0u);
  EXPECT_EQ(problem({{-1.0, 3.0}, {100.0}}).rfind("sieve_mm[0]: must be in (0, 100] mm, got -1", 0), 0u);
  EXPECT_EQ(problem({{1.0, 2.0, 3.0}, {100.0}}).rfind("sieve_retained_pct: needs one value per interval", 0), 0u);
  EXPECT_EQ(problem({{1.0, 2.0, 3.0}, {110.0, -10.0}}).rfind("sieve_retained_pct[1]: must be a mass % >= 0, got -10", 0), 0u);
  EXPECT_EQ(problem({{1.0, 2.0, 3.0}, {50.0, 48.0}}), "sieve_retained_pct: the fractions must sum to 100 %, got 98 %");
  EXPECT_EQ(problem({{1.0, 2.0, 3.0}, {50.0, NAN}}).rfind("sieve_retained_pct[1]", 0), 0u);
}

// Granules drawn from the number distribution, weighed by their mass (d³), give back the sheet: each
// interval's mass fraction and the curve's d50 (within 0.5 %-points and 0.02 mm at 200,000 granules,
// about 5 standard errors). Drawing the intervals by their mass fractions instead, or uniformly in d
// within an interval, misses both by far more.
TEST(SieveAnalysis, SampledGranulesReproduceTheFractions) {
  const SieveAnalysis s = four_intervals();
  const SieveNumberDistribution number(s);
  std::mt19937_64 rng(11);
  std::vector<double> mass(4, 0.0);
  std::vector<std::pair<double, double>> by_size;
  double total = 0.0, sum_d = 0.0, sum_d3 = 0.0;
  const int n = 200000;
  for (int k = 0; k < n; ++k) {
    const double d_m = number.diameter_m(unit_uniform(rng()));
    ASSERT_GE(d_m, number.min_m() * (1 - 1e-12));
    ASSERT_LE(d_m, number.max_m() * (1 + 1e-12));
    const double d_mm = 1e3 * d_m, m = d_mm * d_mm * d_mm;
    std::size_t i = 0;
    while (i + 1 < 4 && d_mm >= s.sieve_mm[i + 1]) ++i;
    mass[i] += m;
    total += m;
    sum_d += d_m;
    sum_d3 += d_m * d_m * d_m;
    by_size.emplace_back(d_mm, m);
  }
  for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(100.0 * mass[i] / total, s.retained_pct[i], 0.5) << "interval " << i;
  std::sort(by_size.begin(), by_size.end());
  double below = 0.0, d50 = 0.0;
  for (const auto& [d_mm, m] : by_size) {
    below += m;
    if (below >= 0.5 * total) {
      d50 = d_mm;
      break;
    }
  }
  EXPECT_NEAR(d50, sieve_passing_size_mm(s, 50.0), 0.02);
  // The moments the feed rate and the table's row use.
  EXPECT_NEAR(sum_d / n, number.mean_m(), 2e-3 * number.mean_m());
  EXPECT_NEAR(sum_d3 / n, number.mean_cube_m3(), 1e-2 * number.mean_cube_m3());
}

const char* kSieveScene = R"toml(
[machine]
disc_radius_m = 0.3
[inlet]
radius_m = 0.01
offset_m = 0.1
[[materials]]
name = "sheet"
density_kg_m3 = 1500
sieve_mm = [1.0, 2.0, 3.15, 4.0, 5.0]
sieve_retained_pct = [10, 40, 40, 10]
)toml";

std::string scene_error(const std::vector<std::string>& overrides, const std::string& extra = "") {
  try {
    scene::parse_scene(std::string(kSieveScene) + extra, "scene.toml", overrides);
  } catch (const scene::SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneSieve, ReadAndTheRowHoldsItsNumberMoments) {
  const scene::Scene sc = scene::parse_scene(kSieveScene, "scene.toml");
  const scene::Material& m = sc.materials.front();
  EXPECT_EQ(m.sieve, four_intervals());
  const SieveNumberDistribution number(m.sieve);
  EXPECT_EQ(m.diameter_mean_m, number.mean_m());
  EXPECT_EQ(m.diameter_sd_m, number.sd_m());
  // The analysis is an input of the run: another fraction, another inputs hash.
  const std::string text = sc.run_inputs_text(m, 500.0);
  EXPECT_NE(text.find("material.sieve_mm[4] = 5\n"), std::string::npos) << text;
  EXPECT_NE(text.find("material.sieve_retained_pct[3] = 10\n"), std::string::npos) << text;
  const scene::Scene other = scene::parse_scene(kSieveScene, "scene.toml", {"materials.0.sieve_retained_pct=[10, 41, 39, 10]"});
  EXPECT_NE(other.run_inputs_hash(other.materials.front(), 500.0), sc.run_inputs_hash(m, 500.0));
}

TEST(SceneSieve, BadSheetsAreErrorsNamingTheKey) {
  EXPECT_EQ(scene_error({}), "");
  EXPECT_NE(scene_error({"materials.0.sieve_retained_pct=[10, 40, 40, 9]"})
                .find("scene.toml: materials[0].sieve_retained_pct: the fractions must sum to 100 %, got 99 %"),
            std::string::npos);
  EXPECT_NE(scene_error({"materials.0.sieve_mm=[1.0, 2.0, 1.5, 4.0, 5.0]"})
                .find("materials[0].sieve_mm[2]: sieve sizes must increase, got 1.5 after 2"),
            std::string::npos);
  EXPECT_NE(scene_error({"materials.0.sieve_retained_pct=[10, 50, 50, -10]"}).find("materials[0].sieve_retained_pct[3]: must be a mass % >= 0"),
            std::string::npos);
  EXPECT_NE(scene_error({"materials.0.sieve_mm=[1.0, 2.0, 3.15, 4.0]"}).find("materials[0].sieve_retained_pct: needs one value per interval"),
            std::string::npos);
  EXPECT_NE(scene_error({"materials.0.diameter_mean_m=3e-3"}).find("materials[0].diameter_mean_m: is a lognormal size, but this material gives its sizes as a sieve analysis"),
            std::string::npos);
  EXPECT_NE(scene_error({"materials.0.sieve_mm=\"x\""}).find("materials[0].sieve_mm: expected an array of numbers"), std::string::npos);
}

TEST(SceneSieve, OneListWithoutTheOtherIsAnError) {
  const std::string fractions_only = R"toml(
[[materials]]
name = "m"
density_kg_m3 = 1500
sieve_retained_pct = [100]
)toml";
  try {
    scene::parse_scene(fractions_only, "scene.toml");
    ADD_FAILURE() << "accepted";
  } catch (const scene::SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("materials[0].sieve_mm: missing"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace spread
