#pragma once
// Contact laws composed from sub-models (HOOMD/LAMMPS GRANULAR style, docs/design.md §7): ComposedLaw<Normal,
// Damping, Tangential, Rolling, Cohesion> puts one model of each list below together into an evaluator with an
// inline kernel over the lane types (one contact, or two in lanes) and per-pair coefficients derived once
// per material pair (Coeffs: each sub-model's own, R* and M*). The force passes are templates over the
// law, instantiated for the combinations force_variants.hpp generates from these lists, so no contact
// pays a virtual call or a branch on the model. Sign and frame conventions: contact_kernel.hpp.
#include <cmath>
#include <cstddef>
#include <utility>

#include "libspread/physics/dem/cohesion_models.hpp"
#include "libspread/physics/dem/contact_kernel.hpp"
#include "libspread/physics/dem/contact_law.hpp"
#include "libspread/physics/dem/damping_models.hpp"
#include "libspread/physics/dem/lanes.hpp"
#include "libspread/physics/dem/material.hpp"
#include "libspread/physics/dem/normal_models.hpp"
#include "libspread/physics/dem/rolling_models.hpp"
#include "libspread/physics/dem/tangential_models.hpp"

namespace spread::dem {

// A list of sub-model types; a model's position is its enumerator's value (contact_law.hpp).
template <class... Models>
struct SubModels {
  static constexpr std::size_t size = sizeof...(Models);
};
template <std::size_t I, class List>
struct SubModelAt;
template <std::size_t I, class First, class... Rest>
struct SubModelAt<I, SubModels<First, Rest...>> : SubModelAt<I - 1, SubModels<Rest...>> {};
template <class First, class... Rest>
struct SubModelAt<0, SubModels<First, Rest...>> {
  using type = First;
};

// Adding a sub-model: its type in its family's header, its enumerator in contact_law.hpp (same position),
// its rule in contact_law_conflict, and here.
using NormalModels = SubModels<NormalNone, NormalLinear, NormalHertz>;
using DampingModels = SubModels<DampingNone, DampingLinearViscous, DampingHertz>;
using TangentialModels = SubModels<TangentialNone, TangentialLinear, TangentialThornton>;
using RollingModels = SubModels<RollingNone, RollingConstantTorque>;
using CohesionModels = SubModels<CohesionNone>;

namespace detail {
template <class List, std::size_t... I>
constexpr bool ids_are_positions(std::index_sequence<I...>) {
  return ((static_cast<std::size_t>(SubModelAt<I, List>::type::kId) == I) && ...);
}
template <class List>
constexpr bool ids_are_positions() {
  return ids_are_positions<List>(std::make_index_sequence<List::size>{});
}
static_assert(ids_are_positions<NormalModels>() && ids_are_positions<DampingModels>() &&
              ids_are_positions<TangentialModels>() && ids_are_positions<RollingModels>() &&
              ids_are_positions<CohesionModels>(),
              "each sub-model list must be in its enum's order (contact_law.hpp)");
}  // namespace detail

template <class Normal, class Damping, class Tangential, class Rolling, class Cohesion = CohesionNone>
struct ComposedLaw {
  static constexpr ContactLaw kLaw{.normal = Normal::kId, .damping = Damping::kId, .tangential = Tangential::kId,
                                   .rolling = Rolling::kId, .cohesion = Cohesion::kId};
  static constexpr bool kRolling = Rolling::kActive;
  using RollingModel = Rolling;

  // Everything of the law that depends only on the two bodies (R*, M*, the pair's material constants), not
  // on the contact's state: computed by coeffs() once per material pair whose particles all share one
  // radius and mass (the engine's table, refreshed when particles are added), or per contact otherwise.
  struct Coeffs {
    double r_eff_m = 0.0;   // R* (rolling resistance)
    double m_eff_kg = 0.0;  // M*
    typename Normal::Coeffs normal;
    typename Damping::Coeffs damping;
    typename Tangential::Coeffs tangential;
    [[no_unique_address]] typename Cohesion::Coeffs cohesion;
    bool uniform = false;   // engine table only: true when the entry holds for every particle pair of these materials
  };

  SPREAD_CONTACT_INLINE static Coeffs coeffs(const PairParams& p, double r_eff_m, double m_eff_kg) {
    PairScales s{r_eff_m, m_eff_kg, 0.0};
    if constexpr (Normal::kUsesSqrtR || Damping::kUsesSqrtR || Tangential::kUsesSqrtR) s.sqrt_r_eff_m0_5 = std::sqrt(r_eff_m);
    Coeffs c;
    c.r_eff_m = r_eff_m;
    c.m_eff_kg = m_eff_kg;
    c.normal = Normal::coeffs(p, s);
    c.damping = Damping::coeffs(p, s);
    c.tangential = Tangential::coeffs(p, s);
    if constexpr (Cohesion::kActive) c.cohesion = Cohesion::coeffs(p, s);
    return c;
  }

  // One contact (T = double) or several (T = lanes::Lanes2, Lanes8) with the same coefficients c and friction μ.
  // contact_normal: unit normal from b to a, and its unnormalised axis (ContactNormal); delta_m: overlap > 0;
  // slip_m_s: Eq. 8; h: in/out history (the elastic tangential force and this evaluation's overlap).
  template <class T>
  SPREAD_CONTACT_INLINE static LawForce<T> kernel(const Coeffs& c, double friction, const ContactNormal<T>& contact_normal,
                                                  T delta_m, const lanes::V3<T>& slip_m_s, double dt_s, LawHistory<T>& h) {
    const lanes::V3<T>& normal = contact_normal.unit;
    const typename Normal::template Geometry<T> g = Normal::geometry(delta_m);
    const T slip_n = dot(slip_m_s, normal);
    // Elastic plus dashpot, clipped at 0: a contact never pulls (δ̇ = −slip·n).
    const T f_n = lanes::max0(Damping::add(c.damping, Normal::force(c.normal, delta_m, g), g, slip_n));
    LawForce<T> out;
    out.normal_force_n = f_n;
    if constexpr (Tangential::kActive) {
      const lanes::V3<T> slip_t = slip_m_s - slip_n * normal;
      out.tangential_n =
          Tangential::force(c.tangential, contact_normal, delta_m, g, slip_t, dt_s, lanes::splat<T>(friction) * f_n, h);
      out.force_n = f_n * normal + out.tangential_n;
    } else {
      out.tangential_n = lanes::zero3<T>();
      out.force_n = f_n * normal;
    }
    // The attraction after the cap: friction and rolling resistance take the repulsive F_n.
    if constexpr (Cohesion::kActive) out.force_n = out.force_n - Cohesion::force(c.cohesion, delta_m) * normal;
    h.overlap_m = delta_m;
    return out;
  }

  // Rolling resistance on a (b takes its opposite): the rolling model's torque against the relative spin
  // ω_a − ω_b from the normal force F_n, R* and the pair's I* = (1/I_a + 1/I_b)^-1 (walls: I_a); zero
  // without a rolling model. Both passes take it from here, so the law alone decides whether and how.
  SPREAD_CONTACT_INLINE static lanes::V3<double> rolling_torque(const PairParams& p, double normal_force_n, double r_eff_m,
                                                                const lanes::V3<double>& relative_spin_rad_s,
                                                                double inertia_eff_kg_m2, double dt_s) {
    if constexpr (kRolling) {
      const Vec3 t = Rolling::torque(p.rolling_friction, normal_force_n, r_eff_m,
                                     Vec3(relative_spin_rad_s.x, relative_spin_rad_s.y, relative_spin_rad_s.z),
                                     inertia_eff_kg_m2, dt_s);
      return {t.x(), t.y(), t.z()};
    } else {
      return {0.0, 0.0, 0.0};
    }
  }
  // Several contacts' rolling torques (T = lanes::Lanes2 or Lanes8), lane by lane the one-contact torque.
  template <class T>
  SPREAD_CONTACT_INLINE static lanes::V3<T> rolling_torque(const PairParams& p, T normal_force_n, double r_eff_m,
                                                           const lanes::V3<T>& relative_spin_rad_s, T inertia_eff_kg_m2,
                                                           double dt_s) {
    lanes::V3<T> out;
    for (int l = 0; l < static_cast<int>(sizeof(T) / sizeof(double)); ++l) {
      const lanes::V3<double> t = rolling_torque(p, normal_force_n[l], r_eff_m, lanes::lane3(relative_spin_rad_s, l),
                                                 inertia_eff_kg_m2[l], dt_s);
      out.x[l] = t.x;
      out.y[l] = t.y;
      out.z[l] = t.z;
    }
    return out;
  }

  // Lever arm from a's centre to the contact point (Eq. 10): how the normal model shares the overlap.
  template <class T>
  SPREAD_CONTACT_INLINE static T lever(T radius_m, double share, T overlap_m) {
    return Normal::lever(radius_m, share, overlap_m);
  }

  // Eigen-interface evaluation: the wall contacts and single contacts; the pair pass calls kernel directly.
  // in.r_eff_m and in.m_eff_kg are not read: c holds what depends on them.
  static ContactForce eval(const PairParams& p, const Coeffs& c, const ContactInput& in, double* history) {
    using lanes::V3;
    LawHistory<double> h = load_history(history);
    const V3<double> n{in.normal.x(), in.normal.y(), in.normal.z()};
    const LawForce<double> r = kernel(c, p.friction, ContactNormal<double>{n, n, 1.0}, in.overlap_m,
                                      V3<double>{in.slip_m_s.x(), in.slip_m_s.y(), in.slip_m_s.z()}, in.dt_s, h);
    store_history(h, history);
    ContactForce out;
    out.force_n = Vec3(r.force_n.x, r.force_n.y, r.force_n.z);
    out.tangential_force_n = Vec3(r.tangential_n.x, r.tangential_n.y, r.tangential_n.z);
    out.normal_force_n = r.normal_force_n;
    return out;
  }
  static ContactForce eval(const PairParams& p, const ContactInput& in, double* history) {
    return eval(p, coeffs(p, in.r_eff_m, in.m_eff_kg), in, history);
  }
};

// The two laws scenes name (contact_law.hpp's kHertzThorntonLaw, kLinearSpringDashpotLaw), without rolling.
using HertzThornton = ComposedLaw<NormalHertz, DampingHertz, TangentialThornton, RollingNone>;
using LinearSpringDashpot = ComposedLaw<NormalLinear, DampingLinearViscous, TangentialLinear, RollingNone>;

}  // namespace spread::dem
