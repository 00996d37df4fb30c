// NaN and Inf in every floating-point argument of the C API: spread_predict's definition
// fields, spread_transverse_bound's tray width and every field of spread_trajectory's definition give
// SPREAD_ERROR_NOT_FINITE — a clear code, the result untouched — never a NaN result or
// SPREAD_ERROR_INTERNAL. disc_height_m = NaN is documented as "the machine's stored height", so for it
// only ±Inf are errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "spread/spread.h"
#include "tests/stability/stability_table.hpp"

namespace spread::stability {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
const double kNonFinite[] = {kNaN, kInf, -kInf};

class CapiNonFinite : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_EQ(spread_open(stability_table_path().c_str(), &tables_), SPREAD_OK); }
  void TearDown() override { spread_close(tables_); }

  spread_prediction_def valid_def() const {
    spread_prediction_def def = spread_prediction_def_default();
    def.material = "Urea";
    def.rpm = 0.5 * (kTableMinRpm + kTableMaxRpm);
    return def;
  }

  spread_tables* tables_ = nullptr;
};

TEST_F(CapiNonFinite, ValidDefinitionPredictsFinite) {
  spread_prediction_def def = valid_def();
  spread_prediction result{};
  ASSERT_EQ(spread_predict(tables_, &def, &result, nullptr, 0), SPREAD_OK);
  EXPECT_TRUE(std::isfinite(result.throw_width_m));
  EXPECT_GT(result.throw_width_m, 1.0);
  def.disc_height_m = kNaN;  // documented: the machine's stored height
  ASSERT_EQ(spread_predict(tables_, &def, &result, nullptr, 0), SPREAD_OK);
  double stored = 0.0;
  ASSERT_EQ(spread_default_disc_height(tables_, &stored), SPREAD_OK);
  EXPECT_EQ(result.disc_height_m, stored);
}

TEST_F(CapiNonFinite, EveryPredictionFieldRefusesNanAndInf) {
  const std::vector<std::pair<std::string, std::function<void(spread_prediction_def&, double)>>> fields = {
      {"rpm", [](spread_prediction_def& d, double v) { d.rpm = v; }},
      {"disc_height_m", [](spread_prediction_def& d, double v) { d.disc_height_m = v; }},
      {"wind_m_s[0]", [](spread_prediction_def& d, double v) { d.wind_m_s[0] = v; }},
      {"wind_m_s[1]", [](spread_prediction_def& d, double v) { d.wind_m_s[1] = v; }},
      {"cv_target_percent", [](spread_prediction_def& d, double v) { d.cv_target_percent = v; }},
      {"bout_width_m", [](spread_prediction_def& d, double v) { d.bout_width_m = v; }},
      {"tray_width_m", [](spread_prediction_def& d, double v) { d.tray_width_m = v; }},
  };
  for (const auto& [name, set] : fields) {
    for (double bad : kNonFinite) {
      if (name == "disc_height_m" && std::isnan(bad)) continue;
      for (std::uint32_t effects : {SPREAD_EFFECT_ALL, 0u}) {  // also when the field's effect is off
        SCOPED_TRACE(name + " = " + std::to_string(bad) + ", effects " + std::to_string(effects));
        spread_prediction_def def = valid_def();
        def.effects = effects;
        set(def, bad);
        spread_prediction result{};
        result.throw_width_m = -7.0;  // sentinel: a refusal must not write the result
        std::vector<double> trays(4096, -7.0);
        EXPECT_EQ(spread_predict(tables_, &def, &result, trays.data(), trays.size()), SPREAD_ERROR_NOT_FINITE);
        EXPECT_EQ(result.throw_width_m, -7.0);
        EXPECT_EQ(trays.front(), -7.0);
      }
    }
  }
}

TEST_F(CapiNonFinite, TransverseBoundRefusesNanAndInf) {
  for (double bad : kNonFinite) {
    std::size_t count = 12345;
    EXPECT_EQ(spread_transverse_bound(tables_, bad, &count), SPREAD_ERROR_NOT_FINITE) << bad;
    EXPECT_EQ(count, 12345u);
  }
}

TEST(CapiTrajectoryNonFinite, EveryFieldRefusesNanAndInf) {
  using Setter = std::function<void(spread_trajectory_def&, double)>;
  std::vector<std::pair<std::string, Setter>> fields = {
      {"diameter_m", [](spread_trajectory_def& d, double v) { d.diameter_m = v; }},
      {"density_kg_m3", [](spread_trajectory_def& d, double v) { d.density_kg_m3 = v; }},
      {"ground_z_m", [](spread_trajectory_def& d, double v) { d.ground_z_m = v; }},
      {"air_density_kg_m3", [](spread_trajectory_def& d, double v) { d.air_density_kg_m3 = v; }},
      {"air_viscosity_pa_s", [](spread_trajectory_def& d, double v) { d.air_viscosity_pa_s = v; }},
  };
  for (int i = 0; i < 3; ++i) {
    const std::string index = "[" + std::to_string(i) + "]";
    fields.emplace_back("position_m" + index, [i](spread_trajectory_def& d, double v) { d.position_m[i] = v; });
    fields.emplace_back("velocity_m_s" + index, [i](spread_trajectory_def& d, double v) { d.velocity_m_s[i] = v; });
    fields.emplace_back("spin_rad_s" + index, [i](spread_trajectory_def& d, double v) { d.spin_rad_s[i] = v; });
    fields.emplace_back("wind_m_s" + index, [i](spread_trajectory_def& d, double v) { d.wind_m_s[i] = v; });
  }
  spread_trajectory_def valid = spread_trajectory_def_default();
  valid.velocity_m_s[0] = 20.0;
  spread_landing landing{};
  ASSERT_EQ(spread_trajectory(&valid, &landing), SPREAD_OK);
  for (const auto& [name, set] : fields) {
    for (double bad : kNonFinite) {
      SCOPED_TRACE(name + " = " + std::to_string(bad));
      spread_trajectory_def def = valid;
      set(def, bad);
      spread_landing out{};
      out.flight_time_s = -7.0;
      EXPECT_EQ(spread_trajectory(&def, &out), SPREAD_ERROR_NOT_FINITE);
      EXPECT_EQ(out.flight_time_s, -7.0);
    }
  }
}


// Finite but absurd inputs: a launch at 3e307 m/s overflowed the landing position to inf (found by
// fuzz_capi_trajectory, fuzz/regressions/capi_trajectory/). Each field has a physical domain (spread.h):
// its bound is flown, a value just beyond it is refused and leaves the output untouched.
TEST(CapiTrajectoryDomain, EveryFieldRefusesValuesBeyondItsBound) {
  struct Case {
    std::string name;
    std::function<void(spread_trajectory_def&, double)> set;
    double at_bound;
    double beyond;
  };
  std::vector<Case> cases = {
      {"diameter_m low", [](spread_trajectory_def& d, double v) { d.diameter_m = v; }, 1e-6, 0.9e-6},
      {"diameter_m high", [](spread_trajectory_def& d, double v) { d.diameter_m = v; }, 0.1, 0.11},
      {"density_kg_m3 low", [](spread_trajectory_def& d, double v) { d.density_kg_m3 = v; }, 1.0, 0.5},
      {"density_kg_m3 high", [](spread_trajectory_def& d, double v) { d.density_kg_m3 = v; }, 25000.0, 26000.0},
      {"ground_z_m", [](spread_trajectory_def& d, double v) { d.ground_z_m = v; }, -1000.0, -1001.0},
      {"air_density_kg_m3", [](spread_trajectory_def& d, double v) { d.air_density_kg_m3 = v; }, 100.0, 101.0},
      {"air_viscosity_pa_s", [](spread_trajectory_def& d, double v) { d.air_viscosity_pa_s = v; }, 1.0, 1.1},
  };
  for (int i = 0; i < 3; ++i) {
    const std::string index = "[" + std::to_string(i) + "]";
    cases.push_back({"position_m" + index, [i](spread_trajectory_def& d, double v) { d.position_m[i] = v; },
                     i == 2 ? 1000.0 : -1000.0, i == 2 ? 1001.0 : -1001.0});
    cases.push_back({"velocity_m_s" + index, [i](spread_trajectory_def& d, double v) { d.velocity_m_s[i] = v; },
                     -1000.0, -3.2e307});
    cases.push_back({"spin_rad_s" + index, [i](spread_trajectory_def& d, double v) { d.spin_rad_s[i] = v; }, 1e5,
                     1.1e5});
    cases.push_back(
        {"wind_m_s" + index, [i](spread_trajectory_def& d, double v) { d.wind_m_s[i] = v; }, 100.0, 101.0});
  }
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    spread_trajectory_def def = spread_trajectory_def_default();
    def.effects = 0;  // vacuum: the bound itself must fly, whatever drag would make of it
    c.set(def, c.at_bound);
    spread_landing landing{};
    const spread_status at_bound = spread_trajectory(&def, &landing);
    EXPECT_TRUE(at_bound == SPREAD_OK || at_bound == SPREAD_ERROR_NOT_LANDED) << spread_status_str(at_bound);
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(std::isfinite(landing.position_m[k]));
    c.set(def, c.beyond);
    spread_landing out{};
    out.flight_time_s = -7.0;
    EXPECT_EQ(spread_trajectory(&def, &out), SPREAD_ERROR_OUT_OF_RANGE);
    EXPECT_EQ(out.flight_time_s, -7.0);
  }
}

}  // namespace
}  // namespace spread::stability
