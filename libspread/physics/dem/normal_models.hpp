#pragma once
// Normal elastic sub-models of a contact law (contact_law.hpp): the repulsive force F_el(δ) and how the
// overlap δ is shared between the two bodies' lever arms (Eq. 10). Each has per-pair coefficients in
// Coeffs (computed once per material pair, contact_laws.hpp) and the powers of δ its partners reuse in
// Geometry (the Hertz damping and Thornton's tangential law take δ^{1/2} and δ^{1/4} from it).
#include "libspread/physics/dem/contact_kernel.hpp"
#include "libspread/physics/dem/contact_law.hpp"
#include "libspread/physics/dem/material.hpp"

namespace spread::dem {

// No normal force. Listed so that the sub-model lists are complete; contact_law_conflict refuses it in
// the engine (no contact time to choose a step from).
struct NormalNone {
  static constexpr NormalModel kId = NormalModel::kNone;
  static constexpr const char* kName = "none";
  static constexpr bool kUsesSqrtR = false;
  struct Coeffs {};
  template <class T>
  struct Geometry {};
  SPREAD_CONTACT_INLINE static Coeffs coeffs(const PairParams&, const PairScales&) { return {}; }
  template <class T>
  SPREAD_CONTACT_INLINE static Geometry<T> geometry(T) { return {}; }
  template <class T>
  SPREAD_CONTACT_INLINE static T force(const Coeffs&, T, const Geometry<T>&) { return lanes::splat<T>(0.0); }
  // Without a normal force nothing indents: the contact point is on the surface.
  template <class T>
  SPREAD_CONTACT_INLINE static T lever(T radius_m, double, T) { return radius_m; }
};

// Hooke (seed 001): F_el = k_n δ, k_n the scene's normal spring (LinearSprings).
struct NormalLinear {
  static constexpr NormalModel kId = NormalModel::kLinear;
  static constexpr const char* kName = "linear";
  static constexpr bool kUsesSqrtR = false;
  struct Coeffs {
    double stiffness_n_m = 0.0;  // k_n
  };
  template <class T>
  struct Geometry {};
  SPREAD_CONTACT_INLINE static Coeffs coeffs(const PairParams& p, const PairScales&) { return {p.kn_linear_n_m}; }
  template <class T>
  SPREAD_CONTACT_INLINE static Geometry<T> geometry(T) { return {}; }
  template <class T>
  SPREAD_CONTACT_INLINE static T force(const Coeffs& c, T delta_m, const Geometry<T>&) {
    return lanes::splat<T>(c.stiffness_n_m) * delta_m;
  }
  // Seed 001: d_c = −(R − h/2) n, i.e. each body takes half the overlap.
  template <class T>
  SPREAD_CONTACT_INLINE static T lever(T radius_m, double, T overlap_m) { return radius_m - lanes::splat<T>(0.5) * overlap_m; }
};

// Hertz (seed 000 Eq. 16): F_el = 4/3 √R* E* δ^{3/2}.
struct NormalHertz {
  static constexpr NormalModel kId = NormalModel::kHertz;
  static constexpr const char* kName = "hertz";
  static constexpr bool kUsesSqrtR = true;
  struct Coeffs {
    double stiffness_n_m1_5 = 0.0;  // 4/3 √R* E*: F_el = this · δ^{3/2}
  };
  template <class T>
  struct Geometry {
    T sqrt_delta_m0_5;     // δ^{1/2}
    T quarter_delta_m0_25;  // δ^{1/4}
  };
  SPREAD_CONTACT_INLINE static Coeffs coeffs(const PairParams& p, const PairScales& s) {
    return {(4.0 / 3.0) * s.sqrt_r_eff_m0_5 * p.e_star_pa};
  }
  template <class T>
  SPREAD_CONTACT_INLINE static Geometry<T> geometry(T delta_m) {
    const T sqrt_delta = lanes::sqrt(delta_m);
    return {sqrt_delta, lanes::sqrt(sqrt_delta)};
  }
  template <class T>
  SPREAD_CONTACT_INLINE static T force(const Coeffs& c, T delta_m, const Geometry<T>& g) {
    return lanes::splat<T>(c.stiffness_n_m1_5) * delta_m * g.sqrt_delta_m0_5;
  }
  // Eq. 10, corrected: body a takes the share E*/E_a* of the indentation.
  template <class T>
  SPREAD_CONTACT_INLINE static T lever(T radius_m, double share, T overlap_m) {
    return radius_m - lanes::splat<T>(share) * overlap_m;
  }
};

}  // namespace spread::dem
