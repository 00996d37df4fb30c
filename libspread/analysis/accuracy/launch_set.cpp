#include "libspread/analysis/accuracy/launch_set.hpp"

#include <stdexcept>

#include "libspread/physics/launch/analytic_launch.hpp"

namespace spread::accuracy::detail {

scene::Scene load_study_scene(const StudyOptions& options) {
  if (options.scene_path.empty()) throw std::invalid_argument("accuracy: no scene file given");
  scene::Scene scene = scene::load_scene_file(options.scene_path);
  scene.source_name = scene_display_name(options.scene_path);
  return scene;
}

const scene::Material& study_material(const scene::Scene& scene, const StudyOptions& options) {
  const std::string name = options.material.empty() ? scene.simulate_material : options.material;
  const scene::Material* m = scene.find_material(name);
  if (m == nullptr) throw std::invalid_argument("accuracy: the scene has no material \"" + name + "\"");
  return *m;
}

LaunchSet make_launch_set(const scene::Scene& scene, const scene::Material& material, double rpm, int count,
                          std::uint64_t seed) {
  launch::AnalyticLaunchOptions lo;
  lo.spin = scene.sweep.spin_model;
  const auto samples = launch::analytic_launch_samples(scene.machine, material, rpm, scene.inlet, count, seed, lo);
  const double omega = rpm * 2.0 * kPi / 60.0;
  const double rim_speed = omega * scene.machine.disc_radius_m;
  LaunchSet set;
  set.air.density_kg_m3 = scene.air.density_kg_m3;
  set.air.viscosity_pa_s = scene.air.viscosity_pa_s;
  for (const auto& s : samples) {
    set.granules.push_back({s.diameter_m, material.density_kg_m3});
    flight::State st;
    st.position_m = Vec3(s.x_m, s.y_m, s.z_m + scene.machine.disc_height_m);
    st.velocity_m_s = rim_speed * Vec3(s.vx_norm, s.vy_norm, s.vz_norm);
    st.spin_rad_s = omega * Vec3(s.wx_norm, s.wy_norm, s.wz_norm);
    set.launches.push_back(st);
    set.mass_kg.push_back(s.mass_kg);
  }
  return set;
}

}  // namespace spread::accuracy::detail
