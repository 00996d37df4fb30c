// Plans from a boundary (headland rounds, tramlines at the bout width) and recorded tracks, with the
// tracks a terminal gets wrong refused by line.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "libspread/analysis/field/boundary.hpp"
#include "libspread/analysis/field/plan.hpp"
#include "libspread/analysis/field/projection.hpp"
#include "libspread/analysis/field/track_csv.hpp"
#include "libspread/core/error.hpp"
#include "tests/support/error_message.hpp"

namespace spread::field {
namespace {

Boundary rectangle(double width_m, double length_m) {
  return make_boundary({{0, 0}, {width_m, 0}, {width_m, length_m}, {0, length_m}}, "local", "test");
}

using spread::testing::error_of;

TEST(FieldPlan, HeadlandRoundAndTramlinesAtTheBoutWidth) {
  // 240 m wide (along the longest edge, the x axis), 120 m deep: one headland round 12 m inside, then
  // tramlines 36, 60, 84 m from the bottom edge — 108 m is within W/2 of the top edge, the headland's.
  PlanSettings s;
  s.bout_width_m = 24.0;
  s.headland_passes = 1;
  const auto passes = plan_field(rectangle(240.0, 120.0), s);
  ASSERT_EQ(passes.size(), 4u);
  EXPECT_EQ(passes[0].kind, PassKind::kHeadland);
  EXPECT_TRUE(passes[0].outermost);
  EXPECT_NEAR(path_length_m(passes[0].path), 2.0 * (216.0 + 96.0), 1e-9);
  // Counter-clockwise: the boundary on the driver's right.
  EXPECT_GT(signed_area_m2(Ring(passes[0].path.begin(), passes[0].path.end() - 1)), 0.0);
  const double expected_y[] = {36.0, 60.0, 84.0};
  for (int j = 0; j < 3; ++j) {
    const Pass& t = passes[static_cast<std::size_t>(j) + 1];
    EXPECT_EQ(t.kind, PassKind::kTramline);
    ASSERT_EQ(t.path.size(), 2u);
    EXPECT_NEAR(t.path[0].y_m, expected_y[j], 1e-9);
    EXPECT_NEAR(t.path[1].y_m, expected_y[j], 1e-9);
    // Inside the headland: from 24 m to 216 m, driven to and fro.
    EXPECT_NEAR(std::min(t.path[0].x_m, t.path[1].x_m), 24.0, 1e-9);
    EXPECT_NEAR(std::max(t.path[0].x_m, t.path[1].x_m), 216.0, 1e-9);
    EXPECT_EQ(t.path[1].x_m > t.path[0].x_m, j % 2 == 0);
  }
}

TEST(FieldPlan, RefusesAHeadlandWiderThanTheField) {
  PlanSettings s;
  s.bout_width_m = 24.0;
  s.headland_passes = 3;  // the third round would lie 60 m inside a 100 m wide field
  const std::string message = error_of([&] { plan_field(rectangle(300.0, 100.0), s); });
  EXPECT_NE(message.find("headland pass 3"), std::string::npos) << message;
}

TEST(FieldTrack, PassesSplitWhereTheFeedIsShut) {
  const std::string csv =
      "# a terminal's log\n"
      "time_s,x_m,y_m,speed_m_s,heading_deg,spreading\n"
      "0,10,0,4,0,1\n1,10,4,4,0,1\n2,10,8,4,0,1\n3,12,10,4,90,0\n4,16,10,4,90,0\n5,20,8,4,180,1\n6,20,4,4,180,1\n";
  const auto passes = parse_track_csv(csv, "track.csv", rectangle(100.0, 100.0));
  ASSERT_EQ(passes.size(), 2u);
  EXPECT_NEAR(path_length_m(passes[0].path), 8.0, 1e-12);
  EXPECT_NEAR(path_length_m(passes[1].path), 4.0, 1e-12);
}

TEST(FieldTrack, LongitudeLatitudeIsProjectedIntoTheBoundarysCrs) {
  // A boundary in UTM 32N (EPSG:32632) and a track logged in longitude/latitude due north along 9° E, its
  // central meridian, 0.001° of latitude a fix: the pass lies at easting 500,000 m and is as long as the
  // meridian arc, 0.9996 · M(52°) · 0.002° (M = 6,375,150 m: WGS 84's meridian radius at 52°).
  const Ring lon_lat = {{8.99, 51.99}, {9.01, 51.99}, {9.01, 52.01}, {8.99, 52.01}};
  const Boundary field = make_boundary(lon_lat_to(lon_lat, "EPSG:32632", "test"), "EPSG:32632", "test");
  const std::string csv = "time_s,lon_deg,lat_deg,speed_m_s,heading_deg\n0,9,51.999,4,0\n28,9,52.000,4,0\n56,9,52.001,4,0\n";
  const auto passes = parse_track_csv(csv, "track.csv", field);
  ASSERT_EQ(passes.size(), 1u);
  EXPECT_NEAR(passes[0].path[1].x_m, 500000.0, 1e-3);
  const double pi = 3.14159265358979323846;
  EXPECT_NEAR(path_length_m(passes[0].path), 0.9996 * 6375150.0 * 0.002 * pi / 180.0, 0.05);
  // The same track refused for a field in local metres.
  const Boundary local = rectangle(100.0, 100.0);
  EXPECT_NE(error_of([&] { parse_track_csv(csv, "track.csv", local); }).find("local metres"), std::string::npos);
}

TEST(FieldTrack, RefusesAJump) {
  const std::string csv = "time_s,x_m,y_m,speed_m_s,heading_deg\n0,10,0,4,0\n1,10,4,4,0\n2,10,90,4,0\n";
  const std::string message = error_of([&] { parse_track_csv(csv, "track.csv", rectangle(100.0, 100.0)); });
  EXPECT_NE(message.find("track.csv:4"), std::string::npos) << message;
  EXPECT_NE(message.find("jumps"), std::string::npos) << message;
}

TEST(FieldTrack, RefusesTimeThatDoesNotIncreaseAndAHeadingAgainstTheTrack) {
  const Boundary field = rectangle(100.0, 100.0);
  const std::string back_in_time = "time_s,x_m,y_m,speed_m_s,heading_deg\n0,10,0,4,0\n0,10,4,4,0\n";
  EXPECT_NE(error_of([&] { parse_track_csv(back_in_time, "t.csv", field); }).find("t.csv:3: time_s does not increase"),
            std::string::npos);
  const std::string reversed = "time_s,x_m,y_m,speed_m_s,heading_deg\n0,10,0,4,180\n1,10,4,4,180\n";
  EXPECT_NE(error_of([&] { parse_track_csv(reversed, "t.csv", field); }).find("heading_deg"), std::string::npos);
  const std::string no_position = "time_s,speed_m_s,heading_deg\n0,4,0\n";
  EXPECT_NE(error_of([&] { parse_track_csv(no_position, "t.csv", field); }).find("neither x_m"), std::string::npos);
}

}  // namespace
}  // namespace spread::field
