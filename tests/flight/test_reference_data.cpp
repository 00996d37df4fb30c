// Landings against scipy's solve_ivp (DOP853, rtol 1e-12) from data/make_reference.py: an independent
// implementation of the same equations and an independent integrator.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "libspread/physics/flight/flight.hpp"
#include "tests/flight/flight_test_support.hpp"

namespace spread::flight {
namespace {

struct ReferenceCase {
  std::string name;
  Granule granule;
  State launch;
  double ground_z_m = 0.0;
  LiftModel lift = LiftModel::kSmoothSaturating;
  State landing;
  double flight_time_s = 0.0;
};

std::vector<ReferenceCase> load_cases() {
  std::ifstream file(std::string(SPREAD_FLIGHT_TEST_DATA_DIR) + "/reference_landings.csv");
  std::vector<ReferenceCase> cases;
  std::string line;
  bool header_seen = false;
  while (std::getline(file, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (!header_seen) {
      header_seen = true;
      continue;
    }
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) f.push_back(cell);
    if (f.size() != 24) {
      ADD_FAILURE() << "bad reference line: " << line;
      continue;
    }
    const auto d = [&](std::size_t i) { return std::stod(f[i]); };
    ReferenceCase c;
    c.name = f[0];
    c.granule = Granule{d(1), d(2)};
    c.launch.position_m = Vec3(d(3), d(4), d(5));
    c.launch.velocity_m_s = Vec3(d(6), d(7), d(8));
    c.launch.spin_rad_s = Vec3(d(9), d(10), d(11));
    c.ground_z_m = d(12);
    c.lift = f[13] == "obd" ? LiftModel::kOesterleBuiDinh : LiftModel::kSmoothSaturating;
    c.landing.position_m = Vec3(d(14), d(15), d(16));
    c.landing.velocity_m_s = Vec3(d(17), d(18), d(19));
    c.landing.spin_rad_s = Vec3(d(20), d(21), d(22));
    c.flight_time_s = d(23);
    cases.push_back(c);
  }
  return cases;
}

void check_against_reference(Settings settings, double position_tolerance_m) {
  const auto cases = load_cases();
  ASSERT_EQ(cases.size(), 4u);
  for (const ReferenceCase& c : cases) {
    settings.lift = c.lift;
    const Landing l = fly_to_ground(c.granule, c.launch, c.ground_z_m, Air{}, test::kDiscEffects, settings);
    ASSERT_TRUE(l.landed) << c.name;
    EXPECT_LT((l.state.position_m - c.landing.position_m).norm(), position_tolerance_m) << c.name;
    EXPECT_NEAR(l.flight_time_s, c.flight_time_s, position_tolerance_m / 5.0) << c.name;
    EXPECT_LT((l.state.velocity_m_s - c.landing.velocity_m_s).norm(), 10 * position_tolerance_m) << c.name;
    EXPECT_LT((l.state.spin_rad_s - c.landing.spin_rad_s).norm(), 1e-3 * c.landing.spin_rad_s.norm()) << c.name;
  }
}

TEST(ReferenceData, DormandPrinceDefaultsWithinOneMillimetre) { check_against_reference(Settings{}, 1e-3); }

TEST(ReferenceData, Rk4AtOneMillisecondWithinAFewMillimetres) {
  check_against_reference(test::rk4(1e-3), 3e-3);
}

TEST(ReferenceData, TightDormandPrinceAgreesToNanometres) {
  check_against_reference(test::tight_dormand_prince(), 1e-9);  // measured ~1e-12 m
}

}  // namespace
}  // namespace spread::flight
