// Tables: rpm grid spacing and launch samples per run against the prediction error (throw width, R̄,
// working width) relative to a direct computation at the requested rpm (analytic launch at exactly that
// rpm, many samples, the same predictor and flight), against prediction time (Predictor::predict, the
// path the C API takes) and table size (bytes of the SQLite file written by tables::TableWriter).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include <unistd.h>

#include "libspread/analysis/accuracy/accuracy.hpp"
#include "libspread/analysis/accuracy/launch_set.hpp"
#include "libspread/analysis/accuracy/stopwatch.hpp"
#include "libspread/physics/launch/analytic_launch.hpp"
#include "libspread/analysis/predict/predictor.hpp"
#include "libspread/io/tables/table_writer.hpp"

namespace spread::accuracy {
namespace {

tables::TableContents make_table(const scene::Scene& scene, const scene::Material& material,
                                 const std::vector<double>& rpms, int samples) {
  tables::TableContents c;
  c.machine = scene::table_machine(scene.machine);
  c.materials = {material};
  launch::AnalyticLaunchOptions lo;
  lo.spin = scene.sweep.spin_model;
  for (double rpm : rpms) {
    tables::Run run;
    run.material = material.name;
    run.rpm = rpm;
    run.source = "analytic";
    run.samples = launch::analytic_launch_samples(scene.machine, material, rpm, scene.inlet, samples,
                                                  scene.numerics.seed, lo);
    run.particle_count = samples;
    run.scene_hash = scene.hash();
    run.scene_text = scene.provenance_text();
    run.effects = "analytic";
    run.software_version = "accuracy-study";
    run.created_utc = "1970-01-01T00:00:00Z";  // fixed: the size must not depend on the clock
    run.stats_json = "{}";
    run.convergence_json = "[]";
    c.runs.push_back(std::move(run));
  }
  return c;
}

// Bytes of the table as a SQLite file (written to a scratch file and removed).
std::uintmax_t table_bytes(const tables::TableContents& c, const std::string& scratch) {
  std::filesystem::remove(scratch);
  {
    tables::TableWriter w(scratch);
    w.write_machine(c.machine);
    w.write_materials(c.materials);
    for (const auto& run : c.runs) w.write_run(run);
  }
  const auto bytes = std::filesystem::file_size(scratch);
  std::filesystem::remove(scratch);
  return bytes;
}

struct Metrics {
  double throw_width = 0.0, r_bar = 0.0, working_width = 0.0;
};

Metrics predict_metrics(predict::Predictor& p, const std::string& material, double rpm, double* time_s,
                        double min_time_s) {
  predict::PredictionRequest req;
  req.material = material;
  req.rpm = rpm;
  req.effects = flight::kDrag | flight::kMagnus | flight::kSpinDecay;
  predict::Prediction out;
  if (p.predict(req, out) != predict::PredictStatus::kOk) throw std::runtime_error("accuracy: prediction refused");
  // The working width as the first band's upper end: the headline may switch to a wider band once the
  // samples establish it (docs/metrics.md "Effective working width"), which is another quantity.
  Metrics m{out.throw_width_m, out.mean_radius_m, out.first_band_width_to_and_fro_m};
  if (time_s != nullptr) *time_s = detail::median_time_s([&] { (void)p.predict(req, out); }, min_time_s);
  return m;
}

}  // namespace

// The analytic source flies no granule scatter: at the bundled scene's drop point (turned so that each
// disc's fan crosses the centre line) its pattern is an M whose first band of bout widths ends at shallow
// dips that open and close with the sample count (the DEM's scatter fills them), so the working width there
// measures the dips, not the sampling error. The study turns the drop point back to this angle, where the
// analytic pattern's first band ends at a clear crossing.
constexpr double kStudyInletAngle_rad = 1.5;

Study table_study(const StudyOptions& options) {
  scene::Scene scene = detail::load_study_scene(options);
  scene.inlet.angle_rad = kStudyInletAngle_rad;
  const auto& material = detail::study_material(scene, options);
  const double lo = 450.0, hi = 750.0;
  const std::vector<double> spacings =
      options.quick ? std::vector<double>{0, 150, 75} : std::vector<double>{0, 150, 100, 75, 50, 25};
  const std::vector<int> sample_counts =
      options.quick ? std::vector<int>{125, 500, 2000} : std::vector<int>{125, 250, 500, 1000, 2000, 4000};
  // Off every grid above (the worst case of interpolation is between rows).
  const std::vector<double> test_rpms =
      options.quick ? std::vector<double>{560, 690} : std::vector<double>{480, 560, 615, 690};
  const int direct_samples = options.quick ? 8192 : 16384;
  const double min_time_s = options.quick ? 0.02 : 0.2;
  const std::string scratch =
      (std::filesystem::temp_directory_path() / ("spread-accuracy-" + std::to_string(::getpid()) + ".sqlite")).string();

  std::vector<Metrics> direct;
  for (double rpm : test_rpms) {
    predict::Predictor p(make_table(scene, material, {rpm}, direct_samples));
    direct.push_back(predict_metrics(p, material.name, rpm, nullptr, 0.0));
  }

  Study st;
  st.name = "tables";
  st.title = "Tables: rpm spacing and samples per run";
  char buf[1200];
  std::snprintf(buf, sizeof buf,
                "`%s`, analytic tables (the drop point at inlet.angle_rad = %.2f rad: without the granules' "
                "scatter the scene's own drop point spreads an M whose first band ends at dips that come and go "
                "with the sample count) with rows every Δrpm from %.0f to %.0f rpm and n samples per row. Each "
                "table is loaded into a `predict::Predictor` and asked for %zu rpm between rows (",
                material.name.c_str(), kStudyInletAngle_rad, lo, hi, test_rpms.size());
  st.method = buf;
  for (std::size_t k = 0; k < test_rpms.size(); ++k) st.method += (k ? ", " : "") + cell(test_rpms[k]);
  std::snprintf(buf, sizeof buf,
                "); the direct computation is the same predictor on a one-row table made at exactly that rpm with "
                "%d samples. Errors are the worst over the test rpms: throw width (99 %% of the mass) and R̄ "
                "relative, the to-and-fro working width (CV <= 15 %%) in metres — it moves in 0.5 m tray steps, so "
                "its error is 0 or at least one tray. Time = median `predict()` CPU time (effects drag, Magnus, "
                "spin decay; both discs); size = bytes of the SQLite file.",
                direct_samples);
  st.method += buf;
  st.columns = {"rpm_spacing", "samples_per_run", "rows", "table_bytes", "predict_time_ms", "rel_error_throw_width",
                "rel_error_R_bar", "error_working_width_m", "error_throw_width_m"};

  struct Point {
    double spacing;
    int samples;
    double time_s, err_tw, err_r, err_ww, err_tw_m;
    std::uintmax_t bytes;
  };
  std::vector<Point> points;
  std::vector<Series> series;
  for (double spacing : spacings) {
    // Spacing 0: one row at exactly each test rpm — the sampling error alone, no interpolation.
    std::vector<double> rpms;
    for (double r = lo; spacing > 0.0 && r <= hi + 1e-9; r += spacing) rpms.push_back(r);
    Series s{spacing > 0.0 ? "drpm " + cell(spacing) : "row at the exact rpm", {}, {}};
    for (int n : sample_counts) {
      const tables::TableContents contents = make_table(scene, material, spacing > 0.0 ? rpms : test_rpms, n);
      const std::uintmax_t bytes = table_bytes(contents, scratch);
      predict::Predictor p(contents);
      Point pt{spacing, n, 0.0, 0.0, 0.0, 0.0, 0.0, bytes};
      for (std::size_t k = 0; k < test_rpms.size(); ++k) {
        double t = 0.0;
        const Metrics m = predict_metrics(p, material.name, test_rpms[k], &t, min_time_s);
        pt.time_s += t / static_cast<double>(test_rpms.size());
        pt.err_tw = std::max(pt.err_tw, std::abs(m.throw_width - direct[k].throw_width) / direct[k].throw_width);
        pt.err_r = std::max(pt.err_r, std::abs(m.r_bar - direct[k].r_bar) / direct[k].r_bar);
        pt.err_ww = std::max(pt.err_ww, std::abs(m.working_width - direct[k].working_width));
        pt.err_tw_m = std::max(pt.err_tw_m, std::abs(m.throw_width - direct[k].throw_width));
      }
      points.push_back(pt);
      st.figures["error_" + (spacing > 0.0 ? cell(spacing) : std::string("exact")) + "_" + std::to_string(n)] =
          std::max(pt.err_tw, pt.err_r);
      st.rows.push_back({spacing > 0.0 ? cell(spacing) : "exact", std::to_string(n), std::to_string(spacing > 0.0 ? rpms.size() : test_rpms.size()), std::to_string(bytes),
                         cell(pt.time_s * 1e3), cell(pt.err_tw), cell(pt.err_r), cell(pt.err_ww), cell(pt.err_tw_m)});
      s.x.push_back(pt.time_s * 1e3);
      s.y.push_back(std::max(std::max(pt.err_tw, pt.err_r), 1e-16));
      if (options.progress) {
        *options.progress << "tables drpm " << spacing << " n " << n << ": throw width error " << pt.err_tw
                          << ", R error " << pt.err_r << ", " << pt.time_s * 1e3 << " ms, " << bytes << " B\n";
      }
    }
    series.push_back(s);
  }
  Plot plot;
  plot.file = "tables.png";
  plot.title = "Tables: worst of throw-width / R-bar error vs prediction time";
  plot.x_label = "prediction time (ms)";
  plot.y_label = "max relative error";
  plot.series = series;
  plot.threshold_y = kErrorBudget;
  st.plots.push_back(plot);
  // The same errors against the file size, one line per samples-per-run (x: the rpm spacing's bytes).
  Plot by_size;
  by_size.file = "tables_bytes.png";
  by_size.title = "Tables: worst of throw-width / R-bar error vs table size";
  by_size.x_label = "table size (bytes)";
  by_size.y_label = "max relative error";
  by_size.threshold_y = kErrorBudget;
  for (int n : sample_counts) {
    Series s{"n = " + std::to_string(n), {}, {}};
    for (const auto& pt : points) {
      if (pt.samples != n || pt.spacing == 0.0) continue;
      s.x.push_back(static_cast<double>(pt.bytes));
      s.y.push_back(std::max(std::max(pt.err_tw, pt.err_r), 1e-16));
    }
    by_size.series.push_back(s);
  }
  st.plots.push_back(by_size);

  // What the rpm spacing costs in error: analytic rows are the same launch model at another rpm, and the
  // predictor rescales a row to the requested rpm, so interpolation should add next to nothing to the
  // sampling error of a row at the exact rpm. Measured: the largest difference over the grid.
  double spacing_effect = 0.0;
  for (const auto& pt : points) {
    if (pt.spacing == 0.0) continue;
    for (const auto& ex : points) {
      if (ex.spacing == 0.0 && ex.samples == pt.samples) {
        spacing_effect = std::max({spacing_effect, std::abs(pt.err_r - ex.err_r), std::abs(pt.err_tw - ex.err_tw)});
      }
    }
  }
  st.figures["spacing_effect"] = spacing_effect;
  // The best throw-width error any measured setting reaches (why the criterion on it is one tray, not 1 %).
  double best_tw = std::numeric_limits<double>::infinity();
  int best_tw_samples = 0;
  for (const auto& pt : points) {
    if (pt.err_tw < best_tw) {
      best_tw = pt.err_tw;
      best_tw_samples = pt.samples;
    }
  }
  st.figures["best_throw_width_error"] = best_tw;

  // The criterion, explicit: R̄ within 1 % (continuous); throw width and working width within one 0.5 m
  // tray. Both widths are read off the tray grid, and the throw width (a 99 % tail quantile) is not
  // within 1 % of the direct value at any measured setting (best_tw above), so 1 % of it is below what
  // the trays resolve and what any affordable sample count reaches.
  const double tray_m = 0.5;
  st.figures["tray_m"] = tray_m;
  const Point* best = nullptr;
  for (const auto& pt : points) {
    if (pt.spacing == 0.0 || pt.err_r > kErrorBudget || pt.err_tw_m > tray_m || pt.err_ww > tray_m) continue;
    // Prediction time is proportional to the samples flown; compare samples first (timings are noisy),
    // then the table size.
    if (best == nullptr || pt.samples < best->samples || (pt.samples == best->samples && pt.bytes < best->bytes)) {
      best = &pt;
    }
  }
  char crit[900];
  std::snprintf(crit, sizeof crit,
                "- Criterion (not the plain 1 %% rule): R̄ within 1 %%, throw width and working width within one "
                "%.1f m tray of the direct computation. Why: the throw width (99 %% of the mass, a tail quantile) "
                "is at best %.2g %% off at any measured setting (n = %d), so 1 %% on it is out of reach of the "
                "measured sample counts and below what %.1f m trays resolve; the working width moves in whole "
                "trays.\n",
                tray_m, 100.0 * best_tw, best_tw_samples, tray_m);
  std::snprintf(buf, sizeof buf,
                "- rpm spacing: analytic rows are one launch model at different rpm and the predictor rescales "
                "a row to the requested rpm, so the spacing changes the error by at most %.2g %% (largest "
                "difference to the row at the exact rpm over the grid): for analytic tables it costs only file "
                "size, and its recommendation is simply the coarsest measured. The spacing of a DEM-source "
                "table is not measured here (too costly per row; tests/predict's DEM interpolation check, "
                "label long).\n",
                100.0 * spacing_effect);
  st.recommendation = std::string(crit) + buf;
  if (best != nullptr) {
    st.figures["recommended_samples"] = best->samples;
    st.figures["recommended_spacing"] = best->spacing;
    st.figures["recommended_error"] = std::max(best->err_tw, best->err_r);
    st.figures["recommended_error_r_bar"] = best->err_r;
    st.figures["recommended_error_throw_width_m"] = best->err_tw_m;
    st.figures["recommended_error_working_width_m"] = best->err_ww;
    st.figures["recommended_time_ms"] = best->time_s * 1e3;
    const int default_samples = scene.sweep.samples_per_run;
    double default_spacing = 0.0;
    for (std::size_t k = 1; k < scene.sweep.rpm.size(); ++k) {
      default_spacing = std::max(default_spacing, scene.sweep.rpm[k] - scene.sweep.rpm[k - 1]);
    }
    std::snprintf(buf, sizeof buf,
                  "- Cheapest within that criterion (fewest samples flown per prediction, then the smallest "
                  "file): **Δrpm %g with %d samples per run** (R̄ off by %.2g %%, throw width by %.2g m = %.2g %%, "
                  "working width by %.2g m; %.3g ms per prediction, %ju bytes). Prediction time is proportional "
                  "to the samples per run. `%s` builds its tables with %d samples per run at rows up to %g rpm "
                  "apart.\n",
                  best->spacing, best->samples, 100.0 * best->err_r, best->err_tw_m, 100.0 * best->err_tw,
                  best->err_ww, best->time_s * 1e3, best->bytes, scene.source_name.c_str(), default_samples,
                  default_spacing);
    st.recommendation += buf;
  } else {
    st.recommendation += "- No measured table setting is within 1 % on R̄ and one tray on the widths.\n";
  }
  return st;
}

}  // namespace spread::accuracy
