#include "libspread/physics/dem/scene_config.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "libspread/physics/dem/time_step.hpp"

namespace spread::dem {

namespace {
// machine.disc_model = "stl": the machine's own disc (and vanes) from an STL file, every failure an
// error naming machine.stl_path. The path is already resolved against the scene file's directory.
std::shared_ptr<const TriangleMesh> load_disc_stl(const scene::Scene& s) {
  const scene::Machine& m = s.machine;
  const std::string key = s.source_name + ": machine.stl_path: ";
  std::error_code ec;
  if (!std::filesystem::is_regular_file(m.stl_path, ec))
    throw scene::SceneError(key + "no such file '" + m.stl_path + "'");
  TriangleMesh mesh;
  try {
    mesh = read_stl(m.stl_path, m.stl_scale);  // throws when not STL or when no valid triangle remains
  } catch (const std::exception& e) {
    throw scene::SceneError(key + e.what());
  }
  // The collector sits at disc_radius_m (unless numerics.collector_radius_m): a mesh reaching beyond it
  // is the wrong disc, or the wrong unit (a file in mm read as m).
  double reach_m = 0.0;
  for (const Vec3& v : mesh.vertices) reach_m = std::max(reach_m, std::hypot(v.x(), v.y()));
  if (reach_m > m.disc_radius_m * 1.01) {
    std::ostringstream msg;
    msg << key << "the mesh reaches " << reach_m << " m from the axis, beyond machine.disc_radius_m = "
        << m.disc_radius_m << " m (a file in mm needs machine.stl_scale = 0.001)";
    throw scene::SceneError(msg.str());
  }
  return std::make_shared<const TriangleMesh>(std::move(mesh));
}
}  // namespace

namespace {

// The granule's material and the rigid disc's. The disc has no values of its own: it repeats the granule's
// restitution, wall friction and rolling friction, so the particle–disc pair's means are exactly the
// granule's values (½(x + x) = x).
Material particle_material(const scene::Material& sm) {
  Material particle;
  particle.name = sm.name;
  particle.density_kg_m3 = sm.density_kg_m3;
  particle.youngs_modulus_pa = sm.youngs_modulus_pa;
  particle.poisson_ratio = sm.poisson_ratio;
  particle.restitution = sm.restitution;
  particle.friction_particle = sm.friction_particle;
  particle.friction_wall = sm.friction_wall;
  particle.rolling_friction = sm.rolling_friction;
  return particle;
}

std::vector<Material> materials_of(const scene::Material& sm) {
  const Material particle = particle_material(sm);
  Material steel;
  steel.name = "disc";
  steel.rigid = true;
  steel.restitution = sm.restitution;
  steel.friction_wall = sm.friction_wall;
  steel.rolling_friction = sm.rolling_friction;
  return {particle, steel};
}

// A blend: its components' materials in component order (a granule's material index is its component's
// index), then the disc's. Each component–disc pair is set to exactly the component's own wall friction,
// restitution and rolling friction (PairOverride), as the single material's disc repeats its values:
// the mixing rule's means would otherwise give a component a friction that is not its own.
void blend_materials_of(const scene::Material& blend, SimulationConfig& c) {
  c.materials.clear();
  c.overrides.clear();
  for (const tables::BlendComponent& component : blend.components) c.materials.push_back(particle_material(component.material));
  const int disc = static_cast<int>(c.materials.size());
  std::vector<Material> first = materials_of(blend.components.front().material);
  c.materials.push_back(first.back());
  for (int k = 0; k < disc; ++k) {
    const scene::Material& m = blend.components[static_cast<std::size_t>(k)].material;
    c.overrides.push_back(PairOverride{k, disc, m.restitution, m.friction_wall, m.rolling_friction});
  }
  c.disc_material = disc;
}

// A blend's feed: every component with its mass fraction, sizes and density.
void blend_inlet_of(const scene::Material& blend, SimulationConfig& c) {
  c.inlet.components.clear();
  for (std::size_t k = 0; k < blend.components.size(); ++k) {
    const tables::BlendComponent& component = blend.components[k];
    InletComponent in;
    in.material = static_cast<int>(k);
    in.density_kg_m3 = component.material.density_kg_m3;
    in.mass_fraction = component.mass_fraction;
    in.diameter_mean_m = component.material.diameter_mean_m;
    in.diameter_sd_m = component.material.diameter_sd_m;
    in.sieve = component.material.sieve;
    c.inlet.components.push_back(std::move(in));
  }
}

// The material whose mean granule sets the linear law's spring: a blend's heaviest mean granule (the
// shortest contact time needs the stiffest spring of the same duration).
const scene::Material& spring_material(const scene::Material& sm) {
  if (!sm.is_blend()) return sm;
  const scene::Material* heaviest = &sm.components.front().material;
  auto mean_mass = [](const scene::Material& m) { return m.density_kg_m3 * std::pow(m.diameter_mean_m, 3); };
  for (const tables::BlendComponent& component : sm.components) {
    if (mean_mass(component.material) > mean_mass(*heaviest)) heaviest = &component.material;
  }
  return *heaviest;
}

// The disc, its speed and its height.
void disc_of(const scene::Scene& s, SimulationConfig& c) {
  const scene::Machine& m = s.machine;
  c.disc.radius_m = m.disc_radius_m;
  c.disc.cone_angle_rad = m.cone_angle_rad;
  // Frame: the rim at z = 0, so the ground is z = −disc_height_m (the rim height above the ground).
  c.disc.z_apex_m = -m.disc_radius_m * std::tan(m.cone_angle_rad);
  c.disc.vane_count = m.vane_count;
  c.disc.vane_start_radius_m = m.vane_start_radius_m;
  c.disc.vane_end_radius_m = m.vane_end_radius_m;
  c.disc.vane_height_m = m.vane_height_m;
  c.disc.vane_pitch_rad = -m.vane_pitch_rad;  // scene: > 0 leans backwards; DiscGeometry: > 0 forwards
  c.disc.mesh_size_m = m.disc_model == scene::DiscModel::kMesh ? m.mesh_size_m : 0.0;
  if (m.disc_model == scene::DiscModel::kStl) {
    c.disc.mesh = load_disc_stl(s);  // disc and vanes: the vane keys describe nothing here
    c.disc.vane_count = 0;
  }
  c.rpm = m.rpm * (m.rotation_sense < 0 ? -1.0 : 1.0);
  c.disc_material = 1;
  c.disc_height_m = m.disc_height_m;
}

// The feed: where it falls onto the disc, how much, and the granules' sizes.
void inlet_of(const scene::Scene& s, const scene::Material& sm, SimulationConfig& c) {
  const scene::Machine& m = s.machine;
  const scene::Inlet& in = s.inlet;
  c.inlet.radius_m = in.radius_m;
  c.inlet.mass_rate_kg_s = in.mass_flow_kg_s;
  c.inlet.diameter_mean_m = sm.diameter_mean_m;
  c.inlet.diameter_sd_m = sm.diameter_sd_m;
  c.inlet.sieve = sm.sieve;
  c.inlet.material = 0;
  c.inlet.seed = s.numerics.seed;
  const double surface_z = c.disc.z_apex_m + std::tan(m.cone_angle_rad) * in.offset_m;
  c.inlet.centre_m = Vec3(in.offset_m * std::cos(in.angle_rad), in.offset_m * std::sin(in.angle_rad),
                          surface_z + in.drop_height_m);
}

// The engine's effects, contact law, integrator and step. The engine honours every DEM effect
// (wall_contact too); the disc scene refuses to run without walls.
EngineParams engine_params_of(const scene::Scene& s, const scene::Material& sm) {
  EngineParams ep;
  ep.effects = s.effects & effect::kDemEffects;
  if (!s.has(effect::kWallContact))
    throw scene::SceneError(s.source_name + ": effects.enabled: the disc DEM needs 'wall_contact' (nothing would hold the particles)");
  const scene::Numerics& n = s.numerics;
  ep.contact_law = n.contact_model == scene::ContactModel::kLinear ? kLinearSpringDashpotLaw : kHertzThorntonLaw;
  if (s.has(effect::kRolling)) ep.contact_law.rolling = RollingModel::kConstantTorque;
  ep.integrator = n.integrator == scene::Integrator::kVelocityVerlet ? Integrator::kVelocityVerlet : Integrator::kSymplecticEuler;
  ep.dt_s = n.dt_contact_s;
  ep.contact_steps = n.steps_per_contact;
  ep.threads = n.threads > 0 ? n.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (n.contact_model == scene::ContactModel::kLinear) {
    // The scene gives no spring constant: pick k_n so the linear contact lasts as long as the Hertz one
    // of a mean particle on the disc at rim speed + 5 m/s.
    const scene::Machine& m = s.machine;
    const double r = 0.5 * sm.diameter_mean_m;
    const double mass = sm.density_kg_m3 * 4.0 / 3.0 * kPi * r * r * r;
    const double v = std::abs(m.rpm) * 2.0 * kPi / 60.0 * m.disc_radius_m + 5.0;
    const double e_star = sm.youngs_modulus_pa / (1.0 - sm.poisson_ratio * sm.poisson_ratio);
    const double tc = hertz_contact_time_s(mass, r, e_star, v);
    ep.linear.normal_stiffness_n_m = mass * (kPi / tc) * (kPi / tc);
  }
  return ep;
}

// The run's length, the collector, and the flight after launch.
void flight_of(const scene::Scene& s, SimulationConfig& c) {
  const scene::Numerics& n = s.numerics;
  c.duration_s = n.duration_s;
  c.collector_radius_m = n.collector_radius_m;
  c.flight_effects = s.effects & effect::kFlightEffects;
  c.air.density_kg_m3 = s.air.density_kg_m3;
  c.air.viscosity_pa_s = s.air.viscosity_pa_s;
  c.air.wind_m_s = Vec3(s.air.wind_m_s[0], s.air.wind_m_s[1], 0.0);
  c.flight_settings.scheme = n.flight_scheme == scene::FlightScheme::kRk4 ? flight::Scheme::kRk4 : flight::Scheme::kDormandPrince45;
  c.flight_settings.dt_s = n.flight_dt_s;
  c.flight_settings.rel_tol = n.flight_tolerance;
  c.flight_threads = c.engine.threads;
}

}  // namespace

SimulationConfig config_from_scene(const scene::Scene& s, const std::string& material_name) {
  const std::string name = material_name.empty() ? s.simulate_material : material_name;
  const scene::Material* sm = name.empty() ? (s.materials.empty() ? nullptr : &s.materials.front()) : s.find_material(name);
  if (!sm) throw scene::SceneError(s.source_name + ": simulate.material: unknown material '" + name + "'");
  SimulationConfig c;
  if (sm->is_blend()) {
    disc_of(s, c);
    blend_materials_of(*sm, c);
    inlet_of(s, sm->components.front().material, c);
    blend_inlet_of(*sm, c);
  } else {
    c.materials = materials_of(*sm);
    disc_of(s, c);
    inlet_of(s, *sm, c);
  }
  c.engine = engine_params_of(s, spring_material(*sm));
  flight_of(s, c);
  return c;
}

}  // namespace spread::dem
