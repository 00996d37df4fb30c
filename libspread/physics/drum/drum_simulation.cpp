#include "libspread/physics/drum/drum_simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "libspread/physics/drum/drum_mantle.hpp"

namespace spread::drum {

namespace {

// The next `m` steps of a loop that steps while the time stays below t_limit_s (or below it less Δt/2) and
// reads the state only after the m-th: all m in one call (DemEngine::steps, which gives each step's opening
// kick and drift to the previous step's pass) when t_limit_s is more than m + 1 steps away, so that the loop
// would surely have taken all of them; else one step. Returns the count taken — the same steps and bits as
// one step at a time.
int steps_toward(dem::DemEngine& e, int m, double t_limit_s) {
  if (m > 1 && t_limit_s - e.time_s() > (m + 1) * e.dt_s()) {
    e.steps(static_cast<std::size_t>(m));
    return m;
  }
  e.step();
  return 1;
}

}  // namespace

dem::DemEngine make_drum_engine(const DrumScene& s, double omega) {
  std::vector<dem::Material> mats;
  for (std::size_t i = 0; i < s.species.size(); ++i) {
    dem::Material m;
    m.name = "species " + std::to_string(i);
    m.density_kg_m3 = s.species[i].density_kg_m3;
    m.youngs_modulus_pa = s.youngs_modulus_pa;
    m.poisson_ratio = s.poisson_ratio;
    m.restitution = s.restitution;
    m.friction_particle = s.friction_particle;
    m.friction_wall = s.friction_wall;
    m.rolling_friction = s.rolling_friction;
    mats.push_back(m);
  }
  const int wall_mat = static_cast<int>(mats.size());
  dem::Material wall = mats.front();
  wall.name = "drum wall";
  wall.rigid = true;
  mats.push_back(wall);
  wall.name = "end walls";
  mats.push_back(wall);
  const int end_mat = wall_mat + 1;
  // Pair values: particle–particle μ for every species pair, the wall friction against the drum, and
  // frictionless end walls when they stand in for a periodic axis.
  std::vector<dem::PairOverride> ov;
  for (int a = 0; a < wall_mat; ++a) {
    for (int b = a; b < wall_mat; ++b) ov.push_back({a, b, s.restitution, s.friction_particle, s.rolling_friction});
    ov.push_back({a, wall_mat, s.restitution, s.friction_wall, s.rolling_friction});
    const bool smooth = s.axial == AxialBoundary::kFrictionlessWalls;
    ov.push_back({a, end_mat, s.restitution, smooth ? 0.0 : s.friction_wall, smooth ? 0.0 : s.rolling_friction});
  }
  dem::WallSet walls;
  dem::WallGroup drum;
  drum.name = "drum";
  drum.angular_velocity_rad_s = omega;
  add_drum_mantle(s, wall_mat, drum, mats, ov);  // cylinder, plus the bead lining of a rough wall
  dem::WallGroup ends;
  ends.name = "end walls";
  ends.material = end_mat;
  ends.pieces.push_back(dem::make_plane(Vec3::Zero(), Vec3::UnitZ()));
  ends.pieces.push_back(dem::make_plane(Vec3(0.0, 0.0, s.length_m), -Vec3::UnitZ()));
  if (s.axial == AxialBoundary::kWalls) ends.angular_velocity_rad_s = omega;  // end plates turn with the drum
  walls.groups = {drum, ends};
  if (s.axial == AxialBoundary::kPeriodic) walls.groups = {drum};  // no end walls: periodic images instead

  dem::EngineParams ep;
  ep.contact_law = s.law;
  ep.linear.normal_stiffness_n_m = s.normal_stiffness_n_m;
  ep.linear.tangential_ratio = s.tangential_ratio;
  ep.integrator = s.integrator;
  ep.effects = effect::kParticleContact | effect::kWallContact | effect::kRotation;
  if (s.rolling_friction > 0.0) {
    ep.effects |= effect::kRolling;
    ep.contact_law.rolling = dem::RollingModel::kConstantTorque;
  }
  ep.dt_s = s.dt_s;
  ep.contact_steps = s.contact_steps;
  // Fastest impacts: a particle thrown from the wall speed falling across the drum.
  ep.impact_speed_m_s = omega * s.radius_m + std::sqrt(2.0 * kStandardGravity_m_s2 * 2.0 * s.radius_m);
  double dmin = 1e300, dmax = 0.0;
  for (const auto& x : s.species) { dmin = std::min(dmin, x.diameter_m); dmax = std::max(dmax, x.diameter_m); }
  ep.min_particle_radius_m = 0.5 * dmin;
  ep.max_particle_radius_m = 0.5 * dmax;
  ep.gravity_m_s2 = Vec3(0.0, -kStandardGravity_m_s2, 0.0);  // drum axis is z, gravity along −y
  ep.threads = s.threads;
  if (s.axial == AxialBoundary::kPeriodic) {
    // The engine needs the period to hold twice the pair-search cut-off d_max + skin (skin = r_max).
    if (!(s.length_m >= 3.0 * dmax))
      throw std::invalid_argument(s.source_name + ": drum.length_m: " + std::to_string(s.length_m) +
                                  " m is too short for axial = \"periodic\": at least 3 × the largest diameter (" +
                                  std::to_string(3.0 * dmax) + " m)");
    ep.periodic_z = {true, 0.0, s.length_m};
  }
  return dem::DemEngine(std::move(mats), std::move(ov), std::move(walls), ep);
}

namespace {

void copy_state(const dem::ParticleArrays& from, dem::DemEngine& to) {
  for (std::size_t i = 0; i < from.size(); ++i)
    if (from.active[i]) to.add_particle(from.position(i), from.velocity(i), from.radius_m[i], from.material[i], from.spin(i));
}

}  // namespace

DrumResult run_drum(const DrumScene& s) {
  validate(s);
  const auto t0 = std::chrono::steady_clock::now();
  DrumResult r;
  r.froude = froude_number(s);
  const auto placed = grid_packing(s);
  r.particles = placed.size();

  // Stage 1: settling in the resting drum.
  dem::DemEngine settle = make_drum_engine(s, 0.0);
  double m_mean = 0.0, d_mean = 0.0;
  for (const auto& q : placed) {
    settle.add_particle(q.position_m, Vec3::Zero(), q.radius_m, q.species);
    d_mean += 2.0 * q.radius_m;
  }
  for (std::size_t i = 0; i < settle.particles().size(); ++i) m_mean += settle.particles().mass_kg[i];
  m_mean /= static_cast<double>(placed.size());
  d_mean /= static_cast<double>(placed.size());
  r.dt_s = settle.dt_s();
  r.contact_time_s = settle.contact_time_s();
  // "Negligible": the mean kinetic energy per particle below rest_energy_ratio of lifting it one diameter.
  r.rest_threshold_j = s.rest_energy_ratio * static_cast<double>(placed.size()) * m_mean * kStandardGravity_m_s2 * d_mean;
  // The bed starts at rest (KE = 0): rest counts only after the time to fall across the drum.
  const double t_fall = std::sqrt(2.0 * 2.0 * s.radius_m / kStandardGravity_m_s2);
  const int every = std::max(1, static_cast<int>(std::round(0.002 / settle.dt_s())));
  int k = 0;
  while (settle.time_s() < s.settle_max_s) {
    k += steps_toward(settle, every - k % every, s.settle_max_s);
    if (k % every) continue;
    const double ke = settle.kinetic_energy_j();
    r.energy.push_back({"settle", settle.time_s(), ke});
    if (settle.time_s() > t_fall && ke < r.rest_threshold_j) {
      r.settled = true;
      break;
    }
  }
  r.settle_time_s = settle.time_s();
  r.particle_steps += settle.stats().particle_steps;

  // Stage 2: rotation, starting from the settled positions and velocities (the seed's second stage).
  dem::DemEngine turn = make_drum_engine(s, s.angular_velocity_rad_s);
  copy_state(settle.particles(), turn);
  const DrumGeometry geo{free_radius_m(s), s.length_m, s.angular_velocity_rad_s};  // the bed's wall: bead tips if rough
  const int sample_steps = std::max(1, static_cast<int>(std::round(s.sample_every_s / turn.dt_s())));
  std::vector<Snapshot> window;
  k = 0;
  while (turn.time_s() + 0.5 * turn.dt_s() < s.rotate_s) {
    k += steps_toward(turn, std::min(every - k % every, sample_steps - k % sample_steps), s.rotate_s);
    if (k % every == 0) r.energy.push_back({"rotate", r.settle_time_s + turn.time_s(), turn.kinetic_energy_j()});
    if (k % sample_steps == 0) {
      r.snapshots.push_back(measure(turn.particles(), geo, turn.time_s()));
      if (turn.time_s() >= s.measure_from_s - 1e-12) window.push_back(r.snapshots.back());
    }
  }
  r.evidence = classify(window, r.froude);
  r.particle_steps += turn.stats().particle_steps;
  r.final_particles = turn.particles();
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  if (!s.output_directory.empty()) {
    std::filesystem::create_directories(s.output_directory);
    if (s.energy_csv) {
      const auto path = (std::filesystem::path(s.output_directory) / "kinetic_energy.csv").string();
      write_energy_csv(r.energy, path);
      r.files.push_back(path);
    }
    if (s.particles_csv) {
      const auto path = (std::filesystem::path(s.output_directory) / "particles.csv").string();
      write_particles_csv(r.final_particles, path);
      r.files.push_back(path);
    }
  }
  return r;
}

void write_energy_csv(const std::vector<EnergySample>& e, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write the kinetic-energy history");
  out << "phase,time_s,kinetic_energy_j\n";
  out.precision(10);
  for (const auto& q : e) out << q.phase << ',' << q.time_s << ',' << q.kinetic_energy_j << '\n';
}

void write_particles_csv(const dem::ParticleArrays& p, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write the particles");
  out << "id,species,x_m,y_m,z_m,vx_m_s,vy_m_s,vz_m_s,diameter_m\n";
  out.precision(10);
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.active[i])
      out << p.id[i] << ',' << p.material[i] << ',' << p.x[i] << ',' << p.y[i] << ',' << p.z[i] << ',' << p.vx[i] << ','
          << p.vy[i] << ',' << p.vz[i] << ',' << 2.0 * p.radius_m[i] << '\n';
}

}  // namespace spread::drum
