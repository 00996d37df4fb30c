// Flight study: landing-point error of fixed-step RK4 (Δt_f 0.1–20 ms) and adaptive Dormand–Prince 5(4)
// (several tolerances) against a very tight Dormand–Prince reference (rel/abs 1e-11), against the wall
// time per trajectory. Launches: analytic launch samples of the study scene at the study rpm.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "libspread/analysis/accuracy/accuracy.hpp"
#include "libspread/analysis/accuracy/launch_set.hpp"
#include "libspread/analysis/accuracy/stopwatch.hpp"
#include "libspread/physics/dem/scene_config.hpp"
#include "libspread/analysis/predict/flight_defaults.hpp"

namespace spread::accuracy {
namespace {

struct FlightPoint {
  std::string scheme;        // "rk4" | "dopri5"
  double knob = 0.0;         // RK4: Δt (s); dopri5: tolerance
  // "" for a grid point; else which product default this row measures: "predictor default"
  // (predict::default_flight_settings) or "scene default" (the study scene's numerics as
  // dem::config_from_scene turns them into the DEM run's flight settings).
  std::string role;
  flight::Settings settings;
  double max_error_m = 0.0, mean_error_m = 0.0, max_rel_error = 0.0;
  double time_per_flight_s = 0.0, mean_steps = 0.0;
};

}  // namespace

Study flight_study(const StudyOptions& options) {
  const scene::Scene scene = detail::load_study_scene(options);
  const auto& material = detail::study_material(scene, options);
  const int count = options.quick ? 16 : 64;
  const detail::LaunchSet set = detail::make_launch_set(scene, material, options.rpm, count, scene.numerics.seed);
  const std::size_t n = set.launches.size();

  // Reference landings.
  std::vector<Vec3> reference(n);
  const flight::Settings ref_settings = predict::reference_flight_settings();
  for (std::size_t k = 0; k < n; ++k) {
    reference[k] = flight::fly_to_ground(set.granules[k], set.launches[k], 0.0, set.air, set.effects, ref_settings)
                       .state.position_m;
  }

  std::vector<FlightPoint> points;
  const std::vector<double> dts_ms = options.quick ? std::vector<double>{0.5, 1, 2, 5, 10, 20}
                                                   : std::vector<double>{0.1, 0.2, 0.5, 1, 2, 5, 10, 20};
  for (double dt_ms : dts_ms) {
    FlightPoint p{"rk4", dt_ms * 1e-3, "", predict::fixed_step_rk4_settings(dt_ms * 1e-3)};
    points.push_back(p);
  }
  const std::vector<double> tols = options.quick ? std::vector<double>{1e-2, 1e-3, 1e-4, 1e-6}
                                                 : std::vector<double>{1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8};
  const flight::Settings current = predict::default_flight_settings();
  for (double tol : tols) {
    flight::Settings s = current;  // the predictor's first trial step and limits, tolerance varied
    s.rel_tol = tol;
    s.abs_tol = tol;
    points.push_back({"dopri5", tol, "", s});
  }
  points.push_back({"dopri5", current.rel_tol, "predictor default", current});
  // The scene's flight settings as a DEM run (`spread simulate`) uses them: numerics.flight_scheme,
  // flight_dt_s and flight_tolerance (relative; the absolute tolerance stays flight::Settings' default).
  const flight::Settings scene_flight = dem::config_from_scene(scene, options.material).flight_settings;
  const bool scene_is_rk4 = scene_flight.scheme == flight::Scheme::kRk4;
  points.push_back({scene_is_rk4 ? "rk4" : "dopri5", scene_is_rk4 ? scene_flight.dt_s : scene_flight.rel_tol,
                    "scene default", scene_flight});

  const double min_time_s = options.quick ? 0.02 : 0.3;
  // Warm-up (caches, CPU clock) so the first timed setting is not penalised.
  for (std::size_t k = 0; k < n; ++k) {
    (void)flight::fly_to_ground(set.granules[k], set.launches[k], 0.0, set.air, set.effects, points.back().settings);
  }
  for (auto& p : points) {
    double steps = 0.0, sum_err = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      const flight::Landing l =
          flight::fly_to_ground(set.granules[k], set.launches[k], 0.0, set.air, set.effects, p.settings);
      const Vec3 d = l.state.position_m - reference[k];
      const double err = std::hypot(d.x(), d.y());
      const double radius = std::hypot(reference[k].x(), reference[k].y());
      p.max_error_m = std::max(p.max_error_m, err);
      p.max_rel_error = std::max(p.max_rel_error, err / radius);
      sum_err += err;
      steps += l.steps + l.rejected_steps;
    }
    p.mean_error_m = sum_err / static_cast<double>(n);
    p.mean_steps = steps / static_cast<double>(n);
    double sink = 0.0;
    p.time_per_flight_s = detail::median_time_s(
                              [&] {
                                for (std::size_t k = 0; k < n; ++k) {
                                  sink += flight::fly_to_ground(set.granules[k], set.launches[k], 0.0, set.air,
                                                                set.effects, p.settings)
                                              .flight_time_s;
                                }
                              },
                              min_time_s) /
                          static_cast<double>(n);
    if (options.progress) {
      *options.progress << "flight " << p.scheme << " " << p.knob << (p.role.empty() ? "" : " (" + p.role + ")")
                        << ": max error " << p.max_error_m << " m, " << p.time_per_flight_s * 1e6 << " us\n";
    }
    if (sink < 0.0) p.mean_steps = -1.0;  // keeps the timed flights from being optimised away
  }

  Study st;
  st.name = "flight";
  st.title = "Flight integrator: landing-point error against time per trajectory";
  char buf[1600];
  std::snprintf(buf, sizeof buf,
                "%zu launches of `%s` at %.0f rpm (analytic launch samples of `%s`, effects drag, Magnus, spin "
                "decay, disc %.2f m above the ground) flown with each setting. Error = horizontal distance between "
                "the landing point and that of the reference (Dormand–Prince, rel/abs tolerance 1e-11); relative "
                "error = that distance / the reference landing radius from the disc centre (worst launch). Time = "
                "median CPU time per trajectory; \"cheapest\" ranks settings of one scheme by steps per trajectory "
                "(deterministic), schemes by time. Dormand–Prince grid rows use rel = abs tolerance and the predictor's "
                "first trial step; the two default rows are the settings as the product uses them (predictor: "
                "`predict::default_flight_settings()`; scene: `dem::config_from_scene`, the flight of `spread "
                "simulate`).",
                n, material.name.c_str(), options.rpm, scene.source_name.c_str(), scene.machine.disc_height_m);
  st.method = buf;
  st.columns = {"scheme", "dt_s_or_tol", "max_error_m", "mean_error_m", "max_rel_error", "time_per_flight_us",
                "steps_per_flight"};
  Series rk4{"RK4 (label: dt)", {}, {}}, dp{"Dormand-Prince (label: tol)", {}, {}};
  for (const auto& p : points) {
    st.rows.push_back({p.scheme + (p.role.empty() ? "" : " (" + p.role + ")"), cell(p.knob), cell(p.max_error_m),
                       cell(p.mean_error_m), cell(p.max_rel_error), cell(p.time_per_flight_s * 1e6),
                       cell(p.mean_steps)});
    if (!p.role.empty()) continue;
    Series& s = p.scheme == "rk4" ? rk4 : dp;
    s.x.push_back(p.time_per_flight_s * 1e6);
    s.y.push_back(std::max(p.max_rel_error, 1e-16));
  }
  Plot plot;
  plot.file = "flight.png";
  plot.title = "Flight: worst landing error vs time per trajectory";
  plot.x_label = "time per trajectory (us)";
  plot.y_label = "max relative landing error";
  plot.series = {rk4, dp};
  plot.threshold_y = kErrorBudget;
  st.plots.push_back(plot);

  // Observed order of RK4: least-squares slope of log(error) over log(Δt) on the points whose error is
  // at least 10× the smallest RK4 error (the floor set by the float32 launch samples, round-off and the
  // reference's own tolerance, reached below a few ms).
  double floor_m = std::numeric_limits<double>::infinity();
  for (const auto& p : points) {
    if (p.scheme == "rk4") floor_m = std::min(floor_m, p.max_error_m);
  }
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int m = 0;
  for (const auto& p : points) {
    if (p.scheme != "rk4" || !(p.max_error_m > 10.0 * floor_m)) continue;
    const double x = std::log(p.knob), y = std::log(p.max_error_m);
    sx += x; sy += y; sxx += x * x; sxy += x * y; ++m;
  }
  st.figures["rk4_order"] = m >= 2 ? (m * sxy - sx * sy) / (m * sxx - sx * sx) : std::nan("");

  // Cheapest within budget: relative (1 % of the landing radius) and the predictor's absolute 1 cm.
  // Within one scheme the cost is ranked by the steps per trajectory (deterministic; timings of settings
  // a few percent apart swap on a loaded machine), between schemes by the measured time.
  auto cheapest = [&](auto&& ok) -> const FlightPoint* {
    const FlightPoint* best = nullptr;
    for (const auto& p : points) {
      if (!p.role.empty() || !ok(p)) continue;
      const bool cheaper = best == nullptr ||
                           (p.scheme == best->scheme ? p.mean_steps < best->mean_steps
                                                     : p.time_per_flight_s < best->time_per_flight_s);
      if (cheaper) best = &p;
    }
    return best;
  };
  const FlightPoint* rel = cheapest([](const FlightPoint& p) { return p.max_rel_error <= kErrorBudget; });
  const FlightPoint* both = cheapest(
      [](const FlightPoint& p) { return p.max_rel_error <= kErrorBudget && p.max_error_m <= 0.01; });
  const FlightPoint* cm = cheapest([](const FlightPoint& p) { return p.max_error_m <= 0.01; });
  const FlightPoint& def = points[points.size() - 2];
  const FlightPoint& scene_def = points.back();
  st.figures["default_max_error_m"] = def.max_error_m;
  st.figures["default_time_us"] = def.time_per_flight_s * 1e6;
  st.figures["scene_default_max_error_m"] = scene_def.max_error_m;
  auto describe = [](const FlightPoint* p) {
    if (p == nullptr) return std::string("none of the measured settings");
    char b[200];
    std::snprintf(b, sizeof b, "%s %s %.3g (worst error %.3g m = %.3g %%, %.3g us per trajectory)", p->scheme.c_str(),
                  p->scheme == "rk4" ? "dt" : "tol", p->knob, p->max_error_m, 100.0 * p->max_rel_error,
                  p->time_per_flight_s * 1e6);
    return std::string(b);
  };
  if (both != nullptr) {
    st.figures["recommended_rel_error"] = both->max_rel_error;
    st.figures["recommended_error_m"] = both->max_error_m;
    st.figures["recommended_time_us"] = both->time_per_flight_s * 1e6;
    st.figures["recommended_is_rk4"] = both->scheme == "rk4" ? 1.0 : 0.0;
    st.figures["recommended_knob"] = both->knob;
  }
  if (cm != nullptr) {
    st.figures["cm_max_error_m"] = cm->max_error_m;
    st.figures["cm_knob"] = cm->knob;
    st.figures["cm_is_rk4"] = cm->scheme == "rk4" ? 1.0 : 0.0;
  }
  std::snprintf(buf, sizeof buf, "Observed RK4 order (slope of log error over log Δt on the points >= 10x the error floor): %.2f.\n\n",
                st.figures["rk4_order"]);
  st.recommendation = std::string(buf) + "- Cheapest within 1 % of the landing radius: " + describe(rel) +
                      ".\n- Cheapest within 1 cm (the predictor's documented accuracy, 2 % of a 0.5 m tray): " +
                      describe(cm) + ".\n- **Recommended default** (cheapest within both): " + describe(both) +
                      ".\n- Predictor default (`libspread/analysis/predict/flight_defaults.cpp`, rel = abs tolerance): " +
                      describe(&def) + ".\n- Scene default for DEM runs (`" + scene.source_name +
                      "` numerics, relative tolerance " + cell(scene_flight.rel_tol) + ", absolute " +
                      cell(scene_flight.abs_tol) + ", first trial step " + cell(scene_flight.dt_s) +
                      " s): " + describe(&scene_def) + ".\n";
  return st;
}

}  // namespace spread::accuracy
