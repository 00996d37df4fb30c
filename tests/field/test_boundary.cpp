// Field boundaries: GeoJSON read and projected with PROJ to the right metres, and every bad boundary
// refused with a message naming what is wrong.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "libspread/analysis/field/boundary.hpp"
#include "libspread/analysis/field/geojson_boundary.hpp"
#include "libspread/analysis/field/projection.hpp"
#include "libspread/core/error.hpp"
#include "tests/support/error_message.hpp"

namespace spread::field {
namespace {

std::string polygon(const std::string& ring, const std::string& crs_member = "") {
  return R"({"type": "Feature", )" + crs_member + R"("properties": {}, "geometry": {"type": "Polygon", "coordinates": [)" +
         ring + "]}}";
}

using spread::testing::error_of;

Boundary boundary_of(const std::string& text) {
  const SourceRing source = parse_geojson_boundary(text, "field.geojson");
  const ProjectedRing projected = project_to_metres(source);
  return make_boundary(projected.ring, projected.crs, "field.geojson");
}

TEST(FieldBoundary, LonLatIsProjectedToItsUtmZone) {
  // 0.01° × 0.01° at 52° N on zone 32's central meridian (9° E). On the ellipsoid its area is
  // (π/180)² · 0.01² · M(φ) N(φ) cos φ, the meridian and prime-vertical radii of WGS 84
  // M = a(1 − e²)/(1 − e² sin²φ)^{3/2}, N = a/(1 − e² sin²φ)^{1/2}; UTM's scale factor 0.9996 at the
  // central meridian makes it 0.9992 of that.
  const Boundary b = boundary_of(polygon("[[9.0, 52.0], [9.01, 52.0], [9.01, 52.01], [9.0, 52.01], [9.0, 52.0]]"));
  EXPECT_EQ(b.crs, "EPSG:32632");
  EXPECT_NEAR(b.ring[0].x_m, 500000.0, 1e-3);  // the central meridian's false easting
  const double pi = 3.14159265358979323846;
  const double a = 6378137.0, e2 = 0.00669437999014, phi = 52.005 * pi / 180.0;
  const double w = 1.0 - e2 * std::sin(phi) * std::sin(phi);
  const double m = a * (1.0 - e2) / std::pow(w, 1.5), n = a / std::sqrt(w);
  const double ellipsoid_m2 = std::pow(pi / 180.0 * 0.01, 2) * m * n * std::cos(phi);
  EXPECT_NEAR(b.area_m2 / (0.9996 * 0.9996 * ellipsoid_m2), 1.0, 2e-3);
  EXPECT_EQ(utm_crs_for(-58.4, -34.6), "EPSG:32721");  // Buenos Aires: zone 21 south
}

TEST(FieldBoundary, ProjectedCrsIsKeptInItsMetres) {
  const std::string crs = R"("crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::25832"}}, )";
  const Boundary b = boundary_of(polygon(
      "[[560000, 5800000], [560300, 5800000], [560300, 5800200], [560000, 5800200], [560000, 5800000]]", crs));
  EXPECT_EQ(b.crs, "EPSG:25832");
  EXPECT_DOUBLE_EQ(b.area_m2, 60000.0);
}

TEST(FieldBoundary, RefusesAnOpenRing) {
  const std::string message =
      error_of([] { boundary_of(polygon("[[9.0, 52.0], [9.01, 52.0], [9.01, 52.01], [9.0, 52.01]]")); });
  EXPECT_NE(message.find("open"), std::string::npos) << message;
  EXPECT_NE(message.find("field.geojson"), std::string::npos) << message;
}

TEST(FieldBoundary, RefusesASelfIntersectingRing) {
  // A bow tie: the second and fourth edges cross.
  const std::string message = error_of(
      [] { boundary_of(polygon("[[9.0, 52.0], [9.01, 52.01], [9.01, 52.0], [9.0, 52.01], [9.0, 52.0]]")); });
  EXPECT_NE(message.find("self-intersecting"), std::string::npos) << message;
  EXPECT_NE(message.find("edge 0"), std::string::npos) << message;
}

TEST(FieldBoundary, RefusesMetresReadAsLongitudeLatitude) {
  const std::string message = error_of([] {
    boundary_of(polygon("[[560000, 5800000], [560300, 5800000], [560300, 5800200], [560000, 5800000]]"));
  });
  EXPECT_NE(message.find("not longitude/latitude"), std::string::npos) << message;
  EXPECT_NE(message.find("wrong units"), std::string::npos) << message;
}

TEST(FieldBoundary, RefusesDegreesReadAsMetres) {
  const std::string crs = R"("crs": {"type": "name", "properties": {"name": "local"}}, )";
  const std::string message = error_of(
      [&] { boundary_of(polygon("[[9.0, 52.0], [9.01, 52.0], [9.01, 52.01], [9.0, 52.01], [9.0, 52.0]]", crs)); });
  EXPECT_NE(message.find("wrong units"), std::string::npos) << message;
  EXPECT_NE(message.find("m²"), std::string::npos) << message;
}

TEST(FieldBoundary, RefusesAFieldInTheWrongHemisphere) {
  // Southern coordinates (negative northings, no false northing) given in UTM zone 32 north.
  const std::string crs = R"("crs": {"type": "name", "properties": {"name": "EPSG:32632"}}, )";
  const std::string message = error_of([&] {
    boundary_of(polygon(
        "[[560000, -3800000], [560300, -3800000], [560300, -3799800], [560000, -3799800], [560000, -3800000]]", crs));
  });
  EXPECT_NE(message.find("wrong hemisphere"), std::string::npos) << message;
  EXPECT_NE(message.find("EPSG:32632"), std::string::npos) << message;
}

TEST(FieldBoundary, RefusesAMultiPolygonAndHoles) {
  EXPECT_NE(error_of([] { parse_geojson_boundary(R"({"type": "MultiPolygon", "coordinates": []})", "f"); })
                .find("MultiPolygon"),
            std::string::npos);
  const std::string holes = R"({"type": "Polygon", "coordinates": [[[0,0],[1,0],[1,1],[0,0]], [[0.1,0.1],[0.2,0.1],[0.2,0.2],[0.1,0.1]]]})";
  EXPECT_NE(error_of([&] { parse_geojson_boundary(holes, "f"); }).find("hole"), std::string::npos);
}

}  // namespace
}  // namespace spread::field
