#include "libspread/physics/launch/patterson_reece.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace spread::launch {

double VaneMotion::Solution::s_m(double t_s) const {
  return s_p_m + a_m * std::exp(lambda1 * t_s) + b_m * std::exp(lambda2 * t_s);
}

double VaneMotion::Solution::s_dot_m_s(double t_s) const {
  return lambda1 * a_m * std::exp(lambda1 * t_s) + lambda2 * b_m * std::exp(lambda2 * t_s);
}

VaneMotion::Solution VaneMotion::solve(double r0_m) const {
  if (!(omega_rad_s > 0.0) || !(friction >= 0.0) || !(cone_angle_rad >= 0.0) || !(gravity_m_s2 >= 0.0) ||
      !(r0_m > 0.0)) {
    throw std::invalid_argument("VaneMotion: need omega > 0, friction >= 0, cone angle >= 0, r0 > 0");
  }
  const double cos_a = std::cos(cone_angle_rad);
  const double sin_a = std::sin(cone_angle_rad);
  const double a = friction * omega_rad_s * cos_a;
  const double b = omega_rad_s * omega_rad_s * cos_a * (cos_a - friction * sin_a);
  const double c = gravity_m_s2 * (sin_a + friction * cos_a);
  if (!(b > 0.0)) {
    throw std::invalid_argument("VaneMotion: cone too steep for this friction (needs tan(cone angle) < 1/mu)");
  }
  Solution sol{};
  const double root = std::sqrt(a * a + b);
  sol.lambda1 = -a + root;
  sol.lambda2 = -a - root;
  sol.s_p_m = c / b;
  const double s0 = r0_m / cos_a;
  if (!(s0 > sol.s_p_m)) {
    throw std::invalid_argument("VaneMotion: friction holds the granule at r0 = " + std::to_string(r0_m) +
                                " m (needs r0 > " + std::to_string(sol.s_p_m * cos_a) +
                                " m at this speed): rpm too low or feed too close to the centre");
  }
  const double span = sol.lambda1 - sol.lambda2;
  sol.a_m = (s0 - sol.s_p_m) * (-sol.lambda2) / span;
  sol.b_m = (s0 - sol.s_p_m) * sol.lambda1 / span;
  return sol;
}

VaneExit vane_exit(const VaneMotion& motion, double r0_m, double r_exit_m) {
  if (!(r_exit_m > r0_m)) throw std::invalid_argument("vane_exit: exit radius must exceed the start radius");
  const VaneMotion::Solution sol = motion.solve(r0_m);
  const double cos_a = std::cos(motion.cone_angle_rad);
  const double s_exit = r_exit_m / cos_a;
  // s(t) rises monotonically (A, B > 0, ṡ(0) = 0, s̈ > 0); since B e^{λ2 t} > 0, s(t_hi) > s_exit at
  // t_hi = ln((s_exit − s_p)/A)/λ1: [0, t_hi] brackets the root.
  double lo = 0.0;
  double hi = std::log((s_exit - sol.s_p_m) / sol.a_m) / sol.lambda1;
  double t = 0.5 * hi;
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double f = sol.s_m(t) - s_exit;
    if (f > 0.0) hi = t; else lo = t;
    const double slope = sol.s_dot_m_s(t);
    double next = slope > 0.0 ? t - f / slope : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);  // Newton left the bracket: bisect
    if (std::abs(next - t) <= 1e-15 * std::max(1.0, t) || hi - lo <= 1e-15 * hi) {
      t = next;
      break;
    }
    t = next;
  }
  VaneExit exit{};
  exit.time_s = t;
  exit.speed_along_vane_m_s = sol.s_dot_m_s(t);
  exit.radial_speed_m_s = exit.speed_along_vane_m_s * cos_a;
  exit.vertical_speed_m_s = exit.speed_along_vane_m_s * std::sin(motion.cone_angle_rad);
  exit.tangential_speed_m_s = motion.omega_rad_s * r_exit_m;
  exit.turned_angle_rad = motion.omega_rad_s * t;
  return exit;
}

double exit_angle_from_tangent_limit_rad(double friction) {
  return std::atan(std::sqrt(1.0 + friction * friction) - friction);
}

}  // namespace spread::launch
