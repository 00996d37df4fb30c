#pragma once
// A contact law as five sub-models chosen independently (docs/design.md §7: no fused type per combination):
// the normal elastic force, the normal damping, the tangential force, the rolling resistance and the
// cohesion, each family with an explicit `none` (one choice per family). This header is the run-time
// description; the evaluators are the sub-model types (normal_models.hpp, damping_models.hpp,
// tangential_models.hpp, rolling_models.hpp, cohesion_models.hpp) put together by ComposedLaw
// (contact_laws.hpp). Each enumerator's value is its type's position in the lists of
// contact_laws.hpp (checked there at compile time).
#include <cstdint>
#include <string>

namespace spread::dem {

enum class NormalModel : std::uint8_t { kNone, kLinear, kHertz };
enum class DampingModel : std::uint8_t { kNone, kLinearViscous, kHertz };
enum class TangentialModel : std::uint8_t { kNone, kLinear, kThornton };
enum class RollingModel : std::uint8_t { kNone, kConstantTorque };
// An attraction between touching bodies; an add-on family: a model other than none is compiled only with
// the combinations it names (its kCompiledWith, force_variants.hpp), so each adds that many variants.
enum class CohesionModel : std::uint8_t { kNone };

struct ContactLaw {
  NormalModel normal = NormalModel::kHertz;
  DampingModel damping = DampingModel::kHertz;
  TangentialModel tangential = TangentialModel::kThornton;
  RollingModel rolling = RollingModel::kNone;
  CohesionModel cohesion = CohesionModel::kNone;
  friend constexpr bool operator==(const ContactLaw&, const ContactLaw&) = default;
};

// Seed 000 Eqs. 16–25: Hertz normal, δ^{1/4} damping, Thornton's incremental tangential law.
inline constexpr ContactLaw kHertzThorntonLaw{.normal = NormalModel::kHertz, .damping = DampingModel::kHertz,
                                              .tangential = TangentialModel::kThornton, .rolling = RollingModel::kNone,
                                              .cohesion = CohesionModel::kNone};
// Seed 001: linear springs, dashpots from the restitution, Coulomb slider.
inline constexpr ContactLaw kLinearSpringDashpotLaw{.normal = NormalModel::kLinear, .damping = DampingModel::kLinearViscous,
                                                    .tangential = TangentialModel::kLinear, .rolling = RollingModel::kNone,
                                                    .cohesion = CohesionModel::kNone};

constexpr ContactLaw with_rolling(ContactLaw law, RollingModel rolling) {
  law.rolling = rolling;
  return law;
}
constexpr ContactLaw with_cohesion(ContactLaw law, CohesionModel cohesion) {
  law.cohesion = cohesion;
  return law;
}

// A combination an add-on model (cohesion) is compiled with: the law (its cohesion none) and the spin.
struct BaseCombination {
  ContactLaw law;
  bool rotation;
};

// Why these sub-models cannot run together (with rotation on or off), or nullptr when they can. The one
// rule set behind both the engine's start-up check and the compile-time list of instantiated laws.
constexpr const char* contact_law_conflict(const ContactLaw& law, bool rotation) {
  if (law.normal == NormalModel::kNone)
    return "the normal model is 'none': the engine needs one (its time step is the contact time t_c / N_c)";
  // The damping ratios are fitted to one normal law each (restitution.hpp): γ(e) to F = k δ^{3/2} + c δ^{1/4} δ̇,
  // ζ(e) to F = k δ + c δ̇; and the linear dashpot c_n = 2ζ √(M* k_n) needs a stiffness in N/m.
  if (law.damping == DampingModel::kHertz && law.normal != NormalModel::kHertz)
    return "damping 'hertz' (c_n δ^{1/4}, seed 000 Eqs. 17–18) needs the 'hertz' normal model";
  if (law.damping == DampingModel::kLinearViscous && law.normal != NormalModel::kLinear)
    return "damping 'linear_viscous' (c_n = 2ζ √(M* k_n), seed 001) needs the 'linear' normal model";
  // Thornton's k_t = 8 G* a with the Hertz contact radius a = √(R* δ) (Eq. 19); the linear tangential spring
  // is k_t = tangential_ratio · k_n of the linear normal spring. Both are capped by μ F_n (Eq. 6).
  if (law.tangential == TangentialModel::kThornton && law.normal != NormalModel::kHertz)
    return "tangential 'thornton' (k_t = 8 G* √(R* δ), Eq. 19) needs the 'hertz' normal model (its contact radius)";
  if (law.tangential == TangentialModel::kLinear && law.normal != NormalModel::kLinear)
    return "tangential 'linear' (k_t = tangential_ratio · k_n) needs the 'linear' normal model (its spring k_n)";
  if (law.rolling == RollingModel::kConstantTorque && !rotation)
    return "rolling 'constant_torque' acts on the particles' spin: it needs the 'rotation' effect";
  return nullptr;
}

// "normal hertz, damping hertz, tangential thornton, rolling none, cohesion none": the sub-models' names.
std::string to_string(const ContactLaw& law);

// Throws std::invalid_argument("contact law (normal …, …): <conflict>") when contact_law_conflict finds one.
void validate_contact_law(const ContactLaw& law, bool rotation);

}  // namespace spread::dem
