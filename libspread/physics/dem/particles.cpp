#include "libspread/physics/dem/particles.hpp"

namespace spread::dem {

void ParticleArrays::push_back(const Vec3& pos, const Vec3& vel, const Vec3& s, double radius, double mass,
                               double inertia, std::uint16_t mat, std::uint32_t pid, double birth) {
  x.push_back(pos.x()); y.push_back(pos.y()); z.push_back(pos.z());
  vx.push_back(vel.x()); vy.push_back(vel.y()); vz.push_back(vel.z());
  fx.push_back(0.0); fy.push_back(0.0); fz.push_back(0.0);
  if (with_spin) {
    wx.push_back(s.x()); wy.push_back(s.y()); wz.push_back(s.z());
    tx.push_back(0.0); ty.push_back(0.0); tz.push_back(0.0);
  }
  radius_m.push_back(radius);
  mass_kg.push_back(mass);
  inertia_kg_m2.push_back(inertia);
  inv_mass_kg.push_back(1.0 / mass);
  inv_inertia_kg_m2.push_back(1.0 / inertia);
  birth_time_s.push_back(birth);
  x0.push_back(pos.x()); y0.push_back(pos.y()); z0.push_back(pos.z());
  id.push_back(pid);
  material.push_back(mat);
  active.push_back(1);
  wall_key.insert(wall_key.end(), kWallSlots, 0u);
  wall_history.insert(wall_history.end(), kWallSlots * kHistoryDoubles, 0.0);
  wall_normal.insert(wall_normal.end(), kWallSlots * 3, 0.0);
}

std::size_t ParticleArrays::compact() {
  const std::size_t n = size();
  std::size_t w = 0;
  for (std::size_t r = 0; r < n; ++r) {
    if (!active[r]) continue;
    if (w != r) {
      for (auto* v : {&x, &y, &z, &vx, &vy, &vz, &fx, &fy, &fz, &radius_m, &mass_kg, &inertia_kg_m2, &inv_mass_kg, &inv_inertia_kg_m2, &birth_time_s,
                      &x0, &y0, &z0})
        (*v)[w] = (*v)[r];
      if (with_spin)
        for (auto* v : {&wx, &wy, &wz, &tx, &ty, &tz}) (*v)[w] = (*v)[r];
      id[w] = id[r];
      material[w] = material[r];
      active[w] = 1;
      for (int s = 0; s < kWallSlots; ++s) {
        wall_key[w * kWallSlots + s] = wall_key[r * kWallSlots + s];
        for (int k = 0; k < kHistoryDoubles; ++k)
          wall_history[(w * kWallSlots + s) * kHistoryDoubles + k] = wall_history[(r * kWallSlots + s) * kHistoryDoubles + k];
        for (int k = 0; k < 3; ++k) wall_normal[(w * kWallSlots + s) * 3 + k] = wall_normal[(r * kWallSlots + s) * 3 + k];
      }
    }
    ++w;
  }
  const std::size_t removed = n - w;
  for (auto* v : {&x, &y, &z, &vx, &vy, &vz, &fx, &fy, &fz, &radius_m, &mass_kg, &inertia_kg_m2, &inv_mass_kg, &inv_inertia_kg_m2, &birth_time_s, &x0,
                  &y0, &z0})
    v->resize(w);
  if (with_spin)
    for (auto* v : {&wx, &wy, &wz, &tx, &ty, &tz}) v->resize(w);
  id.resize(w);
  material.resize(w);
  active.resize(w);
  wall_key.resize(w * kWallSlots);
  wall_history.resize(w * kWallSlots * kHistoryDoubles);
  wall_normal.resize(w * kWallSlots * 3);
  return removed;
}

}  // namespace spread::dem
