#include "tools/spread/blend_output.hpp"

#include <cmath>
#include <iostream>
#include <string>

#include "tools/spread/number_format.hpp"

namespace spread::cli {
// The helpers in a namespace of their own: the CLI's files compile together (tools/spread/CMakeLists.txt).
namespace blend_output {
namespace {

using nlohmann::json;

json number_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

std::string nutrients_text(const blends::ComponentPattern& c) {
  std::string text;
  for (int k = 0; k < tables::kNutrientCount; ++k) {
    const double pct = c.nutrient_pct[static_cast<std::size_t>(k)];
    if (pct > 0.0) text += (text.empty() ? "" : ", ") + format("%g %% ", pct) + tables::kNutrients[k].name;
  }
  return text.empty() ? "no nutrients given" : text;
}

}  // namespace
}  // namespace blend_output

std::string widest_common_bout_text(const blends::BlendPatterns& b, double cv_target) {
  if (b.limiting_component < 0) return "no component predicted";
  const blends::ComponentPattern& limit = b.components[static_cast<std::size_t>(b.limiting_component)];
  if (!(b.widest_common_bout_m > 0.0))
    return "no bout width: " + limit.name + format(" does not meet CV <= %g %% at any bout", 100.0 * cv_target);
  return format("%.2f m", b.widest_common_bout_m) + ", limited by " + limit.name +
         format(" (its CV rises above %g %% there)", 100.0 * cv_target);
}

void print_blend(const blends::BlendPatterns& b, double cv_target) {
  std::cout << "blend " << b.blend << ": widest bout at which every component meets CV <= "
            << format("%g %%", 100.0 * cv_target) << ": " << widest_common_bout_text(b, cv_target) << "\n";
  std::cout << format("  at the %.2f m bout: blend CV ", b.bout_width_m) << format("%.1f %% to-and-fro", 100.0 * b.cv_to_and_fro)
            << format(", %.1f %% racetrack", 100.0 * b.cv_racetrack) << format("; separation index %.3f", b.separation_index) << "\n";
  std::cout << "  components (mass share, mean landing radius R, CV alone at the bout, its own widest bout, CV of its share across the bout):\n";
  for (const blends::ComponentPattern& c : b.components) {
    std::cout << "    " << c.name << std::string(c.name.size() < 22 ? 22 - c.name.size() : 1, ' ')
              << format("%5.1f %%", 100.0 * c.mass_fraction) << format("  R %.2f m", c.mean_radius_m)
              << format("  CV %.1f %% to-and-fro", 100.0 * c.cv_to_and_fro) << format(", %.1f %% racetrack", 100.0 * c.cv_racetrack)
              << format("  alone to %.2f m", c.widest_width_m) << format("  share CV %.3f", c.share_cv) << "  ("
              << blend_output::nutrients_text(c) << ")\n";
  }
  for (const blends::NutrientPattern& n : b.nutrients) {
    if (!n.carried) continue;
    std::cout << "  nutrient " << n.name << format(": CV %.1f %% to-and-fro", 100.0 * n.cv_to_and_fro) << format(", %.1f %% racetrack", 100.0 * n.cv_racetrack)
              << "\n";
  }
}

nlohmann::json blend_json(const blends::BlendPatterns& b, double cv_target) {
  using blend_output::number_or_null;
  using nlohmann::json;
  nlohmann::json components = nlohmann::json::array(), nutrients = nlohmann::json::array();
  for (const blends::ComponentPattern& c : b.components) {
    nlohmann::json pct = nlohmann::json::object();
    for (int k = 0; k < tables::kNutrientCount; ++k) pct[tables::kNutrients[k].key] = c.nutrient_pct[static_cast<std::size_t>(k)];
    components.push_back({{"name", c.name},
                          {"material", c.material},
                          {"mass_fraction", c.mass_fraction},
                          {"nutrients_percent", pct},
                          {"mean_radius_m", number_or_null(c.mean_radius_m)},
                          {"cv_to_and_fro_percent", number_or_null(100.0 * c.cv_to_and_fro)},
                          {"cv_racetrack_percent", number_or_null(100.0 * c.cv_racetrack)},
                          {"widest_width_m", number_or_null(c.widest_width_m)},
                          {"share_cv", number_or_null(c.share_cv)},
                          {"tray_mass_fraction", c.tray_mass_fraction}});
  }
  for (const blends::NutrientPattern& n : b.nutrients) {
    if (!n.carried) continue;
    nutrients.push_back({{"name", n.name},
                         {"cv_to_and_fro_percent", number_or_null(100.0 * n.cv_to_and_fro)},
                         {"cv_racetrack_percent", number_or_null(100.0 * n.cv_racetrack)}});
  }
  const bool limited = b.limiting_component >= 0;
  return {{"name", b.blend},
          {"cv_target_percent", 100.0 * cv_target},
          {"widest_common_bout_m", b.widest_common_bout_m},
          {"limiting_component", limited ? json(b.components[static_cast<std::size_t>(b.limiting_component)].name) : json(nullptr)},
          {"bout_width_m", b.bout_width_m},
          {"cv_to_and_fro_percent", number_or_null(100.0 * b.cv_to_and_fro)},
          {"cv_racetrack_percent", number_or_null(100.0 * b.cv_racetrack)},
          {"separation_index", number_or_null(b.separation_index)},
          {"tray_width_m", b.trays.tray_width_m},
          {"tray_count", b.trays.tray_count},
          {"tray_mass_fraction", b.tray_mass_fraction},
          {"components", components},
          {"nutrients", nutrients}};
}

}  // namespace spread::cli
