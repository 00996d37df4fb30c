// GeoJSON boundary reader (RFC 7946 §3.1.6: a linear ring is closed, its first and last positions
// equivalent; §3.1.1: a position is longitude, latitude[, altitude]).
#include "libspread/analysis/field/geojson_boundary.hpp"

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "libspread/core/error.hpp"

namespace spread::field {
namespace {

using nlohmann::json;

[[noreturn]] void refuse_geojson(const std::string& where, const std::string& what) {
  throw Error(ErrorKind::kCorrupt, where, where + ": " + what);
}

// The Polygon geometry of the document: itself, its Feature's, or its FeatureCollection's first.
const json& polygon_of(const json& doc, const std::string& where) {
  const std::string type = doc.value("type", "");
  if (type == "Polygon") return doc;
  if (type == "Feature") {
    if (!doc.contains("geometry") || !doc["geometry"].is_object()) refuse_geojson(where, "the Feature has no geometry");
    return polygon_of(doc["geometry"], where);
  }
  if (type == "FeatureCollection" && doc.contains("features") && doc["features"].is_array()) {
    for (const json& feature : doc["features"]) {
      if (feature.contains("geometry") && feature["geometry"].is_object() &&
          feature["geometry"].value("type", "") == "Polygon") {
        return feature["geometry"];
      }
    }
    refuse_geojson(where, "the FeatureCollection holds no Polygon feature (a field boundary is one Polygon)");
  }
  if (type == "MultiPolygon") refuse_geojson(where, "a MultiPolygon: give one field, one Polygon, per file");
  refuse_geojson(where, "GeoJSON of type '" + type + "': a field boundary is a Polygon (or a Feature holding one)");
}

Point position(const json& p, std::size_t index, const std::string& where) {
  if (!p.is_array() || p.size() < 2 || p.size() > 3 || !p[0].is_number() || !p[1].is_number()) {
    refuse_geojson(where, "position " + std::to_string(index) + " of the outer ring is " + p.dump() +
                      ", not [x, y] or [x, y, z] numbers");
  }
  return {p[0].get<double>(), p[1].get<double>()};
}

std::string crs_of(const json& doc) {
  if (!doc.contains("crs")) return "";
  const json& crs = doc["crs"];
  std::string name = crs.contains("properties") ? crs["properties"].value("name", "") : "";
  // urn:ogc:def:crs:EPSG::25832 → EPSG:25832; CRS84 stays longitude/latitude.
  const std::string urn = "urn:ogc:def:crs:";
  if (name.rfind(urn, 0) == 0) {
    name = name.substr(urn.size());
    const auto colons = name.find("::");
    if (colons != std::string::npos) name = name.substr(0, colons) + ":" + name.substr(colons + 2);
  }
  if (name == "OGC:1.3:CRS84" || name == "OGC:CRS84" || name == "EPSG:4326") return "";
  return name;
}

}  // namespace

SourceRing parse_geojson_boundary(const std::string& text, const std::string& where) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    refuse_geojson(where, std::string("not JSON: ") + e.what());
  }
  const json& polygon = polygon_of(doc, where);
  const json& rings = polygon["coordinates"];
  if (!rings.is_array() || rings.empty() || !rings[0].is_array()) refuse_geojson(where, "the Polygon has no coordinates");
  if (rings.size() > 1) {
    refuse_geojson(where, "the Polygon has " + std::to_string(rings.size() - 1) +
                      " hole(s): obstacles inside a field are not modelled; give the outer ring alone");
  }
  SourceRing out;
  out.where = where;
  out.crs = crs_of(doc);
  const json& ring = rings[0];
  for (std::size_t i = 0; i < ring.size(); ++i) out.ring.push_back(position(ring[i], i, where));
  if (out.ring.size() < 4) {
    refuse_geojson(where, "the outer ring has " + std::to_string(out.ring.size()) +
                      " positions; a closed ring needs at least 4 (3 vertices and the first repeated)");
  }
  const Point first = out.ring.front(), last = out.ring.back();
  if (first.x_m != last.x_m || first.y_m != last.y_m) {
    std::ostringstream msg;
    msg.precision(10);
    msg << "the outer ring is open: its last position (" << last.x_m << ", " << last.y_m << ") is not its first ("
        << first.x_m << ", " << first.y_m << "); a GeoJSON ring repeats its first position at the end (RFC 7946 §3.1.6)";
    refuse_geojson(where, msg.str());
  }
  out.ring.pop_back();
  return out;
}

SourceRing read_geojson_boundary(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(ErrorKind::kMissing, path, path + ": no such file (the field boundary, GeoJSON)");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_geojson_boundary(text.str(), path);
}

}  // namespace spread::field
