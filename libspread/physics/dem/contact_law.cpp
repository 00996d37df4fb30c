// Names and start-up checks of composed contact laws, and the engine's choice among the instantiated
// force variants (force_variants.hpp).
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

#include "libspread/physics/dem/contact_law.hpp"
#include "libspread/physics/dem/contact_laws.hpp"
#include "libspread/physics/dem/force_variants.hpp"

namespace spread::dem {

namespace {
template <class List, class Id, std::size_t... I>
const char* name_in(Id id, std::index_sequence<I...>) {
  const char* name = "?";
  ((static_cast<std::size_t>(id) == I ? (name = SubModelAt<I, List>::type::kName, true) : false) || ...);
  return name;
}
template <class List, class Id>
const char* name_in(Id id) {
  return name_in<List>(id, std::make_index_sequence<List::size>{});
}
std::string describe(const ForceVariant& v) {
  const std::string effects = effect::to_string(v.effects());
  return "(" + to_string(v.law) + (effects.empty() ? ", no pass-shaping effect)" : ", with " + effects + ")");
}
}  // namespace

std::string to_string(const ContactLaw& law) {
  return std::string("normal ") + name_in<NormalModels>(law.normal) + ", damping " + name_in<DampingModels>(law.damping) +
         ", tangential " + name_in<TangentialModels>(law.tangential) + ", rolling " + name_in<RollingModels>(law.rolling) +
         ", cohesion " + name_in<CohesionModels>(law.cohesion);
}

void validate_contact_law(const ContactLaw& law, bool rotation) {
  if (const char* conflict = contact_law_conflict(law, rotation))
    throw std::invalid_argument("contact law (" + to_string(law) + "): " + conflict);
}

std::size_t find_force_variant(const ContactLaw& law, effect::EffectSet effects) {
  validate_contact_law(law, (effects & effect::kRotation) != 0);
  const ForceVariant wanted = force_variant_of(law, effects);
  for (std::size_t i = 0; i < kForceVariants.size(); ++i)
    if (kForceVariants[i] == wanted) return i;
  std::string known;
  for (const ForceVariant& v : kForceVariants) known += "\n  " + describe(v);
  throw std::invalid_argument("contact law " + describe(wanted) +
                              " is valid but not compiled into the force pass (force_variants.hpp "
                              "reachable_from_scenes, a cohesion model's kCompiledWith); compiled:" + known);
}

}  // namespace spread::dem
