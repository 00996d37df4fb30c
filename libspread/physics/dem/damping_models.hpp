#pragma once
// Normal damping sub-models of a contact law (contact_law.hpp): the dashpot added to the elastic force
// before the sum is clipped at 0 (a contact pulls neither body). δ̇ = −slip·n (contact_kernel.hpp).
// The damping ratio behind each coefficient comes from the pair restitution (PairParams::damping_ratio,
// fitted per damping model: restitution.hpp); the tangential dashpots use the same ratio.
#include "libspread/physics/dem/contact_kernel.hpp"
#include "libspread/physics/dem/contact_law.hpp"
#include "libspread/physics/dem/material.hpp"

namespace spread::dem {

// No dashpot: an elastic contact (e = 1).
struct DampingNone {
  static constexpr DampingModel kId = DampingModel::kNone;
  static constexpr const char* kName = "none";
  static constexpr bool kUsesSqrtR = false;
  struct Coeffs {};
  SPREAD_CONTACT_INLINE static Coeffs coeffs(const PairParams&, const PairScales&) { return {}; }
  template <class T, class Geometry>
  SPREAD_CONTACT_INLINE static T add(const Coeffs&, T elastic_n, const Geometry&, T) { return elastic_n; }
};

// Seed 001: F = F_el + c_n δ̇ with c_n = 2ζ √(M* k_n) (k_n the linear normal spring).
struct DampingLinearViscous {
  static constexpr DampingModel kId = DampingModel::kLinearViscous;
  static constexpr const char* kName = "linear_viscous";
  static constexpr bool kUsesSqrtR = false;
  struct Coeffs {
    double coefficient_n_s_m = 0.0;  // c_n
  };
  SPREAD_CONTACT_INLINE static Coeffs coeffs(const PairParams& p, const PairScales& s) {
    return {2.0 * p.damping_ratio * std::sqrt(s.m_eff_kg * p.kn_linear_n_m)};
  }
  template <class T, class Geometry>
  SPREAD_CONTACT_INLINE static T add(const Coeffs& c, T elastic_n, const Geometry&, T slip_normal_m_s) {
    return elastic_n + lanes::splat<T>(c.coefficient_n_s_m) * (-slip_normal_m_s);
  }
};

// Seed 000 Eqs. 17–18 (Tsuji's form): F = F_el + c_n δ^{1/4} δ̇ with c_n = γ √(8 E* M* √R*); γ is the damping
// ratio against the linearised stiffness dF/dδ = 2 E* √(R* δ).
struct DampingHertz {
  static constexpr DampingModel kId = DampingModel::kHertz;
  static constexpr const char* kName = "hertz";
  static constexpr bool kUsesSqrtR = true;
  struct Coeffs {
    double coefficient_n_s_m1_25 = 0.0;  // c_n: the dashpot is this · δ^{1/4}
  };
  SPREAD_CONTACT_INLINE static Coeffs coeffs(const PairParams& p, const PairScales& s) {
    return {p.damping_ratio * std::sqrt(8.0 * p.e_star_pa * s.m_eff_kg * s.sqrt_r_eff_m0_5)};
  }
  // Geometry: the Hertz normal's (δ^{1/4}).
  template <class T, class Geometry>
  SPREAD_CONTACT_INLINE static T add(const Coeffs& c, T elastic_n, const Geometry& g, T slip_normal_m_s) {
    return elastic_n + lanes::splat<T>(c.coefficient_n_s_m1_25) * g.quarter_delta_m0_25 * (-slip_normal_m_s);
  }
};

}  // namespace spread::dem
