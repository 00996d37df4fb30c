#pragma once
// Picks kg, g or mg for tray masses so the axis numbers stay between 1 and 1000.
#include <string>

namespace spread::plot::detail {

struct MassUnit {
  std::string name;  // "kg", "g", "mg"
  double per_kg;     // numbers shown = mass_kg * per_kg
};

inline MassUnit mass_unit_for(double max_mass_kg) {
  if (max_mass_kg >= 1.0) return {"kg", 1.0};
  if (max_mass_kg >= 1e-3) return {"g", 1e3};
  return {"mg", 1e6};
}

}  // namespace spread::plot::detail
