#pragma once
// From a boundary's source coordinates to metres, with PROJ (Debian libproj-dev):
//   - longitude/latitude (RFC 7946 GeoJSON, crs ""): projected to the UTM zone of the ring's mean
//     position, WGS 84 / UTM zone N (EPSG:326NN) north of the equator, S (EPSG:327NN) south of it — a
//     transverse Mercator with scale factor 0.9996, whose scale error across a 6° zone stays below
//     0.04 %: a field's areas and distances in metres to that;
//   - a projected CRS ("EPSG:25832"): taken as metres as they are, after checking that the CRS is in
//     metres and that the ring lies inside the CRS's area of use (a UTM-north CRS given southern
//     northings, or the wrong zone, is named);
//   - "local": already metres in a frame of the user's.
#include <string>

#include "libspread/analysis/field/geojson_boundary.hpp"

namespace spread::field {

struct ProjectedRing {
  Ring ring;          // metres
  std::string crs;    // the CRS of the metres ("EPSG:32632", or "local")
};

// Throws spread::Error (kArgument, source.where) naming what is wrong: longitude/latitude outside
// ±180°/±90° (the file is in metres: name its CRS), latitudes beyond UTM's ±84°, an unknown CRS, a CRS
// not in metres, a ring outside the CRS's area of use (with the area and the position: wrong hemisphere
// or zone).
ProjectedRing project_to_metres(const SourceRing& source);

// Longitude/latitude points (degrees, x = longitude) into `crs` (a projected CRS, as a boundary's); the
// same checks as a ring. "local" cannot take longitude/latitude: refused.
Ring lon_lat_to(const Ring& lon_lat, const std::string& crs, const std::string& where);

// The WGS 84 / UTM CRS for a longitude/latitude (degrees): "EPSG:326NN" or "EPSG:327NN".
std::string utm_crs_for(double longitude_deg, double latitude_deg);

}  // namespace spread::field
