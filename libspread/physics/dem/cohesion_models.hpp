#pragma once
// Cohesion sub-models of a contact law (contact_law.hpp): an attraction between touching bodies, along the
// contact normal, added to the force after the friction cap (which takes the repulsive F_n). An add-on
// family: a model other than none names the combinations it is compiled with (kCompiledWith: law and spin,
// force_variants.hpp), one force variant each, so adding a model never copies every variant.
#include "libspread/physics/dem/contact_law.hpp"

namespace spread::dem {

struct CohesionNone {
  static constexpr CohesionModel kId = CohesionModel::kNone;
  static constexpr const char* kName = "none";
  static constexpr bool kActive = false;
  struct Coeffs {};
};

}  // namespace spread::dem
