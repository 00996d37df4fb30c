#pragma once
// The force pass's instantiations, generated from the sub-model families (contact_laws.hpp) and the pass's
// own family (spin): one choice per family, each with an explicit none, and of the valid product
// (contact_law_conflict) only what a scene reaches. The engine picks one by its position once
// (find_force_variant); each pass file builds its table of instantiations from the same list
// (engine_detail.hpp), so adding a sub-model or widening the reach never means writing a table by hand.
//
// The product is 3 · 3 · 3 · 2 · 1 (normal, damping, tangential, rolling, cohesion) · 2 (spin) = 108
// entries, 24 valid; the scenes reach 6: the two scene laws (kHertzThorntonLaw, kLinearSpringDashpotLaw),
// each without spin, with spin, and with spin and rolling resistance. Only those are compiled, each a wall
// pass, a pair pass in its forms and a coefficient table. An add-on family's model (cohesion) other than none
// is compiled with the combinations it names (kCompiledWith): a cohesion model named with one adds one
// variant, where a pass-shaping bit of its own doubled them all.
#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "libspread/core/effect_registry.hpp"
#include "libspread/physics/dem/contact_law.hpp"
#include "libspread/physics/dem/contact_laws.hpp"

namespace spread::dem {

// The DEM effects that change a pass's instantiation: rotation (spin state and contact moments), the pass's
// spin family (SpinModel). The others do not shape a pass: particle_contact and wall_contact decide whether
// a pass runs at all (force_dispatch.cpp), and rolling is the law's rolling sub-model.
inline constexpr effect::EffectSet kPassEffects = effect::kRotation;
// The DEM effects that decide whether a pass runs at all (force_dispatch.cpp) or which law runs (rolling: the
// law's rolling model), rather than shaping a pass.
inline constexpr effect::EffectSet kRunEffects = effect::kParticleContact | effect::kWallContact | effect::kRolling;
// A DEM row of the registry in neither set would be accepted by the engine and never evaluated.
static_assert((kPassEffects | kRunEffects) == effect::kDemEffects && (kPassEffects & kRunEffects) == 0,
              "each DEM effect of the registry either shapes the passes (kPassEffects: a family of the pass, "
              "ForceVariant, with an explicit none) or decides which pass or law runs (kRunEffects)");

// The pass's own family, from the rotation effect: no spin state, or rigid-body spin (contact moments).
enum class SpinModel : std::uint8_t { kNone, kRigid };
inline constexpr std::size_t kSpinModels = 2;

struct ForceVariant {
  ContactLaw law;
  SpinModel spin = SpinModel::kNone;
  constexpr bool rotation() const { return spin == SpinModel::kRigid; }
  // The pass-shaping effects this variant's passes carry (a subset of kPassEffects).
  constexpr effect::EffectSet effects() const { return rotation() ? effect::kRotation : effect::EffectSet{0}; }
  friend constexpr bool operator==(const ForceVariant&, const ForceVariant&) = default;
};
// The variant of a law under the engine's effects (only kPassEffects shape it).
constexpr ForceVariant force_variant_of(const ContactLaw& law, effect::EffectSet effects) {
  return ForceVariant{.law = law, .spin = (effects & effect::kRotation) != 0 ? SpinModel::kRigid : SpinModel::kNone};
}

namespace detail {

inline constexpr std::size_t kNormals = NormalModels::size, kDampings = DampingModels::size,
                             kTangentials = TangentialModels::size, kRollings = RollingModels::size,
                             kCohesions = CohesionModels::size;
inline constexpr std::size_t kProductSize = kNormals * kDampings * kTangentials * kRollings * kCohesions * kSpinModels;

// Position in the product → combination (spin fastest, then rolling, tangential, damping, normal; the add-on
// family cohesion slowest, so that a new model's variants come after every variant there was, whose positions
// stay as they were).
constexpr ForceVariant product_variant(std::size_t i) {
  ForceVariant v;
  v.spin = static_cast<SpinModel>(i % kSpinModels);
  i /= kSpinModels;
  v.law.rolling = static_cast<RollingModel>(i % kRollings);
  i /= kRollings;
  v.law.tangential = static_cast<TangentialModel>(i % kTangentials);
  i /= kTangentials;
  v.law.damping = static_cast<DampingModel>(i % kDampings);
  i /= kDampings;
  v.law.normal = static_cast<NormalModel>(i % kNormals);
  v.law.cohesion = static_cast<CohesionModel>(i / kNormals);
  return v;
}

// What scenes reach without an add-on model: the two named laws, rolling resistance or none, spin or none
// (scene_config.cpp, drum_simulation.cpp).
constexpr bool reachable_from_scenes(const ContactLaw& law) {
  const ContactLaw base = with_cohesion(with_rolling(law, RollingModel::kNone), CohesionModel::kNone);
  return base == kHertzThorntonLaw || base == kLinearSpringDashpotLaw;
}

// Whether add-on model `id` of `List` is compiled with `base` (none: with every one; another: with those of
// its kCompiledWith).
template <class List, std::size_t... I>
constexpr bool compiled_with(std::size_t id, const BaseCombination& base, std::index_sequence<I...>) {
  const auto named = [&](const auto& model) {
    using Model = std::remove_cvref_t<decltype(model)>;
    if constexpr (!Model::kActive) {
      return true;
    } else {
      for (const BaseCombination& c : Model::kCompiledWith)
        if (c.law == base.law && c.rotation == base.rotation) return true;
      return false;
    }
  };
  return ((id == I && named(typename SubModelAt<I, List>::type{})) || ...);
}

constexpr bool instantiated(const ForceVariant& v) {
  if (contact_law_conflict(v.law, v.rotation()) != nullptr || !reachable_from_scenes(v.law)) return false;
  const BaseCombination base{.law = with_cohesion(v.law, CohesionModel::kNone), .rotation = v.rotation()};
  return compiled_with<CohesionModels>(static_cast<std::size_t>(v.law.cohesion), base,
                                       std::make_index_sequence<CohesionModels::size>{});
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
                               typename SubModelAt<static_cast<std::size_t>(kForceVariants[I].law.rolling), RollingModels>::type,
                               typename SubModelAt<static_cast<std::size_t>(kForceVariants[I].law.cohesion), CohesionModels>::type>;
// Variant I as the one type the passes are templated on: its law and its spin. A new pass-shaping effect is
// a new family of ForceVariant (none first), read in a pass as V::kThatFamily: no pass's signature changes.
template <std::size_t I>
struct PassVariant {
  using Law = VariantLaw<I>;
  static constexpr effect::EffectSet kEffects = kForceVariants[I].effects();
  static constexpr bool has(effect::EffectSet bit) { return (kEffects & bit) != 0; }
  static constexpr bool kRotation = kForceVariants[I].rotation();
};

// Position of force_variant_of(law, effects) in kForceVariants; throws std::invalid_argument naming the law
// when it is invalid (validate_contact_law) or valid but not instantiated (and which are).
std::size_t find_force_variant(const ContactLaw& law, effect::EffectSet effects);

}  // namespace spread::dem
