#pragma once
// `spread predict --size-classes`: the launched granules' SGN and UI, each size class's share, mean
// landing radius and CV alone at the product's bout, the fine and coarse halves of the mass, and the
// pattern per class (libspread/analysis/size_classes), as text and as the JSON object "size_classes".
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "libspread/analysis/size_classes/size_class_patterns.hpp"

namespace spread::cli {

// "2,2.5,3.15,4,5" → the class boundaries in mm; BadInput naming --size-class-mm when not positive and
// increasing numbers.
std::vector<double> parse_size_class_boundaries_mm(const std::string& text);

void print_size_classes(const size_classes::SizeClassPatterns& patterns);
nlohmann::json size_classes_json(const size_classes::SizeClassPatterns& patterns);

}  // namespace spread::cli
