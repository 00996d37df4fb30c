// Partitioned vs monolithic (seed Sect. 3.1, Eq. 49): the full process on the study scene's disc, once
// partitioned (launched granules leave the DEM and fly in the flight module at their own step) and once
// monolithic (launched granules stay in the DEM loop at Δt_c until they land), with the measured saving
// in steps and in wall time next to C_r = (1 − 1/N_fc) / (1 + T_c/T_f) from the same run's T_c, T_f, N_fc.
// Both runs integrate drag + gravity only in flight, so they solve the same physics. Too slow for
// --quick (a short disc run is tens of seconds): the quick report quotes docs/dem.md's benchmark.
#include <cstdio>

#include "libspread/analysis/accuracy/accuracy.hpp"
#include "libspread/analysis/accuracy/launch_set.hpp"
#include "libspread/analysis/accuracy/monolithic_reference.hpp"
#include "libspread/physics/dem/scene_config.hpp"
#include "libspread/physics/dem/simulate.hpp"

namespace spread::accuracy {

Study partition_study(const StudyOptions& options) {
  Study st;
  st.name = "partition";
  st.title = "Partitioned vs monolithic DEM (Eq. 49)";
  st.columns = {"scheme", "simulated_s", "launched", "on_disc_particle_steps", "flight_steps", "wall_time_s",
                "dt_contact_s", "T_c_s", "T_f_s", "N_fc", "saving_steps", "saving_wall", "C_r_eq49"};
  if (options.quick) {
    st.method =
        "Not run in `--quick` (a disc run long enough for granules to launch takes tens of seconds). The "
        "benchmark in docs/dem.md (`build/bench/bench_dem`, scenes/case1.toml, 0.4 s, analytic disc, on a "
        "loaded machine) measured a saving of 77 % in steps and 39 % in wall time against C_r = 0.80 from "
        "Eq. 49.";
    st.recommendation = "- Keep the partitioned scheme (the default of `dem::simulate`).\n";
    return st;
  }
  const scene::Scene scene = detail::load_study_scene(options);
  dem::SimulationConfig c = dem::config_from_scene(scene, options.material);
  c.duration_s = 0.2;
  c.engine.threads = 1;
  c.flight_threads = 1;
  c.flight_effects = flight::kDrag;
  c.vtk_prefix.clear();
  const dem::SimulationResult part = dem::simulate(c);
  dem::SimulationConfig cm = c;
  cm.fly = false;
  const MonolithicResult monolithic = simulate_monolithic(cm);
  const dem::SimulationResult& mono = monolithic.run;

  const PartitionSaving eq49 = predicted_saving(part);
  const double t_c = eq49.t_c_s, t_f = eq49.t_f_s, n_fc = eq49.n_fc, c_r = eq49.c_r;
  const double steps_part = static_cast<double>(part.particle_steps + part.flight_steps);
  const double steps_mono = static_cast<double>(mono.particle_steps + monolithic.flight_particle_steps);
  const double saving_steps = 1.0 - steps_part / steps_mono;
  const double saving_wall = 1.0 - part.wall_time_s / mono.wall_time_s;
  st.rows.push_back({"partitioned", cell(c.duration_s), std::to_string(part.launches.size()),
                     std::to_string(part.particle_steps), std::to_string(part.flight_steps), cell(part.wall_time_s),
                     cell(part.dt_contact_s), cell(t_c), cell(t_f), cell(n_fc), cell(saving_steps),
                     cell(saving_wall), cell(c_r)});
  st.rows.push_back({"monolithic", cell(c.duration_s), std::to_string(mono.launches.size()),
                     std::to_string(mono.particle_steps), std::to_string(monolithic.flight_particle_steps),
                     cell(mono.wall_time_s), cell(mono.dt_contact_s), cell(std::nan("")), cell(std::nan("")),
                     cell(std::nan("")), cell(std::nan("")), cell(std::nan("")), cell(std::nan(""))});
  st.figures["saving_steps"] = saving_steps;
  st.figures["saving_wall"] = saving_wall;
  st.figures["C_r"] = c_r;
  char buf[1400];
  std::snprintf(buf, sizeof buf,
                "`%s` (disc model %s, N_c %d), %.2f s of feed, one thread, flight with drag only in both "
                "schemes. The partitioned run flies launched granules with the scene's flight integrator; the "
                "monolithic run keeps them in the DEM loop at Δt_c = %.3g s until they land. Steps = on-disc "
                "particle-steps + flight steps (monolithic: DEM steps of flying granules). docs/dem.md's "
                "benchmark (`bench_dem`: scenes/case1.toml, 0.4 s of feed, another run on a loaded machine) "
                "measured the same step saving (77 %%) but 39 %% in wall time: the wall saving depends on the "
                "run length (the share of granules in flight at the end) and on the machine load during each of "
                "the two runs, the step saving far less.",
                scene.source_name.c_str(), scene::to_string(scene.machine.disc_model), scene.numerics.steps_per_contact,
                c.duration_s, part.dt_contact_s);
  st.method = buf;
  std::snprintf(buf, sizeof buf,
                "- Measured saving: **%.0f %% of the steps, %.0f %% of the wall time**; Eq. 49 gives C_r = %.2f "
                "(T_c = %.3f s, T_f = %.3f s, N_fc = %.3g). The step saving falls short of C_r because granules "
                "still on the disc at the end cost the same in both schemes; the wall saving is smaller still "
                "because a free-flight DEM step is far cheaper than an on-disc contact step. Keep the "
                "partitioned scheme (the default).\n",
                100.0 * saving_steps, 100.0 * saving_wall, c_r, t_c, t_f, n_fc);
  st.recommendation = buf;
  if (options.progress) *options.progress << "partition: saving steps " << saving_steps << ", wall " << saving_wall << "\n";
  return st;
}

}  // namespace spread::accuracy
