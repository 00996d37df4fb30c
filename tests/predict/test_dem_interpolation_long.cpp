// Long validation (label `long`): DEM launch rows 450 and 650 rpm of the default machine
// (scenes/case1_sweep.toml), interpolated by quantile cells at 550 rpm, against the DEM row at 550 rpm,
// for Urea.
// Each row simulates 0.6 s (~2200 launches): at 0.3 s the reference itself scatters ~8 % in throw width
// between seeds (docs/building-tables.md), which is more than the 3 % to be resolved. Three seeds; the
// interpolation of each seed's rows is compared with the mean of the seeds' 550 rows, and the criterion
// allows for the sampling noise measured from the seeds themselves (see the assertion). Minutes of DEM.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numeric>
#include <string>
#include <unistd.h>
#include <vector>

#include "libspread/analysis/predict/predictor.hpp"
#include "libspread/io/scene/scene.hpp"
#include "libspread/io/tables/table_reader.hpp"
#include "lookup_builder/table_build.hpp"

namespace spread::predict {
namespace {

struct Figures {
  double throw_width_m = 0.0, mean_radius_m = 0.0, radial_width_m = 0.0;
};

Figures predicted(const tables::TableContents& contents, double rpm) {
  Predictor predictor(contents);
  PredictionRequest request;
  request.material = "Urea";
  request.rpm = rpm;
  Prediction out;
  EXPECT_EQ(predictor.predict(request, out), PredictStatus::kOk);
  return {out.throw_width_m, out.mean_radius_m, out.radial_width_m};
}

// Contents restricted to the runs at these rpm.
tables::TableContents with_rows(tables::TableContents contents, std::vector<double> rpms) {
  std::erase_if(contents.runs, [&](const tables::Run& run) {
    return std::find(rpms.begin(), rpms.end(), run.rpm) == rpms.end();
  });
  return contents;
}

// The same row, relabelled to another rpm (its normalised samples then fly at the requested rpm).
tables::Run relabelled(tables::Run run, double rpm) {
  run.rpm = rpm;
  return run;
}

TEST(PredictDemLong, UreaAt550FromRows450And650WithinThreePercent) {
  const std::string scene_path = std::string(SPREAD_SOURCE_DIR) + "/scenes/case1_sweep.toml";
  std::vector<tables::TableContents> tables_by_seed;
  // SPREAD_DEM_TABLES=a.sqlite:b.sqlite[:...] measures tables built beforehand (Urea rows 450/550/650,
  // one seed each; docs/building-tables.md gives the commands) instead of building two here.
  if (const char* given = std::getenv("SPREAD_DEM_TABLES"); given != nullptr && *given != '\0') {
    std::string list = given;
    for (std::size_t begin = 0; begin <= list.size();) {
      const std::size_t end = std::min(list.find(':', begin), list.size());
      if (end > begin) tables_by_seed.push_back(tables::read_table_file(list.substr(begin, end - begin)));
      begin = end + 1;
    }
    ASSERT_GE(tables_by_seed.size(), 2u) << "SPREAD_DEM_TABLES needs at least two table files";
  }
  if (tables_by_seed.empty()) {
    for (int seed : {1, 2, 3}) {
      const std::string path = (std::filesystem::temp_directory_path() /
                                ("spread_predict_dem_long_" + std::to_string(::getpid()) + "_" +
                                 std::to_string(seed) + ".sqlite"))
                                   .string();
      std::filesystem::remove(path);
      const scene::Scene scene = scene::load_scene_file(
          scene_path, {"sweep.materials=[\"Urea\"]", "sweep.rpm=[450,550,650]", "numerics.duration_s=0.6",
                       "sweep.samples_per_run=100000", "numerics.seed=" + std::to_string(seed)});
      lookup::BuildOptions options;
      options.output_path = path;
      options.jobs = 1;
      lookup::build_tables(scene, options);
      tables_by_seed.push_back(tables::read_table_file(path));
      std::filesystem::remove(path);
    }
  }
  Figures reference;  // mean of the seeds' 550 rows
  const double share = 1.0 / static_cast<double>(tables_by_seed.size());
  std::vector<double> reference_widths, interpolated_widths;  // throw width per seed (m)
  for (const auto& contents : tables_by_seed) {
    const Figures row = predicted(with_rows(contents, {550.0}), 550.0);
    reference_widths.push_back(row.throw_width_m);
    std::printf("row 550: throw width %.3f m, R̄ %.4f m, ξ %.4f m\n", row.throw_width_m, row.mean_radius_m,
                row.radial_width_m);
    reference.throw_width_m += share * row.throw_width_m;
    reference.mean_radius_m += share * row.mean_radius_m;
    reference.radial_width_m += share * row.radial_width_m;
  }
  Figures mean_error;
  for (const auto& contents : tables_by_seed) {
    const Figures f = predicted(with_rows(contents, {450.0, 650.0}), 550.0);
    interpolated_widths.push_back(f.throw_width_m);
    const double tw = f.throw_width_m / reference.throw_width_m - 1.0;
    const double rbar = f.mean_radius_m / reference.mean_radius_m - 1.0;
    const double xi = f.radial_width_m / reference.radial_width_m - 1.0;
    std::printf("rows 450/650 → 550: throw width %.3f m (%+.2f %%), R̄ %.4f m (%+.2f %%), ξ %.4f m (%+.2f %%)\n",
                f.throw_width_m, 100 * tw, f.mean_radius_m, 100 * rbar, f.radial_width_m, 100 * xi);
    mean_error.throw_width_m += share * tw;
    mean_error.mean_radius_m += share * rbar;
    mean_error.radial_width_m += share * xi;
  }
  std::printf("mean over seeds: throw width %+.2f %%, R̄ %+.2f %%, ξ %+.2f %%\n", 100 * mean_error.throw_width_m,
              100 * mean_error.mean_radius_m, 100 * mean_error.radial_width_m);
  // The criterion on the seed mean, as docs/building-tables.md measures it. One seed's 0.6 s rows scatter
  // by a few % in throw width on their own (the 99 % width follows the farthest granules), and a change in
  // the DEM's last bits re-draws that scatter: with two seeds the mean error read −1.30 % before and
  // +4.22 % after one such change (the same law to rounding), so a bare 3 % bound on two seeds failed by
  // chance about one run in four. The throw width must therefore lie within 3 % plus twice the standard
  // error of the difference of the two means, estimated from the seeds (interpolation and reference are
  // independent runs): the test fails when the interpolation is shown to be more than 3 % off.
  auto variance_of_mean = [](const std::vector<double>& v) {
    const double n = static_cast<double>(v.size());
    const double mean = std::accumulate(v.begin(), v.end(), 0.0) / n;
    double ss = 0.0;
    for (double x : v) ss += (x - mean) * (x - mean);
    return ss / (n - 1.0) / n;
  };
  const double se_rel =
      std::sqrt(variance_of_mean(reference_widths) + variance_of_mean(interpolated_widths)) / reference.throw_width_m;
  std::printf("throw width: standard error of the difference of the means %.2f %%, bound %.2f %%\n", 100 * se_rel,
              100 * (0.03 + 2.0 * se_rel));
  EXPECT_LT(std::abs(mean_error.throw_width_m), 0.03 + 2.0 * se_rel);
  EXPECT_LT(std::abs(mean_error.mean_radius_m), 0.03);

  // Context, printed only: each row flown at 550 rpm (how far the normalised launch state is from linear
  // in rpm), and the first method — the mixture of both rows at half weight, assembled as one row.
  Figures mixture_error;
  for (const auto& contents : tables_by_seed) {
    tables::TableContents lower = with_rows(contents, {450.0}), upper = with_rows(contents, {650.0});
    tables::TableContents mixture = lower;
    mixture.runs[0].rpm = 550.0;
    mixture.runs[0].samples.insert(mixture.runs[0].samples.end(), upper.runs[0].samples.begin(),
                                   upper.runs[0].samples.end());
    for (auto& sample : mixture.runs[0].samples) sample.mass_kg *= 0.5f;
    lower.runs[0].rpm = 550.0;
    upper.runs[0].rpm = 550.0;
    const Figures lo = predicted(lower, 550.0), hi = predicted(upper, 550.0), mix = predicted(mixture, 550.0);
    std::printf("flown at 550: row 450 R̄ %.4f m, throw width %.3f m; row 650 R̄ %.4f m, throw width %.3f m\n",
                lo.mean_radius_m, lo.throw_width_m, hi.mean_radius_m, hi.throw_width_m);
    mixture_error.throw_width_m += share * (mix.throw_width_m / reference.throw_width_m - 1.0);
    mixture_error.mean_radius_m += share * (mix.mean_radius_m / reference.mean_radius_m - 1.0);
    mixture_error.radial_width_m += share * (mix.radial_width_m / reference.radial_width_m - 1.0);
  }
  std::printf("mixture of the rows (first method), mean over seeds: throw width %+.2f %%, R̄ %+.2f %%, ξ %+.2f %%\n",
              100 * mixture_error.throw_width_m, 100 * mixture_error.mean_radius_m, 100 * mixture_error.radial_width_m);

  // Two rows that sample one distribution (the 550 rows of both seeds, labelled 540 and 560) must
  // interpolate to that distribution: at 550 the result lies between the two rows (throw width: 2 %
  // margin, one 0.5 m tray at 24 m), where averaging unrelated granules would shrink or stretch it.
  tables::TableContents same = with_rows(tables_by_seed[0], {550.0});
  same.runs = {relabelled(with_rows(tables_by_seed[0], {550.0}).runs.at(0), 540.0),
               relabelled(with_rows(tables_by_seed[1], {550.0}).runs.at(0), 560.0)};
  const Figures between = predicted(same, 550.0);
  tables::TableContents first = same, second = same;
  first.runs = {relabelled(same.runs[0], 550.0)};
  second.runs = {relabelled(same.runs[1], 550.0)};
  const Figures a = predicted(first, 550.0), b = predicted(second, 550.0);
  std::printf("same distribution: rows %.3f / %.3f m, interpolated %.3f m throw width; R̄ %.4f / %.4f → %.4f m;"
              " ξ %.4f / %.4f → %.4f m\n",
              a.throw_width_m, b.throw_width_m, between.throw_width_m, a.mean_radius_m, b.mean_radius_m,
              between.mean_radius_m, a.radial_width_m, b.radial_width_m, between.radial_width_m);
  auto inside = [](double value, double x, double y, double margin) {
    return value >= std::min(x, y) * (1.0 - margin) && value <= std::max(x, y) * (1.0 + margin);
  };
  EXPECT_TRUE(inside(between.throw_width_m, a.throw_width_m, b.throw_width_m, 0.02));
  EXPECT_TRUE(inside(between.mean_radius_m, a.mean_radius_m, b.mean_radius_m, 0.002));
  EXPECT_TRUE(inside(between.radial_width_m, a.radial_width_m, b.radial_width_m, 0.01));
}

}  // namespace
}  // namespace spread::predict
