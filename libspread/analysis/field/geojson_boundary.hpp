#pragma once
// A field boundary from a GeoJSON file (RFC 7946): a Polygon geometry, a Feature holding one, or a
// FeatureCollection whose first Polygon feature is taken. The outer ring, in the file's coordinates:
// longitude/latitude by RFC 7946, unless the file names its CRS in the older "crs" member (GeoJSON 2008:
// {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::25832"}}), as many GIS exports still do.
#include <string>

#include "libspread/analysis/field/field_geometry.hpp"

namespace spread::field {

struct SourceRing {
  Ring ring;            // the outer ring's vertices, the closing repeat dropped (x = longitude in lon/lat)
  std::string crs;      // "EPSG:25832" from the file's crs member, or "" (RFC 7946: longitude/latitude)
  std::string where;    // the file, for messages
};

// Throws spread::Error naming the file and what is wrong: no such file (kMissing), not JSON, no Polygon,
// a MultiPolygon or holes (one field, no obstacles), a ring whose last vertex is not its first (open),
// a position that is not two or three numbers (kCorrupt).
SourceRing read_geojson_boundary(const std::string& path);
// The same from the text of a GeoJSON document; `where` names it in messages.
SourceRing parse_geojson_boundary(const std::string& text, const std::string& where);

}  // namespace spread::field
