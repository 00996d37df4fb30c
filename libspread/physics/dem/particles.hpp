#pragma once
// Particle state in flat arrays (structure of arrays): one std::vector per component, indexed by the
// particle's slot. Spin and torque arrays exist only when rotation is on (docs/design.md §7: no spin state
// without rotation). Wall-contact history lives here too, kWallSlots per particle, so it moves with the
// particle when the arrays are compacted.
#include <cstdint>
#include <vector>

#include "libspread/core/vec3.hpp"
#include "libspread/physics/dem/contact_laws.hpp"

namespace spread::dem {

inline constexpr int kWallSlots = 6;  // wall contacts remembered per particle

// m = ρ 4/3 π r³ (kg), as the engine gives every particle it adds.
inline double sphere_mass(double density_kg_m3, double radius_m) {
  return density_kg_m3 * 4.0 / 3.0 * kPi * radius_m * radius_m * radius_m;
}

struct ParticleArrays {
  std::vector<double> x, y, z;        // position (m)
  std::vector<double> vx, vy, vz;     // velocity (m/s)
  std::vector<double> fx, fy, fz;     // force (N)
  std::vector<double> wx, wy, wz;     // spin (rad/s), rotation only
  std::vector<double> tx, ty, tz;     // torque (N m), rotation only
  std::vector<double> radius_m, mass_kg, inertia_kg_m2;
  // 1/m and 1/I, stored so the integrator multiplies instead of dividing twice per particle per step.
  std::vector<double> inv_mass_kg, inv_inertia_kg_m2;
  std::vector<double> birth_time_s;
  std::vector<double> x0, y0, z0;     // position at the last neighbour-list build (m)
  std::vector<std::uint32_t> id;      // unique, never reused
  std::vector<std::uint16_t> material;
  std::vector<std::uint8_t> active;   // 0: removed, waiting for compaction
  // Wall history: keys (0 = empty slot), kHistoryDoubles per slot, and the slot's last normal.
  std::vector<std::uint32_t> wall_key;
  std::vector<double> wall_history;
  std::vector<double> wall_normal;
  bool with_spin = false;

  std::size_t size() const { return x.size(); }
  Vec3 position(std::size_t i) const { return {x[i], y[i], z[i]}; }
  Vec3 velocity(std::size_t i) const { return {vx[i], vy[i], vz[i]}; }
  Vec3 spin(std::size_t i) const { return with_spin ? Vec3(wx[i], wy[i], wz[i]) : Vec3(Vec3::Zero()); }

  void push_back(const Vec3& pos, const Vec3& vel, const Vec3& spin, double radius, double mass, double inertia,
                 std::uint16_t mat, std::uint32_t pid, double birth);
  // Removes the inactive particles keeping the order of the others. Returns the count removed.
  std::size_t compact();
};

}  // namespace spread::dem
