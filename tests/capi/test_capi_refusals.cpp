// Bad arguments for every function of the C API, as a table: each cause of a refusal has one status
// wherever it is found (a NaN rpm is SPREAD_ERROR_NOT_FINITE in spread_predict and in the searches alike),
// and the detail names the function and the field at fault. Also: a result smaller than the definition's
// version is refused and left untouched, and the edge functions fly a request outside the landing grid
// when the definition opts in.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "capi/src/abi_layout.hpp"
#include "libspread/analysis/predict/edge_spreading.hpp"
#include "libspread/io/tables/table_writer.hpp"
#include "spread/spread.h"
#include "tests/capi/capi_test_files.hpp"
#include "tests/predict/synthetic_table.hpp"

namespace {

using spread::testing::temp_path;

// The synthetic table with runs that record drag alone (as the product's tables do): its materials have a
// landing grid, so requests outside the grid's domain are refused unless they opt in.
std::string write_drag_table() {
  const std::string path = temp_path("refusals_drag.sqlite");
  auto contents = spread::testing::synthetic_contents();
  for (auto& run : contents.runs) run.stats_json = R"({"flight_effects":"drag"})";
  std::filesystem::remove(path);
  spread::tables::TableWriter writer(path);
  writer.write_machine(contents.machine);
  writer.write_materials(contents.materials);
  for (const auto& run : contents.runs) writer.write_run(run);
  return path;
}

class CapiRefusals : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    path_ = write_drag_table();
    ASSERT_EQ(spread_open(path_.c_str(), &tables_), SPREAD_OK) << spread_last_error_detail();
    ASSERT_EQ(spread_workspace_create(tables_, &workspace_), SPREAD_OK);
  }
  static void TearDownTestSuite() {
    spread_workspace_free(workspace_);
    spread_close(tables_);
  }
  // The field's setting every search and edge call starts from.
  static spread_prediction_def def(double rpm = 650.0) {
    spread_prediction_def d = spread_prediction_def_default();
    d.material = "can";
    d.rpm = rpm;
    d.bout_width_m = 18.0;
    return d;
  }
  static inline std::string path_;
  static inline spread_tables* tables_ = nullptr;
  static inline spread_workspace* workspace_ = nullptr;
};

// The causes, each with the one status it has in every function.
const std::map<std::string, spread_status>& cause_status() {
  static const std::map<std::string, spread_status> causes = {
      {"a required pointer is NULL", SPREAD_ERROR_NULL_POINTER},
      {"NaN or infinite", SPREAD_ERROR_NOT_FINITE},
      {"outside its range", SPREAD_ERROR_OUT_OF_RANGE},
      {"a flag or choice outside its values", SPREAD_ERROR_OUT_OF_RANGE},
      {"struct_size older than accepted", SPREAD_ERROR_OUT_OF_RANGE},
      {"result smaller than the definition's", SPREAD_ERROR_OUT_OF_RANGE},
      {"rpm outside the table's rows", SPREAD_ERROR_RPM_OUTSIDE_TABLE},
      {"unknown material", SPREAD_ERROR_UNKNOWN_MATERIAL},
      {"unknown effect bits", SPREAD_ERROR_UNKNOWN_EFFECT},
      {"outside the landing grid", SPREAD_ERROR_OUTSIDE_DOMAIN},
  };
  return causes;
}

TEST_F(CapiRefusals, EveryFunctionGivesACauseItsOneStatusAndNamesTheField) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  spread_prediction result{};
  spread_edge_result edge_result{};
  spread_edge_setting setting{};
  spread_landing landing{};
  spread_tables* opened = nullptr;
  const char* name = nullptr;
  double a = 0.0, b = 0.0, c = 0.0;
  size_t trays = 0;
  const spread_edge_def edge = spread_edge_def_default();

  // Each call takes a definition changed from the defaults by `change`.
  using Change = std::function<void(spread_prediction_def&)>;
  const auto predict = [&](Change change) {
    return [=, &result]() {
      spread_prediction_def d = def();
      change(d);
      return spread_predict(tables_, &d, &result, nullptr, 0);
    };
  };
  const auto workspace_predict = [&](Change change) {
    return [=, &result]() {
      spread_prediction_def d = def();
      change(d);
      return spread_workspace_predict(workspace_, &d, &result, nullptr, 0);
    };
  };
  const auto compensate = [&](Change change) {
    return [=, &result]() {
      spread_prediction_def d = def();
      change(d);
      return spread_compensate_wind(tables_, &d, &result, nullptr, 0);
    };
  };
  using EdgeChange = std::function<void(spread_edge_def&)>;
  const auto predict_edge = [&](Change change, EdgeChange edge_change = [](spread_edge_def&) {}) {
    return [=, &edge_result]() {
      spread_prediction_def d = def();
      change(d);
      spread_edge_def e = edge;
      edge_change(e);
      return spread_predict_edge(tables_, &d, &e, &edge_result, nullptr, 0);
    };
  };
  const auto find_edge = [&](Change change, EdgeChange edge_change = [](spread_edge_def&) {}) {
    return [=, &setting, &edge_result]() {
      spread_prediction_def d = def();
      change(d);
      spread_edge_def e = edge;
      edge_change(e);
      return spread_find_edge_setting(tables_, &d, &e, &setting, &edge_result, nullptr, 0);
    };
  };
  using TrajectoryChange = std::function<void(spread_trajectory_def&)>;
  const auto trajectory = [&](TrajectoryChange change) {
    return [=, &landing]() {
      spread_trajectory_def t = spread_trajectory_def_default();
      change(t);
      return spread_trajectory(&t, &landing);
    };
  };
  const Change nan_rpm = [=](spread_prediction_def& d) { d.rpm = nan; };
  const Change fast = [](spread_prediction_def& d) { d.rpm = 2000.0; };
  const Change gravel = [](spread_prediction_def& d) { d.material = "gravel"; };
  const Change fine_trays = [](spread_prediction_def& d) { d.tray_width_m = 0.01; };
  const Change flag_7 = [](spread_prediction_def& d) { d.fly_outside_domain = 7u; };
  const Change lift = [](spread_prediction_def& d) { d.effects = SPREAD_EFFECT_ALL | 0x100u; };
  const Change high = [](spread_prediction_def& d) { d.disc_height_m = 50.0; };
  const Change no_material = [](spread_prediction_def& d) { d.material = nullptr; };
  const Change tiny_result = [](spread_prediction_def& d) { d.result_size = 0u; };
  const Change v3_def = [](spread_prediction_def& d) {
    d.struct_size = static_cast<uint32_t>(spread::capi::kPredictionDefV3Size);
  };

  struct Case {
    const char* cause;
    const char* function;
    std::function<spread_status()> call;
    const char* field;  // what the detail must name
  };
  const std::vector<Case> cases = {
      // NULL
      {"a required pointer is NULL", "spread_open", [&] { return spread_open(nullptr, &opened); }, "path"},
      {"a required pointer is NULL", "spread_open", [&] { return spread_open(path_.c_str(), nullptr); }, "out_tables"},
      {"a required pointer is NULL", "spread_open_with_allocator",
       [&] { return spread_open_with_allocator(path_.c_str(), nullptr, &opened); }, "allocator"},
      {"a required pointer is NULL", "spread_open_with_flags",
       [&] { return spread_open_with_flags(path_.c_str(), 0u, nullptr, nullptr); }, "out_tables"},
      {"a required pointer is NULL", "spread_table_flags", [&] { return spread_table_flags(tables_, nullptr); },
       "out_flags"},
      {"a required pointer is NULL", "spread_material_count", [&] { return spread_material_count(tables_, nullptr); },
       "out_count"},
      {"a required pointer is NULL", "spread_material_name", [&] { return spread_material_name(tables_, 0, nullptr); },
       "out_name"},
      {"a required pointer is NULL", "spread_material_rpm_range",
       [&] { return spread_material_rpm_range(tables_, 0, &a, nullptr); }, "out_max_rpm"},
      {"a required pointer is NULL", "spread_default_disc_height",
       [&] { return spread_default_disc_height(tables_, nullptr); }, "out_height_m"},
      {"a required pointer is NULL", "spread_landing_domain",
       [&] { return spread_landing_domain(tables_, 0, &a, &b, nullptr); }, "out_max_wind_m_s"},
      {"a required pointer is NULL", "spread_transverse_bound",
       [&] { return spread_transverse_bound(tables_, 0.5, nullptr); }, "out_tray_count"},
      {"a required pointer is NULL", "spread_workspace_create",
       [&] { return spread_workspace_create(tables_, nullptr); }, "out_workspace"},
      {"a required pointer is NULL", "spread_predict", predict(no_material), "def->material"},
      {"a required pointer is NULL", "spread_predict",
       [&] {
         const spread_prediction_def d = def();
         return spread_predict(tables_, &d, nullptr, nullptr, 0);
       },
       "result"},
      {"a required pointer is NULL", "spread_workspace_predict",
       [&] {
         const spread_prediction_def d = def();
         return spread_workspace_predict(nullptr, &d, &result, nullptr, 0);
       },
       "workspace"},
      {"a required pointer is NULL", "spread_compensate_wind", compensate(no_material), "def->material"},
      {"a required pointer is NULL", "spread_predict_edge",
       [&] {
         const spread_prediction_def d = def();
         return spread_predict_edge(tables_, &d, nullptr, &edge_result, nullptr, 0);
       },
       "edge"},
      {"a required pointer is NULL", "spread_find_edge_setting",
       [&] {
         const spread_prediction_def d = def();
         return spread_find_edge_setting(tables_, &d, &edge, nullptr, &edge_result, nullptr, 0);
       },
       "setting"},
      {"a required pointer is NULL", "spread_trajectory",
       [&] {
         const spread_trajectory_def t = spread_trajectory_def_default();
         return spread_trajectory(&t, nullptr);
       },
       "out_landing"},
      // NaN or infinite
      {"NaN or infinite", "spread_predict", predict(nan_rpm), "rpm is nan"},
      {"NaN or infinite", "spread_workspace_predict", workspace_predict(nan_rpm), "rpm is nan"},
      {"NaN or infinite", "spread_compensate_wind", compensate(nan_rpm), "rpm is nan"},
      {"NaN or infinite", "spread_predict_edge", predict_edge(nan_rpm), "rpm is nan"},
      {"NaN or infinite", "spread_find_edge_setting", find_edge(nan_rpm), "rpm is nan"},
      {"NaN or infinite", "spread_compensate_wind", compensate([=](spread_prediction_def& d) { d.bout_width_m = nan; }),
       "bout_width_m is nan"},
      {"NaN or infinite", "spread_predict_edge",
       predict_edge([=](spread_prediction_def& d) { d.disc_rpm[1] = inf; }), "disc_rpm[1] is inf"},
      {"NaN or infinite", "spread_predict_edge",
       predict_edge([](spread_prediction_def&) {}, [=](spread_edge_def& e) { e.gap_m = nan; }), "edge->gap_m is nan"},
      {"NaN or infinite", "spread_transverse_bound", [&] { return spread_transverse_bound(tables_, nan, &trays); },
       "tray_width_m is nan"},
      {"NaN or infinite", "spread_trajectory", trajectory([=](spread_trajectory_def& t) { t.velocity_m_s[0] = inf; }),
       "velocity_m_s[0] is inf"},
      {"NaN or infinite", "spread_trajectory", trajectory([=](spread_trajectory_def& t) { t.air_density_kg_m3 = nan; }),
       "air_density_kg_m3 is nan"},
      // Outside the range
      {"outside its range", "spread_predict", predict(fine_trays), "tray_width_m 0.01 outside [0.1, 100] m"},
      {"outside its range", "spread_workspace_predict", workspace_predict(fine_trays), "tray_width_m 0.01"},
      {"outside its range", "spread_compensate_wind", compensate(fine_trays), "tray_width_m 0.01"},
      {"outside its range", "spread_predict_edge", predict_edge(fine_trays), "tray_width_m 0.01"},
      {"outside its range", "spread_find_edge_setting", find_edge(fine_trays), "tray_width_m 0.01"},
      {"outside its range", "spread_compensate_wind", compensate([](spread_prediction_def& d) { d.bout_width_m = 0.0; }),
       "bout_width_m 0"},
      {"outside its range", "spread_predict_edge",
       predict_edge([](spread_prediction_def& d) { d.disc_drop_point_turn_rad[0] = 4.0; }),
       "disc_drop_point_turn_rad[0] 4 outside"},
      {"outside its range", "spread_predict_edge",
       predict_edge([](spread_prediction_def&) {}, [](spread_edge_def& e) { e.gap_m = 9.0; }), "edge->gap_m 9"},
      {"outside its range", "spread_find_edge_setting",
       find_edge([](spread_prediction_def&) {}, [](spread_edge_def& e) { e.flow_fraction = 0.5; }),
       "edge->flow_fraction 0.5"},
      {"outside its range", "spread_find_edge_setting",
       find_edge([](spread_prediction_def& d) { d.disc_drop_point_turn_rad[1] = 0.2; }),
       "disc_drop_point_turn_rad[1] 0.2"},
      {"outside its range", "spread_transverse_bound", [&] { return spread_transverse_bound(tables_, -0.5, &trays); },
       "tray_width_m -0.5"},
      {"outside its range", "spread_material_name", [&] { return spread_material_name(tables_, 9, &name); }, "index 9"},
      {"outside its range", "spread_material_rpm_range",
       [&] { return spread_material_rpm_range(tables_, -1, &a, &b); }, "index -1"},
      {"outside its range", "spread_landing_domain", [&] { return spread_landing_domain(tables_, 2, &a, &b, &c); },
       "index 2"},
      {"outside its range", "spread_trajectory", trajectory([](spread_trajectory_def& t) { t.diameter_m = 1.0; }),
       "diameter_m 1 outside [1e-06, 0.1]"},
      {"outside its range", "spread_trajectory", trajectory([](spread_trajectory_def& t) { t.position_m[2] = -1.0; }),
       "position_m[2] -1 is below def->ground_z_m"},
      {"outside its range", "spread_trajectory",
       trajectory([](spread_trajectory_def& t) { t.air_viscosity_pa_s = 0.0; }), "air_viscosity_pa_s 0 outside (0, 1]"},
      // Flags and choices
      {"a flag or choice outside its values", "spread_predict", predict(flag_7), "fly_outside_domain 7"},
      {"a flag or choice outside its values", "spread_workspace_predict", workspace_predict(flag_7),
       "fly_outside_domain 7"},
      {"a flag or choice outside its values", "spread_compensate_wind", compensate(flag_7), "fly_outside_domain 7"},
      {"a flag or choice outside its values", "spread_predict_edge", predict_edge(flag_7), "fly_outside_domain 7"},
      {"a flag or choice outside its values", "spread_find_edge_setting", find_edge(flag_7), "fly_outside_domain 7"},
      {"a flag or choice outside its values", "spread_predict_edge",
       predict_edge([](spread_prediction_def&) {}, [](spread_edge_def& e) { e.side = 2; }), "edge->side 2"},
      {"a flag or choice outside its values", "spread_find_edge_setting",
       find_edge([](spread_prediction_def&) {}, [](spread_edge_def& e) { e.kind = 7u; }), "edge->kind 7"},
      {"a flag or choice outside its values", "spread_open_with_flags",
       [&] { return spread_open_with_flags(path_.c_str(), 0x80u, nullptr, &opened); }, "flags 0x80"},
      // Versions
      {"struct_size older than accepted", "spread_predict",
       predict([](spread_prediction_def& d) { d.struct_size = 8u; }), "def->struct_size 8"},
      {"struct_size older than accepted", "spread_compensate_wind", compensate(v3_def), "def->struct_size"},
      {"struct_size older than accepted", "spread_predict_edge", predict_edge(v3_def), "def->struct_size"},
      {"struct_size older than accepted", "spread_find_edge_setting",
       find_edge([](spread_prediction_def&) {}, [](spread_edge_def& e) { e.struct_size = 8u; }), "edge->struct_size 8"},
      {"struct_size older than accepted", "spread_trajectory",
       trajectory([](spread_trajectory_def& t) { t.struct_size = 8u; }), "def->struct_size 8"},
      {"result smaller than the definition's", "spread_predict", predict(tiny_result), "def->result_size 0"},
      {"result smaller than the definition's", "spread_workspace_predict", workspace_predict(tiny_result),
       "def->result_size 0"},
      {"result smaller than the definition's", "spread_compensate_wind",
       compensate([](spread_prediction_def& d) { d.result_size = static_cast<uint32_t>(spread::capi::kPredictionV3Size); }),
       "def->result_size"},
      // The table's contents
      {"rpm outside the table's rows", "spread_predict", predict(fast), "2000 rpm (rpm) outside the rows"},
      {"rpm outside the table's rows", "spread_workspace_predict", workspace_predict(fast), "(rpm) outside the rows"},
      {"rpm outside the table's rows", "spread_compensate_wind", compensate(fast), "(rpm) outside the rows"},
      {"rpm outside the table's rows", "spread_predict_edge", predict_edge(fast), "(rpm) outside the rows"},
      {"rpm outside the table's rows", "spread_find_edge_setting", find_edge(fast), "(rpm) outside the rows"},
      {"rpm outside the table's rows", "spread_predict_edge",
       predict_edge([](spread_prediction_def& d) { d.disc_rpm[1] = 2000.0; }), "(disc_rpm[1]) outside the rows"},
      {"unknown material", "spread_predict", predict(gravel), "material \"gravel\""},
      {"unknown material", "spread_workspace_predict", workspace_predict(gravel), "material \"gravel\""},
      {"unknown material", "spread_compensate_wind", compensate(gravel), "material \"gravel\""},
      {"unknown material", "spread_predict_edge", predict_edge(gravel), "material \"gravel\""},
      {"unknown material", "spread_find_edge_setting", find_edge(gravel), "material \"gravel\""},
      {"unknown effect bits", "spread_predict", predict(lift), "effects 0x10f"},
      {"unknown effect bits", "spread_compensate_wind", compensate(lift), "effects 0x10f"},
      {"unknown effect bits", "spread_predict_edge", predict_edge(lift), "effects 0x10f"},
      {"unknown effect bits", "spread_trajectory", trajectory([](spread_trajectory_def& t) { t.effects = 0x20u; }),
       "effects 0x20"},
      {"outside the landing grid", "spread_predict", predict(high), "disc_height_m 50 outside the landing grid's"},
      {"outside the landing grid", "spread_workspace_predict", workspace_predict(high), "disc_height_m 50"},
      {"outside the landing grid", "spread_compensate_wind", compensate(high), "disc_height_m 50"},
      {"outside the landing grid", "spread_predict_edge", predict_edge(high), "disc_height_m 50"},
      {"outside the landing grid", "spread_find_edge_setting", find_edge(high), "disc_height_m 50"},
  };

  std::map<std::string, std::set<spread_status>> statuses;  // by cause, over every function
  std::set<std::string> functions;
  for (const Case& k : cases) {
    SCOPED_TRACE(std::string(k.function) + ", " + k.cause + ": " + k.field);
    const spread_status status = k.call();
    statuses[k.cause].insert(status);
    functions.insert(k.function);
    EXPECT_EQ(status, cause_status().at(k.cause)) << spread_status_str(status);
    const std::string detail = spread_last_error_detail();
    EXPECT_EQ(detail.rfind(std::string(k.function) + ": ", 0), 0u) << detail;
    EXPECT_NE(detail.find(k.field), std::string::npos) << detail;
  }
  for (const auto& [cause, seen] : statuses) EXPECT_EQ(seen.size(), 1u) << cause;
  EXPECT_EQ(statuses.size(), cause_status().size());
  // Every function of spread.h that can refuse an argument (spread_close, spread_workspace_free,
  // spread_status_str and the version functions cannot).
  EXPECT_EQ(functions.size(), 17u);
}

// A definition whose result_size is below the smallest result written for it is refused, and not one byte
// of the caller's result is written; the smallest accepted size gets exactly that many bytes.
TEST_F(CapiRefusals, AResultSmallerThanTheDefinitionsVersionIsRefusedAndLeftUntouched) {
  spread_prediction_def d = def();
  for (uint32_t size : {0u, 8u, static_cast<uint32_t>(spread::capi::kPredictionV2Size - 1)}) {
    d.result_size = size;
    spread_prediction untouched;
    std::memset(&untouched, 0xAB, sizeof untouched);
    EXPECT_EQ(spread_predict(tables_, &d, &untouched, nullptr, 0), SPREAD_ERROR_OUT_OF_RANGE) << size;
    const auto* bytes = reinterpret_cast<const unsigned char*>(&untouched);
    for (std::size_t i = 0; i < sizeof untouched; ++i) ASSERT_EQ(bytes[i], 0xAB) << "byte " << i << ", result_size " << size;
  }
  d.result_size = static_cast<uint32_t>(spread::capi::kPredictionV2Size);
  spread_prediction smallest;
  std::memset(&smallest, 0xAB, sizeof smallest);
  ASSERT_EQ(spread_predict(tables_, &d, &smallest, nullptr, 0), SPREAD_OK) << spread_last_error_detail();
  const auto* bytes = reinterpret_cast<const unsigned char*>(&smallest);
  for (std::size_t i = spread::capi::kPredictionV2Size; i < sizeof smallest; ++i) ASSERT_EQ(bytes[i], 0xAB) << i;
}

// fly_outside_domain = 1 reaches the edge profile: a disc height above the landing grid is refused without
// it and flown with it, to the library's own profile of that flown request.
TEST_F(CapiRefusals, PredictEdgeFliesOutsideTheLandingGridWhenAsked) {
  spread_prediction_def d = def();
  d.disc_height_m = 3.0;
  spread_edge_def edge = spread_edge_def_default();
  edge.flow_fraction = 0.6;
  spread_edge_result result{};
  ASSERT_EQ(spread_predict_edge(tables_, &d, &edge, &result, nullptr, 0), SPREAD_ERROR_OUTSIDE_DOMAIN);
  d.fly_outside_domain = 1u;
  std::vector<double> rate(2000);
  ASSERT_EQ(spread_predict_edge(tables_, &d, &edge, &result, rate.data(), rate.size()), SPREAD_OK)
      << spread_last_error_detail();

  spread::predict::Predictor predictor(spread::tables::read_table_file(path_), spread::predict::PredictorLimits{});
  spread::predict::PredictionRequest field;
  field.material = "can";
  field.rpm = 650.0;
  field.bout_width_m = 18.0;
  field.disc_height_m = 3.0;
  field.fly_outside_domain = true;
  spread::predict::EdgeSetting setting;
  setting.disc.rpm = 650.0;
  setting.flow_fraction = 0.6;
  spread::predict::EdgeProfile expected;
  ASSERT_EQ(spread::predict::edge_profile(predictor, field, {}, setting, expected), spread::predict::PredictStatus::kOk);
  ASSERT_EQ(static_cast<std::size_t>(result.tray_count), expected.rate.size());
  EXPECT_DOUBLE_EQ(result.mass_beyond_percent, 100.0 * expected.mass_beyond_fraction);
  for (int k = 0; k < result.tray_count; ++k) EXPECT_DOUBLE_EQ(rate[k], 100.0 * expected.rate[k]) << k;
}

}  // namespace
