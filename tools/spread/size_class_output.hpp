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
// A PNG of the fine and the coarse half's patterns across the driving direction (each tray's share of the
// discharged mass; the fine half with its profile overlapped at the bout), on the wider of the two
// layouts. Throws as plot::write_transverse_png does (and without plots, plot::kWithoutPlots).
void write_size_halves_png(const size_classes::SizeClassPatterns& patterns, const std::string& path);
nlohmann::json size_classes_json(const size_classes::SizeClassPatterns& patterns);

}  // namespace spread::cli
