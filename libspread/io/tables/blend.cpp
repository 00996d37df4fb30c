// A blend's components checked as a whole (table_format.hpp): what a scene, a table writer and a reader
// all require of a blend before anything is fed, written or predicted from it.
#include <cmath>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "libspread/io/tables/table_format.hpp"

namespace spread::tables {

std::string blend_component_name(const std::string& blend, const std::string& component) {
  return blend + " / " + component;
}

namespace {
std::string number_text(double value) {
  std::ostringstream out;
  out.precision(6);
  out << value;
  return out.str();
}

}  // namespace

std::string blend_component_problem(const BlendComponent& c) {
  if (c.material.name.empty()) return "name: must be given and not empty";
  if (c.material.is_blend()) return "components: a component cannot be a blend itself";
  if (!(c.mass_fraction > 0.0 && c.mass_fraction <= 1.0))
    return "mass_fraction: must be in (0, 1], got " + number_text(c.mass_fraction);
  double nutrients_pct = 0.0;
  for (const Nutrient& nutrient : kNutrients) {
    const double pct = c.*nutrient.member;
    if (!(pct >= 0.0 && pct <= 100.0)) return std::string(nutrient.key) + ": must be in [0, 100] (% of the component's mass), got " + number_text(pct);
    nutrients_pct += pct;
  }
  if (nutrients_pct > 100.0)
    return "n_pct: the nutrient contents sum to " + number_text(nutrients_pct) + " %, more than the component's mass";
  return {};
}

std::string blend_problem(const std::vector<BlendComponent>& components) {
  if (components.empty()) return "components: a blend needs at least one component";
  std::set<std::string> names;
  double sum = 0.0;
  for (std::size_t i = 0; i < components.size(); ++i) {
    const std::string at = "components[" + std::to_string(i) + "].";
    const std::string problem = blend_component_problem(components[i]);
    if (!problem.empty()) return at + problem;
    if (!names.insert(components[i].material.name).second)
      return at + "name: component \"" + components[i].material.name + "\" listed twice";
    sum += components[i].mass_fraction;
  }
  if (!(std::abs(sum - 1.0) <= kBlendFractionTolerance))
    return "components: the mass fractions must sum to 1 (within " + number_text(kBlendFractionTolerance) +
           "), got " + number_text(sum);
  return {};
}

BlendComponent as_blend_component(const BlendRowComponent& row) {
  BlendComponent c;
  c.material.name = row.material;
  c.mass_fraction = row.mass_fraction;
  c.n_pct = row.n_pct;
  c.p2o5_pct = row.p2o5_pct;
  c.k2o_pct = row.k2o_pct;
  return c;
}

std::string stored_blend_problem(const Blend& blend) {
  std::vector<BlendComponent> components;
  for (const BlendRowComponent& row : blend.components) components.push_back(as_blend_component(row));
  const std::string problem = blend_problem(components);
  return problem.empty() ? problem : "blend " + blend.name + ": " + problem;
}

}  // namespace spread::tables
