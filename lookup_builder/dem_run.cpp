#include "lookup_builder/dem_run.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "libspread/core/source_revision.hpp"
#include "libspread/physics/dem/disc_run.hpp"
#include "libspread/physics/dem/scene_config.hpp"
#include "libspread/physics/dem/simulate.hpp"
#include "libspread/physics/launch/launch_statistics.hpp"
#include "libspread/analysis/metrics/metrics.hpp"
#include "libspread/io/tables/table_writer.hpp"
#include "lookup_builder/row_uncertainty.hpp"

namespace spread::lookup {
namespace {

double relative_change(double now, double before) {
  if (now == before) return 0.0;
  const double scale = std::max(std::abs(now), std::abs(before));
  return scale > 0.0 ? std::abs(now - before) / scale : 0.0;
}

// The launches flown so far and their landings; R̄/ξ are over every landed granule, exactly what
// dem::simulate reports for the same simulated time.
struct FlownLaunches {
  std::vector<double> x_m, y_m, mass_kg;
  std::size_t flown = 0;

  void fly_new(const std::vector<dem::LaunchRecord>& launches, const dem::SimulationConfig& cfg) {
    const std::size_t n = launches.size() - flown;
    if (n == 0) return;
    std::vector<flight::Granule> granules(n);
    std::vector<flight::State> states(n);
    std::vector<flight::Landing> landings(n);
    for (std::size_t k = 0; k < n; ++k) {
      const dem::LaunchRecord& l = launches[flown + k];
      granules[k].diameter_m = l.diameter_m;
      granules[k].density_kg_m3 = cfg.materials[static_cast<std::size_t>(l.material)].density_kg_m3;
      states[k].position_m = l.position_m;
      states[k].velocity_m_s = l.velocity_m_s;
      states[k].spin_rad_s = l.spin_rad_s;
    }
    flight::fly_batch(granules, states, -cfg.disc_height_m, cfg.air, cfg.flight_effects, cfg.flight_settings,
                      landings, cfg.flight_threads);
    for (std::size_t k = 0; k < n; ++k) {
      if (!landings[k].landed) continue;
      x_m.push_back(landings[k].state.position_m.x());
      y_m.push_back(landings[k].state.position_m.y());
      mass_kg.push_back(launches[flown + k].mass_kg);
    }
    flown = launches.size();
  }
};

tables::LaunchSample normalised(const dem::LaunchRecord& l, double omega_rad_s, double rim_speed_m_s) {
  tables::LaunchSample s{};
  s.x_m = static_cast<float>(l.position_m.x());
  s.y_m = static_cast<float>(l.position_m.y());
  s.z_m = static_cast<float>(l.position_m.z());
  s.t_s = static_cast<float>(l.residence_s);  // since the granule was fed (released at the inlet)
  s.vx_norm = static_cast<float>(l.velocity_m_s.x() / rim_speed_m_s);
  s.vy_norm = static_cast<float>(l.velocity_m_s.y() / rim_speed_m_s);
  s.vz_norm = static_cast<float>(l.velocity_m_s.z() / rim_speed_m_s);
  s.wx_norm = static_cast<float>(l.spin_rad_s.x() / omega_rad_s);
  s.wy_norm = static_cast<float>(l.spin_rad_s.y() / omega_rad_s);
  s.wz_norm = static_cast<float>(l.spin_rad_s.z() / omega_rad_s);
  s.diameter_m = static_cast<float>(l.diameter_m);
  s.mass_kg = static_cast<float>(l.mass_kg);
  return s;
}

}  // namespace

const char* to_string(DemStop stop) {
  switch (stop) {
    case DemStop::kConverged: return "converged";
    case DemStop::kParticleBudget: return "particle_budget";
    case DemStop::kTimeBudget: return "time_budget";
  }
  return "unknown";
}

std::string convergence_to_json(const std::vector<ConvergencePoint>& history) {
  nlohmann::json out = nlohmann::json::array();
  for (const ConvergencePoint& p : history) {
    out.push_back({{"simulated_s", p.simulated_s},
                   {"launched", p.launched},
                   {"mean_radius_m", p.mean_radius_m},
                   {"radial_width_m", p.radial_width_m},
                   {"change_mean_radius", p.change_mean_radius},
                   {"change_radial_width", p.change_radial_width}});
    if (std::isfinite(p.working_width_ci_m)) out.back()["working_width_ci_m"] = p.working_width_ci_m;
  }
  return out.dump();
}

namespace {

// The run of the (material, rpm) and, per launch sample, the index of the material its granule was (a
// blend's component; 0 for a single material).
struct DemLaunches {
  tables::Run run;
  std::vector<int> material_of_sample;
};

DemLaunches dem_launches(const scene::Scene& scene, const scene::Material& material, double rpm,
                         const DemRunOptions& options) {
  scene::Scene at_rpm = scene;
  at_rpm.machine.rpm = rpm;
  dem::SimulationConfig cfg = dem::config_from_scene(at_rpm, material.name);
  if (options.threads > 0) {
    cfg.engine.threads = options.threads;
    cfg.flight_threads = options.threads;
  }
  const scene::Sweep& sweep = scene.sweep;

  // The same disc run as dem::simulate()'s, stopped at batch ends: at a stop time T the launches are the
  // ones `spread simulate --set numerics.duration_s=T` produces (same inlet, same steps).
  dem::DiscRun disc_run(cfg);
  const dem::DemEngine& engine = disc_run.engine();
  const dem::Inlet& inlet = disc_run.inlet();

  // The run's samples (normalised launches) with the flight effects a prediction uses.
  const auto run_of = [&](const std::vector<dem::LaunchRecord>& launches) {
    const double omega_rad_s = std::abs(rpm) * 2.0 * kPi / 60.0;
    const double rim_speed_m_s = omega_rad_s * scene.machine.disc_radius_m;
    tables::Run r;
    r.material = material.name;
    r.rpm = rpm;
    r.source = "dem";
    r.samples.reserve(launches.size());
    for (const dem::LaunchRecord& l : launches) r.samples.push_back(normalised(l, omega_rad_s, rim_speed_m_s));
    r.stats_json = nlohmann::json{{"flight_effects", flight::effects_to_string(cfg.flight_effects)}}.dump();
    return r;
  };
  FlownLaunches flown;
  std::vector<ConvergencePoint> history;
  DemStop stop = DemStop::kTimeBudget;
  const std::size_t budget = sweep.particle_budget > 0 ? static_cast<std::size_t>(sweep.particle_budget) : 0;
  const std::size_t min_launches = static_cast<std::size_t>(sweep.samples_per_run);
  for (int batch = 1;; ++batch) {
    const double batch_end_s = std::min(cfg.duration_s, batch * sweep.batch_s);
    while (disc_run.before(batch_end_s)) {
      disc_run.step();
      if (budget > 0 && engine.launches().size() >= budget) break;
    }
    flown.fly_new(engine.launches(), cfg);
    const metrics::RadialStats rs = metrics::radial_statistics(flown.x_m, flown.y_m, flown.mass_kg, 0.0, 0.0);
    ConvergencePoint point;
    point.simulated_s = engine.time_s();
    point.launched = static_cast<std::int64_t>(engine.launches().size());
    point.mean_radius_m = rs.mean_radius_m;
    point.radial_width_m = rs.radial_width_m;
    const bool has_previous = !history.empty() && history.back().launched > 0;
    point.change_mean_radius = has_previous ? relative_change(rs.mean_radius_m, history.back().mean_radius_m) : 1.0;
    point.change_radial_width =
        has_previous ? relative_change(rs.radial_width_m, history.back().radial_width_m) : 1.0;
    history.push_back(point);

    const std::size_t launched = engine.launches().size();
    if (launched > 0 && launched >= min_launches && point.change_mean_radius <= sweep.convergence_tolerance &&
        point.change_radial_width <= sweep.convergence_tolerance) {
      // The answer's uncertainty, when the scene asks for it: R̄ and ξ settle long before the working
      // width does where CV(W) meets the target at a shallow angle.
      bool precise = true;
      if (sweep.working_width_ci_m > 0.0 && !material.is_blend()) {
        tables::Run so_far = run_of(engine.launches());
        const double ci_m = row_working_width_ci_m(scene::table_machine(scene.machine), material, so_far);
        history.back().working_width_ci_m = ci_m;
        precise = !(ci_m > sweep.working_width_ci_m);  // NaN (no working width): nothing to wait for
      }
      if (precise) {
        stop = DemStop::kConverged;
        break;
      }
    }
    if (budget > 0 && launched >= budget) {
      stop = DemStop::kParticleBudget;
      break;
    }
    if (!disc_run.before(cfg.duration_s)) {
      stop = DemStop::kTimeBudget;
      break;
    }
  }

  const std::vector<dem::LaunchRecord>& launches = engine.launches();
  if (launches.empty()) {
    throw std::runtime_error(scene.source_name + ": " + material.name + " @ " + std::to_string(rpm) +
                             " rpm: no granule launched within numerics.duration_s = " +
                             std::to_string(cfg.duration_s) + " s (raise it)");
  }
  tables::Run run = run_of(launches);
  const double rim_speed_m_s = std::abs(rpm) * 2.0 * kPi / 60.0 * scene.machine.disc_radius_m;
  run.scene_text = scene.provenance_text();
  run.scene_hash = scene.hash();
  run.inputs_hash = scene.run_inputs_hash(material, rpm);
  run.effects = effect::to_string(scene.effects);
  run.dt_contact_s = engine.dt_s();
  run.dt_flight_s = cfg.flight_settings.dt_s;
  run.particle_count = static_cast<std::int64_t>(inlet.released());
  run.software_version = std::string(SPREAD_VERSION_STRING) + "+" + source_revision();
  run.created_utc = tables::utc_now_iso8601();

  // Launch statistics (same keys as the analytic source) plus what the DEM run did. No wall times:
  // the stats of a run are part of its deterministic content.
  nlohmann::json stats = nlohmann::json::parse(launch::to_json(launch::launch_statistics(run.samples, rim_speed_m_s)));
  const ConvergencePoint& last = history.back();
  stats["mean_radius_m"] = last.mean_radius_m;
  stats["radial_width_m"] = last.radial_width_m;
  stats["stop"] = to_string(stop);
  stats["simulated_s"] = last.simulated_s;
  stats["released"] = inlet.released();
  stats["launched"] = launches.size();
  stats["landed"] = flown.mass_kg.size();
  stats["on_disc_at_end"] = engine.active_count();
  stats["lost"] = engine.stats().lost;
  stats["particle_steps"] = engine.stats().particle_steps;
  stats["contact_time_s"] = engine.contact_time_s();
  stats["batch_s"] = sweep.batch_s;
  stats["convergence_tolerance"] = sweep.convergence_tolerance;
  stats["particle_budget"] = sweep.particle_budget;
  stats["flight_effects"] = flight::effects_to_string(cfg.flight_effects);
  if (sweep.working_width_ci_m > 0.0) stats["working_width_ci_target_m"] = sweep.working_width_ci_m;
  run.stats_json = stats.dump();
  run.convergence_json = convergence_to_json(history);
  DemLaunches out{std::move(run), {}};
  out.material_of_sample.reserve(launches.size());
  for (const dem::LaunchRecord& l : launches) out.material_of_sample.push_back(l.material);
  return out;
}

}  // namespace

tables::Run dem_run(const scene::Scene& scene, const scene::Material& material, double rpm,
                    const DemRunOptions& options) {
  if (material.is_blend()) throw std::invalid_argument("dem_run: " + material.name + " is a blend (dem_blend_runs)");
  return dem_launches(scene, material, rpm, options).run;
}

std::vector<tables::Run> dem_blend_runs(const scene::Scene& scene, const scene::Material& blend, double rpm,
                                        const DemRunOptions& options) {
  const DemLaunches mixed = dem_launches(scene, blend, rpm, options);
  return split_blend_run(mixed.run, mixed.material_of_sample, blend);
}

std::vector<tables::Run> split_blend_run(const tables::Run& mixed, std::span<const int> component_of_sample,
                                         const scene::Material& blend) {
  if (component_of_sample.size() != mixed.samples.size())
    throw std::invalid_argument("split_blend_run: one component index per launch sample is needed");
  std::vector<tables::Run> runs(blend.components.size());
  for (std::size_t k = 0; k < runs.size(); ++k) {
    tables::Run& r = runs[k];
    r = mixed;
    r.samples.clear();
    r.material = tables::blend_component_name(blend.name, blend.components[k].material.name);
  }
  for (std::size_t i = 0; i < mixed.samples.size(); ++i) {
    const int k = component_of_sample[i];
    if (k < 0 || static_cast<std::size_t>(k) >= runs.size())
      throw std::invalid_argument("split_blend_run: launch " + std::to_string(i) + " has no component of the blend");
    runs[static_cast<std::size_t>(k)].samples.push_back(mixed.samples[i]);
  }
  for (std::size_t k = 0; k < runs.size(); ++k) {
    // The mixed stream's statistics stay (the run's convergence is the stream's); this row's own are named.
    nlohmann::json stats = nlohmann::json::parse(runs[k].stats_json);
    stats["blend"] = blend.name;
    stats["blend_component"] = k;
    stats["component_launched"] = runs[k].samples.size();
    runs[k].stats_json = stats.dump();
    if (runs[k].samples.empty()) {
      throw std::runtime_error(mixed.material + " @ " + std::to_string(mixed.rpm) + " rpm: no granule of component " +
                               blend.components[k].material.name + " launched (raise numerics.duration_s or sweep.samples_per_run)");
    }
  }
  return runs;
}

}  // namespace spread::lookup
