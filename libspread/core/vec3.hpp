#pragma once
// Shared vector type and conventions of libspread.
//
// Frame (all modules): x lateral (positive to the machine's right), y along the driving direction
// (positive forward), z up. The (left) disc centre is the origin of its own launch samples; the ground
// is the plane z = ground_z_m. SI units everywhere unless a name says otherwise.
#include <Eigen/Core>

namespace spread {
using Vec3 = Eigen::Vector3d;
inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kStandardGravity_m_s2 = 9.80665;
}  // namespace spread
