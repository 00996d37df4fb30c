#include "lookup_builder/run_source.hpp"

#include <nlohmann/json.hpp>

#include "libspread/core/source_revision.hpp"
#include "libspread/physics/launch/analytic_launch.hpp"
#include "libspread/physics/launch/launch_statistics.hpp"
#include "libspread/io/tables/table_writer.hpp"
#include "lookup_builder/dem_run.hpp"

namespace spread::lookup {

tables::Run analytic_run(const scene::Scene& scene, const scene::Material& material, double rpm) {
  launch::AnalyticLaunchOptions options;
  options.spin = scene.sweep.spin_model;
  tables::Run run;
  run.material = material.name;
  run.rpm = rpm;
  run.source = "analytic";
  run.samples = launch::analytic_launch_samples(scene.machine, material, rpm, scene.inlet, scene.sweep.samples_per_run,
                                                scene.numerics.seed, options);
  run.scene_text = scene.provenance_text();
  run.scene_hash = scene.hash();
  run.inputs_hash = scene.run_inputs_hash(material, rpm);
  // The analytic model is sliding on disc and vane; nothing else of the scene's effects ran.
  run.effects = std::string("analytic_vane_sliding,spin_") + scene::to_string(scene.sweep.spin_model);
  run.dt_contact_s = 0.0;
  run.dt_flight_s = 0.0;
  run.particle_count = static_cast<std::int64_t>(run.samples.size());
  run.software_version = std::string(SPREAD_VERSION_STRING) + "+" + source_revision();
  run.created_utc = tables::utc_now_iso8601();
  const double rim_speed_m_s = rpm * 2.0 * kPi / 60.0 * scene.machine.disc_radius_m;
  // The flight effects the scene asks for travel with the run: predictions from the table use them.
  nlohmann::json stats = nlohmann::json::parse(launch::to_json(launch::launch_statistics(run.samples, rim_speed_m_s)));
  stats["flight_effects"] = effect::to_string(scene.effects & effect::kFlightEffects);
  run.stats_json = stats.dump();
  run.convergence_json = "[]";
  return run;
}

std::vector<tables::Run> analytic_blend_runs(const scene::Scene& scene, const scene::Material& blend, double rpm) {
  std::vector<tables::Run> runs;
  for (const tables::BlendComponent& component : blend.components) {
    tables::Run run = analytic_run(scene, component.material, rpm);
    run.material = tables::blend_component_name(blend.name, component.material.name);
    run.inputs_hash = scene.run_inputs_hash(blend, rpm);
    runs.push_back(std::move(run));
  }
  return runs;
}

RunSource make_run_source(const scene::Scene& scene, int threads_per_run) {
  switch (scene.sweep.source) {
    case scene::LaunchSource::kAnalytic:
      return [&scene](const scene::Material& material, double rpm) {
        if (material.is_blend()) return analytic_blend_runs(scene, material, rpm);
        return std::vector<tables::Run>{analytic_run(scene, material, rpm)};
      };
    case scene::LaunchSource::kDem: {
      DemRunOptions options;
      options.threads = threads_per_run;
      return [&scene, options](const scene::Material& material, double rpm) {
        if (material.is_blend()) return dem_blend_runs(scene, material, rpm, options);
        return std::vector<tables::Run>{dem_run(scene, material, rpm, options)};
      };
    }
  }
  throw SourceUnavailableError(scene.source_name + ": sweep.source: unknown source");
}

}  // namespace spread::lookup
