#pragma once
// Tangential sub-models of a contact law (contact_law.hpp): the force in the contact plane from the
// tangential slip, capped by Coulomb's μ F_n (Eq. 6). The elastic part is incremental and kept in the
// contact's history (LawHistory::elastic), carried into the current tangent plane every step; the
// dashpot uses the pair's damping ratio (zero with damping 'none').
#include "libspread/physics/dem/contact_kernel.hpp"
#include "libspread/physics/dem/contact_law.hpp"
#include "libspread/physics/dem/material.hpp"

namespace spread::dem {

// No tangential force: frictionless contacts (the history's elastic force stays zero).
struct TangentialNone {
  static constexpr TangentialModel kId = TangentialModel::kNone;
  static constexpr const char* kName = "none";
  static constexpr bool kUsesSqrtR = false;
  static constexpr bool kActive = false;
  struct Coeffs {};
  SPREAD_CONTACT_INLINE static Coeffs coeffs(const PairParams&, const PairScales&) { return {}; }
};

// Seed 001: spring k_t = tangential_ratio · k_n and dashpot 2ζ √(M* k_t), with a Coulomb slider; the spring
// is shortened to the friction limit on slip.
struct TangentialLinear {
  static constexpr TangentialModel kId = TangentialModel::kLinear;
  static constexpr const char* kName = "linear";
  static constexpr bool kUsesSqrtR = false;
  static constexpr bool kActive = true;
  struct Coeffs {
    double stiffness_n_m = 0.0;    // k_t
    double damping_n_s_m = 0.0;    // c_t = 2ζ √(M* k_t)
  };
  SPREAD_CONTACT_INLINE static Coeffs coeffs(const PairParams& p, const PairScales& s) {
    return {p.kt_linear_n_m, 2.0 * p.damping_ratio * std::sqrt(s.m_eff_kg * p.kt_linear_n_m)};
  }
  // slip_t: the tangential slip (m/s); limit_n: μ F_n; h.elastic in and out. Geometry: the normal model's.
  template <class T, class Geometry>
  SPREAD_CONTACT_INLINE static lanes::V3<T> force(const Coeffs& c, const ContactNormal<T>& contact_normal, T, const Geometry&,
                                                  const lanes::V3<T>& slip_t, double dt_s, T limit_n, LawHistory<T>& h) {
    using lanes::splat;
    lanes::V3<T> elastic = detail::carry_into_plane(h.elastic, contact_normal.axis, contact_normal.inv_axis2);
    elastic = elastic - (splat<T>(c.stiffness_n_m) * splat<T>(dt_s)) * slip_t;
    const lanes::V3<T> total = detail::coulomb(elastic, splat<T>(-c.damping_n_s_m) * slip_t, limit_n);
    h.elastic = elastic;
    return total;
  }
};

// Seed 000 Eqs. 19–20 and 23–24: Thornton's incremental law with the Mindlin stiffness k_t = 8 G* √(R* δ),
// scaled down with the contact radius on unloading, and the dashpot 2γ √(8 G* M* √R*) δ^{1/4}.
struct TangentialThornton {
  static constexpr TangentialModel kId = TangentialModel::kThornton;
  static constexpr const char* kName = "thornton";
  static constexpr bool kUsesSqrtR = true;
  static constexpr bool kActive = true;
  struct Coeffs {
    double stiffness_n_m1_5 = 0.0;     // 8 G* √R*: k_t = this · δ^{1/2} (Eq. 19)
    double damping_n_s_m1_25 = 0.0;    // 2γ √(8 G* M* √R*): c_t = this · δ^{1/4} (Eq. 24)
  };
  SPREAD_CONTACT_INLINE static Coeffs coeffs(const PairParams& p, const PairScales& s) {
    return {8.0 * p.g_star_pa * s.sqrt_r_eff_m0_5,
            2.0 * p.damping_ratio * std::sqrt(8.0 * p.g_star_pa * s.m_eff_kg * s.sqrt_r_eff_m0_5)};
  }
  // As TangentialLinear::force; Geometry: the Hertz normal's (δ^{1/2}, δ^{1/4}); h.overlap_m: the previous δ.
  template <class T, class Geometry>
  SPREAD_CONTACT_INLINE static lanes::V3<T> force(const Coeffs& c, const ContactNormal<T>& contact_normal, T delta_m,
                                                  const Geometry& g, const lanes::V3<T>& slip_t, double dt_s, T limit_n,
                                                  LawHistory<T>& h) {
    using lanes::splat;
    lanes::V3<T> elastic = detail::carry_into_plane(h.elastic, contact_normal.axis, contact_normal.inv_axis2);
    // Eq. 20 unloading branch, integrated over one step: scale by k_t/k_t,old = sqrt(δ/δ_old) when the
    // overlap (and with it the contact radius) shrinks (Appendix 2, Eq. 63).
    const T delta_old = h.overlap_m;
    const auto unloading = lanes::both(delta_m < delta_old, delta_old > splat<T>(0.0));
    if (lanes::any(unloading))
      elastic = lanes::select(unloading, elastic * lanes::sqrt(delta_m / lanes::select(unloading, delta_old, splat<T>(1.0))),
                              elastic);
    const T k_t = splat<T>(c.stiffness_n_m1_5) * g.sqrt_delta_m0_5;  // k_t = 8 G* sqrt(R* δ)
    elastic = elastic - (k_t * splat<T>(dt_s)) * slip_t;               // Eq. 19, force opposes the slip
    const lanes::V3<T> damping = (splat<T>(-c.damping_n_s_m1_25) * g.quarter_delta_m0_25) * slip_t;  // Eq. 23
    const lanes::V3<T> total = detail::coulomb(elastic, damping, limit_n);
    h.elastic = elastic;
    return total;
  }
};

}  // namespace spread::dem
