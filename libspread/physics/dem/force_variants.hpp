#pragma once
// The force pass's instantiations, generated from the sub-model lists (contact_laws.hpp) and the registry
// bits: every combination normal × damping × tangential × rolling × subset of the pass-shaping effects
// (kPassEffects) that contact_law_conflict accepts and a scene can reach. The engine picks one by its position once (find_force_variant); each pass file builds
// its table of instantiations from the same list (engine_detail.hpp), so adding a sub-model or widening
// reachable_from_scenes never means writing a table by hand.
//
// The full valid product is 16 laws (8 without rolling) and 24 variants (rolling only with rotation),
// each a wall pass, a pair pass in 4 forms and a coefficient table; the scenes reach 6 of them: the
// two scene laws (kHertzThorntonLaw, kLinearSpringDashpotLaw), each without rotation, with rotation, and
// with rotation and rolling resistance. Only those are compiled.
#include <array>
#include <bit>
#include <cstddef>

#include "libspread/core/effect_registry.hpp"
#include "libspread/physics/dem/contact_law.hpp"
#include "libspread/physics/dem/contact_laws.hpp"

namespace spread::dem {

// The DEM effects that change a pass's instantiation (a template parameter): rotation (spin state and
// contact moments). The others do not shape a pass: particle_contact and wall_contact decide whether a
// pass runs at all (force_dispatch.cpp), and rolling is the law's rolling sub-model.
inline constexpr effect::EffectSet kPassEffects = effect::kRotation;
// The DEM effects that decide whether a pass runs at all (force_dispatch.cpp) or which law runs (rolling: the
// law's rolling model), rather than shaping a pass.
inline constexpr effect::EffectSet kRunEffects = effect::kParticleContact | effect::kWallContact | effect::kRolling;
// A DEM row of the registry in neither set would be accepted by the engine and never evaluated.
static_assert((kPassEffects | kRunEffects) == effect::kDemEffects && (kPassEffects & kRunEffects) == 0,
              "each DEM effect of the registry either shapes the passes (kPassEffects, read in a pass as V::has(bit)) "
              "or decides which pass or law runs (kRunEffects)");

struct ForceVariant {
  ContactLaw law;
  effect::EffectSet effects = 0;  // a subset of kPassEffects
  constexpr bool rotation() const { return (effects & effect::kRotation) != 0; }
  friend constexpr bool operator==(const ForceVariant&, const ForceVariant&) = default;
};

namespace detail {

inline constexpr std::size_t kNormals = NormalModels::size, kDampings = DampingModels::size,
                             kTangentials = TangentialModels::size, kRollings = RollingModels::size;
inline constexpr std::size_t kPassEffectSubsets = std::size_t{1} << std::popcount(kPassEffects);
inline constexpr std::size_t kProductSize = kNormals * kDampings * kTangentials * kRollings * kPassEffectSubsets;

// Subset number k of `mask`: bit j of k becomes the j-th lowest bit of the mask.
constexpr effect::EffectSet subset_of(effect::EffectSet mask, std::size_t k) {
  effect::EffectSet set = 0;
  for (effect::EffectSet rest = mask; rest != 0; rest &= rest - 1, k >>= 1)
    if ((k & 1) != 0) set |= rest & ~(rest - 1);
  return set;
}

// Position in the product → combination (pass-shaping effects fastest, then rolling, tangential, damping,
// normal).
constexpr ForceVariant product_variant(std::size_t i) {
  ForceVariant v;
  v.effects = subset_of(kPassEffects, i % kPassEffectSubsets);
  i /= kPassEffectSubsets;
  v.law.rolling = static_cast<RollingModel>(i % kRollings);
  i /= kRollings;
  v.law.tangential = static_cast<TangentialModel>(i % kTangentials);
  i /= kTangentials;
  v.law.damping = static_cast<DampingModel>(i % kDampings);
  v.law.normal = static_cast<NormalModel>(i / kDampings);
  return v;
}

// What scenes reach: the two named laws, rolling resistance or none (scene_config.cpp, drum_simulation.cpp).
constexpr bool reachable_from_scenes(const ContactLaw& law) {
  const ContactLaw without_rolling = with_rolling(law, RollingModel::kNone);
  return without_rolling == kHertzThorntonLaw || without_rolling == kLinearSpringDashpotLaw;
}

constexpr bool instantiated(const ForceVariant& v) {
  return contact_law_conflict(v.law, v.rotation()) == nullptr && reachable_from_scenes(v.law);
}

constexpr std::size_t count_instantiated() {
  std::size_t n = 0;
  for (std::size_t i = 0; i < kProductSize; ++i) n += instantiated(product_variant(i)) ? 1 : 0;
  return n;
}

}  // namespace detail

inline constexpr std::size_t kForceVariantCount = detail::count_instantiated();

// The instantiated variants, in product order.
inline constexpr std::array<ForceVariant, kForceVariantCount> kForceVariants = [] {
  std::array<ForceVariant, kForceVariantCount> out{};
  std::size_t n = 0;
  for (std::size_t i = 0; i < detail::kProductSize; ++i)
    if (detail::instantiated(detail::product_variant(i))) out[n++] = detail::product_variant(i);
  return out;
}();

// The law type of variant I.
template <std::size_t I>
using VariantLaw = ComposedLaw<typename SubModelAt<static_cast<std::size_t>(kForceVariants[I].law.normal), NormalModels>::type,
                               typename SubModelAt<static_cast<std::size_t>(kForceVariants[I].law.damping), DampingModels>::type,
                               typename SubModelAt<static_cast<std::size_t>(kForceVariants[I].law.tangential), TangentialModels>::type,
                               typename SubModelAt<static_cast<std::size_t>(kForceVariants[I].law.rolling), RollingModels>::type>;
// Variant I as the one type the passes are templated on: its law and its pass-shaping effects. A new
// pass-shaping effect is a new bit of kPassEffects, read in a pass as V::has(bit): no pass's signature
// changes.
template <std::size_t I>
struct PassVariant {
  using Law = VariantLaw<I>;
  static constexpr effect::EffectSet kEffects = kForceVariants[I].effects;
  static constexpr bool has(effect::EffectSet bit) { return (kEffects & bit) != 0; }
  static constexpr bool kRotation = has(effect::kRotation);
};

// Position of (law, effects & kPassEffects) in kForceVariants; throws std::invalid_argument naming the law
// when it is invalid (validate_contact_law) or valid but not instantiated (and which are).
std::size_t find_force_variant(const ContactLaw& law, effect::EffectSet effects);

}  // namespace spread::dem
