#pragma once
// Rolling-resistance sub-models of a contact law (contact_law.hpp): a torque against the bodies'
// relative spin, from the contact's normal force. They act on the spin, so they need the rotation
// effect (contact_law_conflict). The passes call torque() per contact when kActive.
#include <algorithm>

#include "libspread/core/vec3.hpp"
#include "libspread/physics/dem/contact_law.hpp"

namespace spread::dem {

struct RollingNone {
  static constexpr RollingModel kId = RollingModel::kNone;
  static constexpr const char* kName = "none";
  static constexpr bool kActive = false;
};

// Constant directional torque: M_r = −μ_r F_n R* ω̂_rel (μ_r the pair's rolling_friction), limited so that
// it can at most stop the relative spin within one step (it never reverses it).
struct RollingConstantTorque {
  static constexpr RollingModel kId = RollingModel::kConstantTorque;
  static constexpr const char* kName = "constant_torque";
  static constexpr bool kActive = true;
  static Vec3 torque(double rolling_friction, double normal_force_n, double r_eff_m, const Vec3& relative_spin_rad_s,
                     double inertia_eff_kg_m2, double dt_s) {
    const double w = relative_spin_rad_s.norm();
    if (w == 0.0 || rolling_friction == 0.0) return Vec3::Zero();
    const double mag = std::min(rolling_friction * normal_force_n * r_eff_m, w * inertia_eff_kg_m2 / dt_s);
    return (-mag / w) * relative_spin_rad_s;
  }
};

}  // namespace spread::dem
