#pragma once
// A field's boundary in metres, validated: a simple polygon (no edge crosses another), counter-clockwise,
// of a size a field can have. Obstacles are not modelled: the outer ring alone.
#include <string>

#include "libspread/analysis/field/field_geometry.hpp"

namespace spread::field {

// Sizes outside these are not a field in metres: a boundary of 0.0003 m² is one in degrees read as metres,
// one of a million hectares one in centimetres or a wrong projection.
inline constexpr double kMinFieldArea_m2 = 100.0;
inline constexpr double kMaxFieldArea_m2 = 1e8;  // 10,000 ha

struct Boundary {
  Ring ring;                 // counter-clockwise, metres
  std::string crs;           // the projected CRS the metres are in ("EPSG:32632"), or "local"
  double area_m2 = 0.0;
  // Bounding box (m).
  double min_x_m = 0.0, min_y_m = 0.0, max_x_m = 0.0, max_y_m = 0.0;
};

// Validates `ring` (metres, either orientation, not closed) and makes the boundary. Throws spread::Error
// (kArgument, `where`) naming what is wrong: fewer than 3 vertices, a repeated vertex (a zero-length edge),
// two edges that cross (which, and where along the ring), an area outside [kMinFieldArea_m2,
// kMaxFieldArea_m2] (with the likely wrong unit).
Boundary make_boundary(Ring ring, std::string crs, const std::string& where);

}  // namespace spread::field
