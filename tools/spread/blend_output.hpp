#pragma once
// A blend's answer on the command line (`spread predict` and `spread chart` with a blend's name): each
// component's share, mean landing radius and CV at the bout, the blend's total CV, each nutrient's CV, the
// separation index, and the widest bout at which every component meets the target with the component
// that limits it (libspread/analysis/blends), as text and as the JSON object "blend".
#include <nlohmann/json.hpp>

#include "libspread/analysis/blends/blend_patterns.hpp"

namespace spread::cli {

void print_blend(const blends::BlendPatterns& blend, double cv_target);
nlohmann::json blend_json(const blends::BlendPatterns& blend, double cv_target);
// "limited by <component> (its CV rises above 15 % beyond 12.50 m)", or why there is no common bout.
std::string widest_common_bout_text(const blends::BlendPatterns& blend, double cv_target);

}  // namespace spread::cli
