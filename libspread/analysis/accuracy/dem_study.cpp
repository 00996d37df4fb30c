// DEM study on the cheap single-particle verification cases (a full disc is far too costly per point):
//  - steps per contact N_c: Patterson & Reece's vane (exit speed against the closed form) and a head-on
//    impact at e = 0.5 (measured restitution against the requested one, dem::run_impact);
//  - mesh size ξ (normalised by the cone radius, the seed's 0.002…0.02): Appendix-1 cone (dem::run_cone)
//    against its tight ODE reference, at the engine's default N_c;
//  - R̄ and ξ (Eqs. 51–52) of a short run of the study scene's whole disc (few granules, flown to the
//    ground) as N_c and the mesh size vary, against the finest run (N_c: the largest measured; mesh: the
//    analytic disc, the ξ → 0 limit).
// Cost = CPU time of one run of the case (single thread).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <filesystem>
#include <string>

#include "libspread/analysis/accuracy/accuracy.hpp"
#include "libspread/analysis/accuracy/launch_set.hpp"
#include "libspread/analysis/accuracy/stopwatch.hpp"
#include "libspread/analysis/accuracy/vane_at_contact_steps.hpp"
#include "libspread/physics/dem/engine.hpp"
#include "libspread/physics/dem/scene_config.hpp"
#include "libspread/physics/dem/simulate.hpp"
#include "libspread/io/scene/scene.hpp"

namespace spread::accuracy {
namespace {

struct DiscRun {
  double mean_radius_m = 0.0, radial_width_m = 0.0, cpu_s = 0.0, dt_s = 0.0;
  std::size_t launched = 0;
  double r_bar_noise = 0.0;  // 95 % half-width of R̄ from this run's sampling, 1.96·s_r/√N, relative to R̄
};

// One short run of the study scene's disc at N_c and mesh size ξ/R (0: the analytic disc), single thread.
DiscRun run_disc(const scene::Scene& scene, const StudyOptions& options, double duration_s, double contact_steps,
                 double mesh_per_radius) {
  dem::SimulationConfig c = dem::config_from_scene(scene, options.material);
  c.duration_s = duration_s;
  c.engine.threads = 1;
  c.flight_threads = 1;
  c.engine.contact_steps = contact_steps;
  c.engine.dt_s = 0.0;  // automatic: t_c / N_c
  c.disc.mesh_size_m = mesh_per_radius * scene.machine.disc_radius_m;
  c.vtk_prefix.clear();
  const auto start = detail::cpu_now();
  const dem::SimulationResult r = dem::simulate(c);
  DiscRun out;
  out.cpu_s = detail::seconds_since(start);
  out.mean_radius_m = r.mean_radius_m;
  out.radial_width_m = r.radial_width_m;
  out.dt_s = r.dt_contact_s;
  out.launched = r.launches.size();
  // Unweighted spread of the landing radii (origin = the disc centre, as R̄): the sampling noise of R̄.
  double sum = 0.0, sum2 = 0.0;
  std::size_t n = 0;
  for (const auto& l : r.landings) {
    if (!l.landed) continue;
    const double radius = std::hypot(l.state.position_m.x(), l.state.position_m.y());
    sum += radius;
    sum2 += radius * radius;
    ++n;
  }
  if (n > 1 && out.mean_radius_m > 0.0) {
    const double mean = sum / static_cast<double>(n);
    const double sd = std::sqrt(std::max(0.0, (sum2 - static_cast<double>(n) * mean * mean) / static_cast<double>(n - 1)));
    out.r_bar_noise = 1.96 * sd / std::sqrt(static_cast<double>(n)) / out.mean_radius_m;
  }
  return out;
}

// "scenes/case1.toml: 2.9 mm = 0.0100 R, ..." for the bundled scenes with a meshed disc (read from the
// source tree, so the report states what the files hold).
std::string bundled_mesh_sizes() {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(default_scene_path()).parent_path();
  std::string out;
  for (const char* name : {"default.toml", "case1.toml", "case2.toml", "case1_sweep.toml"}) {
    try {
      const scene::Scene sc = scene::load_scene_file((dir / name).string());
      if (sc.machine.disc_model != scene::DiscModel::kMesh) continue;
      char b[160];
      std::snprintf(b, sizeof b, "%sscenes/%s: %.2g mm = %.3g R", out.empty() ? "" : "; ", name,
                    1e3 * sc.machine.mesh_size_m, sc.machine.mesh_size_m / sc.machine.disc_radius_m);
      out += b;
    } catch (const std::exception&) {
      // A scene that does not load is reported by its own tests; the report just omits it.
    }
  }
  return out.empty() ? "no bundled scene uses a meshed disc" : out;
}

}  // namespace

Study dem_study(const StudyOptions& options) {
  Study st;
  st.name = "dem";
  st.title = "DEM: steps per contact N_c and mesh size ξ";
  st.method =
      "N_c (single-particle cases): Patterson & Reece vane (flat disc, one radial vane, 500 rpm, μ 0.3, r0 0.1 m, R 0.4 m, particle "
      "radius 1 mm; error = exit speed in the horizontal plane against the closed form) and a sphere–plane "
      "head-on impact (Hertz–Thornton, e = 0.5, 1 m/s; error = measured restitution against 0.5). ξ: the seed's "
      "Appendix-1 cone (Table 3, μ 0.3, R 0.1 m, 4 particles, analytic cone and meshes of element size ξ·R) at "
      "the engine's default N_c; error = the worst of exit speed, elevation, angle from the tangent and exit "
      "time against the Dormand–Prince ODE reference (1e-12). Time = wall time of one run of the case (single "
      "thread). The vane error has a floor of about −0.1 %: the particle centre sits one radius off the vane "
      "line (docs/dem.md).";
  const scene::Scene scene = detail::load_study_scene(options);
  st.columns = {"case", "N_c", "mesh_xi", "dt_s", "rel_error", "wall_time_s", "triangles"};

  const std::vector<double> ncs =
      options.quick ? std::vector<double>{5, 10, 15, 20} : std::vector<double>{5, 7, 10, 15, 20, 30, 50};
  Series vane{"vane exit speed", {}, {}}, impact{"impact restitution (e = 0.5)", {}, {}};
  Series impact_low{"impact restitution (e = 0.1)", {}, {}};
  double impact_low_err_at_recommended = std::nan("");
  double nc_recommended = std::nan("");
  double vane_err_at_20 = std::nan("");
  for (double nc : ncs) {
    dem::VaneCase vc;
    vc.friction = 0.3;
    const auto start = detail::cpu_now();
    const detail::VaneExit v = detail::run_vane_at(vc, nc);
    const double t_vane = detail::seconds_since(start);
    dem::ImpactCase ic;
    ic.restitution = 0.5;
    ic.contact_steps = nc;
    const auto start_i = detail::cpu_now();
    const dem::ImpactResult ir = dem::run_impact(ic);
    const double t_impact = detail::seconds_since(start_i);
    const double e_err = (ir.e_measured - ir.e_requested) / ir.e_requested;
    // Low restitution converges more slowly in N_c (docs/dem.md): measured alongside, not part of the
    // criterion, so the report can state what the recommended N_c costs at e = 0.1.
    dem::ImpactCase ic_low = ic;
    ic_low.restitution = 0.1;
    const dem::ImpactResult ir_low = dem::run_impact(ic_low);
    const double e_low_err = (ir_low.e_measured - ir_low.e_requested) / ir_low.e_requested;
    st.rows.push_back({"vane", cell(nc), cell(std::nan("")), cell(v.dt_s), cell(v.rel_error), cell(t_vane), "0"});
    st.rows.push_back({"impact", cell(nc), cell(std::nan("")), cell(std::nan("")), cell(e_err), cell(t_impact), "0"});
    st.rows.push_back({"impact (e = 0.1)", cell(nc), cell(std::nan("")), cell(std::nan("")), cell(e_low_err), "—", "0"});
    impact_low.x.push_back(nc);
    impact_low.y.push_back(std::max(std::abs(e_low_err), 1e-16));
    st.figures["impact_error_nc" + cell(nc)] = e_err;
    st.figures["impact_low_error_nc" + cell(nc)] = e_low_err;
    vane.x.push_back(nc);
    vane.y.push_back(std::max(std::abs(v.rel_error), 1e-16));
    impact.x.push_back(nc);
    impact.y.push_back(std::max(std::abs(e_err), 1e-16));
    if (std::isnan(nc_recommended) && std::abs(v.rel_error) <= kErrorBudget && std::abs(e_err) <= kErrorBudget) {
      nc_recommended = nc;
      impact_low_err_at_recommended = e_low_err;
    }
    if (nc == 20.0) vane_err_at_20 = v.rel_error;
    st.figures["vane_time_s_nc" + std::to_string(static_cast<int>(nc))] = t_vane;
    if (options.progress) {
      *options.progress << "dem N_c " << nc << ": vane error " << v.rel_error << " (" << t_vane << " s), impact e error "
                        << e_err << "\n";
    }
  }
  st.figures["nc_recommended"] = nc_recommended;
  st.figures["vane_error_nc20"] = vane_err_at_20;

  const std::vector<double> xis =
      options.quick ? std::vector<double>{0.0, 0.02, 0.01} : std::vector<double>{0.0, 0.02, 0.01, 0.005, 0.0035};
  Series cone{"cone, worst of 4 exit quantities", {}, {}};
  double xi_recommended = std::nan("");
  for (double xi : xis) {
    dem::ConeCase cc;
    cc.mu = 0.3;
    cc.mesh_size = xi;
    const auto start = detail::cpu_now();
    const dem::ConeResult r = dem::run_cone(cc);
    const double t = detail::seconds_since(start);
    const double err = std::max({std::abs(r.rel_error_speed), std::abs(r.rel_error_elevation),
                                 std::abs(r.rel_error_angle), std::abs(r.rel_error_t_exit)});
    st.rows.push_back({xi == 0.0 ? "cone (analytic)" : "cone (mesh)", cell(dem::EngineParams{}.contact_steps),
                       cell(xi), cell(std::nan("")), cell(err), cell(t), std::to_string(r.triangles)});
    if (xi > 0.0) {
      cone.x.push_back(xi);
      cone.y.push_back(std::max(err, 1e-16));
      // Meshes are listed coarse to fine: the first within budget is the cheapest.
      if (std::isnan(xi_recommended) && err <= kErrorBudget) xi_recommended = xi;
    } else {
      st.figures["cone_analytic_error"] = err;
    }
    st.figures["cone_error_xi" + cell(xi)] = err;
    if (options.progress) *options.progress << "dem cone xi " << xi << ": error " << err << " (" << t << " s)\n";
  }
  st.figures["xi_recommended"] = xi_recommended;

  // Whole disc, short run: R̄ and ξ of the landings against the finest run. The runs share the scene's
  // seed, so they release the same granules at the same instants; what differs is the integration (and,
  // through collisions, which granules meet — a chaotic system, so part of the difference is the
  // statistical noise of a run of this many granules, not a bias).
  const double disc_duration_s = options.quick ? 0.12 : 0.16;
  const std::vector<double> disc_ncs =
      options.quick ? std::vector<double>{10, 20} : std::vector<double>{5, 10, 15, 20, 30, 50};
  const std::vector<double> disc_xis =
      options.quick ? std::vector<double>{0.02} : std::vector<double>{0.02, 0.01, 0.005};
  const double disc_nc_mesh = scene.numerics.steps_per_contact;  // the mesh runs use the scene's N_c
  std::vector<DiscRun> nc_runs;
  for (double nc : disc_ncs) {
    nc_runs.push_back(run_disc(scene, options, disc_duration_s, nc, 0.0));
    if (options.progress) {
      *options.progress << "dem disc N_c " << nc << ": R " << nc_runs.back().mean_radius_m << " m, xi "
                        << nc_runs.back().radial_width_m << " m, " << nc_runs.back().launched << " launched ("
                        << nc_runs.back().cpu_s << " s)\n";
    }
  }
  const DiscRun& nc_ref = nc_runs.back();
  // The analytic disc at the mesh runs' N_c (reuse the N_c run when it is in the grid).
  DiscRun analytic_ref;
  bool have_analytic = false;
  for (std::size_t k = 0; k < disc_ncs.size(); ++k) {
    if (disc_ncs[k] == disc_nc_mesh) {
      analytic_ref = nc_runs[k];
      have_analytic = true;
    }
  }
  if (!have_analytic) analytic_ref = run_disc(scene, options, disc_duration_s, disc_nc_mesh, 0.0);
  Series disc_nc_r{"disc R-bar, N_c varied", {}, {}}, disc_nc_x{"disc xi, N_c varied", {}, {}};
  Series disc_mesh_r{"disc R-bar, mesh xi/R varied", {}, {}}, disc_mesh_x{"disc xi, mesh xi/R varied", {}, {}};
  auto rel = [](double a, double b) { return std::abs(a - b) / b; };
  double disc_nc_recommended = std::nan("");
  for (std::size_t k = 0; k < disc_ncs.size(); ++k) {
    const DiscRun& r = nc_runs[k];
    const double er = rel(r.mean_radius_m, nc_ref.mean_radius_m), ex = rel(r.radial_width_m, nc_ref.radial_width_m);
    const std::string label = "disc (analytic) vs N_c " + cell(disc_ncs.back());
    st.rows.push_back({label + ": R̄", cell(disc_ncs[k]), "0", cell(r.dt_s), cell(er), cell(r.cpu_s), "0"});
    st.rows.push_back({label + ": ξ", cell(disc_ncs[k]), "0", cell(r.dt_s), cell(ex), cell(r.cpu_s), "0"});
    st.figures["disc_error_r_bar_nc" + cell(disc_ncs[k])] = er;
    st.figures["disc_error_xi_nc" + cell(disc_ncs[k])] = ex;
    if (&r == &nc_ref) continue;
    disc_nc_r.x.push_back(r.cpu_s);
    disc_nc_r.y.push_back(std::max(er, 1e-16));
    disc_nc_x.x.push_back(r.cpu_s);
    disc_nc_x.y.push_back(std::max(ex, 1e-16));
    if (std::isnan(disc_nc_recommended) && er <= kErrorBudget && ex <= kErrorBudget) disc_nc_recommended = disc_ncs[k];
  }
  st.figures["disc_nc_recommended"] = disc_nc_recommended;
  double disc_xi_recommended = std::nan("");
  double worst_mesh_error_at_recommended = std::nan("");
  for (double xi : disc_xis) {
    const DiscRun r = run_disc(scene, options, disc_duration_s, disc_nc_mesh, xi);
    const double er = rel(r.mean_radius_m, analytic_ref.mean_radius_m);
    const double ex = rel(r.radial_width_m, analytic_ref.radial_width_m);
    st.rows.push_back({"disc (mesh) vs analytic disc: R̄", cell(disc_nc_mesh), cell(xi), cell(r.dt_s), cell(er),
                       cell(r.cpu_s), "—"});
    st.rows.push_back({"disc (mesh) vs analytic disc: ξ", cell(disc_nc_mesh), cell(xi), cell(r.dt_s), cell(ex),
                       cell(r.cpu_s), "—"});
    disc_mesh_r.x.push_back(r.cpu_s);
    disc_mesh_r.y.push_back(std::max(er, 1e-16));
    disc_mesh_x.x.push_back(r.cpu_s);
    disc_mesh_x.y.push_back(std::max(ex, 1e-16));
    st.figures["disc_error_r_bar_mesh" + cell(xi)] = er;
    st.figures["disc_error_xi_mesh" + cell(xi)] = ex;
    if (std::isnan(disc_xi_recommended) && er <= kErrorBudget && ex <= kErrorBudget) disc_xi_recommended = xi;
    if (xi == xi_recommended) worst_mesh_error_at_recommended = std::max(er, ex);
    if (options.progress) {
      *options.progress << "dem disc mesh " << xi << ": R error " << er << ", xi error " << ex << " (" << r.cpu_s
                        << " s)\n";
    }
  }
  st.figures["disc_xi_recommended"] = disc_xi_recommended;
  st.figures["disc_launched"] = static_cast<double>(nc_ref.launched);
  st.figures["disc_time_nc_ref_s"] = nc_ref.cpu_s;
  st.figures["disc_r_bar_noise"] = nc_ref.r_bar_noise;

  Plot p1;
  p1.file = "dem_contact_steps.png";
  p1.title = "DEM: error vs steps per contact N_c";
  p1.x_label = "steps per contact N_c (cost ~ N_c)";
  p1.y_label = "|relative error|";
  p1.series = {vane, impact, impact_low};
  p1.threshold_y = kErrorBudget;
  Plot p2;
  p2.file = "dem_mesh_size.png";
  p2.title = "DEM: Appendix-1 cone, error vs mesh size";
  p2.x_label = "mesh size xi / R";
  p2.y_label = "worst |relative error|";
  p2.series = {cone};
  p2.threshold_y = kErrorBudget;
  Plot p3;
  p3.file = "dem_disc.png";
  p3.title = "DEM: whole-disc R-bar and xi vs CPU time of a short run";
  p3.x_label = "CPU time of one run (s)";
  p3.y_label = "relative error against the finest run";
  p3.series = {disc_nc_r, disc_nc_x, disc_mesh_r, disc_mesh_x};
  p3.threshold_y = kErrorBudget;
  st.plots = {p1, p2, p3};

  char buf[2400];
  std::snprintf(buf, sizeof buf,
                " Whole disc: `%s` (material `%s`, %.0f rpm), %.2f s of feed, one thread, granules launched by "
                "then flown to the ground with the scene's flight settings (%zu launched in the finest run); R̄ "
                "and ξ (Eqs. 51–52) of the landings against the finest run — for N_c the analytic disc at N_c "
                "%g, for the mesh (element size ξ/R · R, at the scene's N_c %g) the analytic disc at that N_c, "
                "the ξ → 0 limit. The runs release the same granules at the same instants; collisions make the "
                "process chaotic, so part of each difference is the sampling noise of a run of this many "
                "granules (compare the particle-count study at that count), not a bias.",
                scene.source_name.c_str(), detail::study_material(scene, options).name.c_str(),
                scene.machine.rpm, disc_duration_s, nc_ref.launched, disc_ncs.back(), disc_nc_mesh);
  st.method += buf;

  // Do the whole-disc errors fall steadily as N_c grows (discretisation) or scatter (sampling noise)?
  bool steady = true;
  for (std::size_t k = 1; k + 1 < disc_ncs.size(); ++k) {
    for (const char* q : {"disc_error_r_bar_nc", "disc_error_xi_nc"}) {
      if (st.figures[q + cell(disc_ncs[k])] > st.figures[q + cell(disc_ncs[k - 1])]) steady = false;
    }
  }
  const int engine_nc = static_cast<int>(dem::EngineParams{}.contact_steps);
  double min_restitution = 1.0;
  for (const auto& m : scene.materials) min_restitution = std::min(min_restitution, m.restitution);
  std::string mesh_at_cone_recommendation;
  if (!std::isnan(worst_mesh_error_at_recommended)) {
    char b[160];
    std::snprintf(b, sizeof b, " (worst of R̄, ξ at the cone's ξ/R %g: %.2g %%)", xi_recommended,
                  100.0 * worst_mesh_error_at_recommended);
    mesh_at_cone_recommendation = b;
  }
  const int scene_nc = scene::Numerics{}.steps_per_contact;
  std::snprintf(buf, sizeof buf,
                "- N_c: the smallest measured N_c with both the vane exit speed and the e = 0.5 restitution within "
                "1 %% is **%g**; the scene default `numerics.steps_per_contact` is %d (every scene-driven run: "
                "`spread simulate`, lookup_builder's DEM source). At that N_c the e = 0.1 restitution is off by "
                "%.2g %% (low restitution converges more slowly; it is not part of the criterion because the "
                "study scene's materials have e >= %g). Cost grows linearly with N_c. The engine's own default "
                "`dem::EngineParams::contact_steps` = %d is the N_c of the single-particle verification cases "
                "(`spread verify`, docs/dem.md), whose tolerances were set at it; it is not used by scene runs.\n"
                "- Whole disc (short run, %zu granules): R̄ and ξ within 1 %% of the N_c %g run from N_c **%s**; "
                "the meshed disc within 1 %% of the analytic one from ξ/R **%s**%s. The sampling noise of R̄ "
                "alone in a run of this size is ±%.2g %% (1.96·s_r/√N of the finest run); %s\n"
                "- Mesh: the coarsest measured ξ/R with the cone within 1 %% is **%g**; the analytic cone is "
                "exact to %.2g and cheapest — prefer `disc_model = \"analytic\"` whenever the disc is a cone "
                "or a plane. The scene default `machine.mesh_size_m = 0` means ξ = %g·R (at R = %.2f m: %.2g "
                "mm). Bundled meshed scenes: %s.\n",
                nc_recommended, scene_nc, 100.0 * std::abs(impact_low_err_at_recommended), min_restitution, engine_nc,
                nc_ref.launched, disc_ncs.back(),
                std::isnan(disc_nc_recommended) ? "— (none of the measured)" : cell(disc_nc_recommended).c_str(),
                std::isnan(disc_xi_recommended) ? "— (none of the measured)" : cell(disc_xi_recommended).c_str(),
                mesh_at_cone_recommendation.c_str(), 100.0 * nc_ref.r_bar_noise,
                steady ? "the differences fall steadily with N_c."
                       : "the differences do not fall steadily with N_c: at this run length they measure that "
                         "noise, not the discretisation, which the single-particle cases above resolve.",
                xi_recommended,
                st.figures["cone_analytic_error"], scene::kDefaultMeshSizePerRadius, scene.machine.disc_radius_m,
                1e3 * scene::kDefaultMeshSizePerRadius * scene.machine.disc_radius_m, bundled_mesh_sizes().c_str());
  st.recommendation = buf;
  return st;
}

}  // namespace spread::accuracy
