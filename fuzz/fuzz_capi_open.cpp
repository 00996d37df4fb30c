// Fuzz harness: spread_open() on arbitrary file bytes, then the queries and one prediction per material
// on whatever it accepted (capi/include/spread/spread.h). Seeds are real table files.
// Checked: only the documented statuses (never SPREAD_ERROR_INTERNAL), and a file that opens gives
// predictions that are refused with a status or are finite — a damaged record must not turn into NaN.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fuzz/capi_invariants.hpp"
#include "fuzz/fuzz_input.hpp"
#include "fuzz/temp_input_file.hpp"
#include "spread/spread.h"

namespace {

constexpr const char* kHarness = "fuzz_capi_open";
constexpr int32_t kMaxMaterialsPredicted = 4;  // bounds the time per input

void exercise(spread_tables* tables) {
  int32_t count = 0;
  spread::fuzz::check_status(kHarness, spread_material_count(tables, &count), "spread_material_count");
  double height_m = 0.0;
  spread::fuzz::check_status(kHarness, spread_default_disc_height(tables, &height_m), "spread_default_disc_height");
  std::size_t capacity = 0;
  const spread_status bound = spread_transverse_bound(tables, 0.5, &capacity);
  spread::fuzz::check_status(kHarness, bound, "spread_transverse_bound");
  std::vector<double> trays(bound == SPREAD_OK ? capacity : 0);
  for (int32_t i = 0; i < count && i < kMaxMaterialsPredicted; ++i) {
    const char* name = nullptr;
    double min_rpm = 0.0;
    double max_rpm = 0.0;
    spread::fuzz::check_status(kHarness, spread_material_name(tables, i, &name), "spread_material_name");
    spread::fuzz::check_status(kHarness, spread_material_rpm_range(tables, i, &min_rpm, &max_rpm),
                               "spread_material_rpm_range");
    spread_prediction_def def = spread_prediction_def_default();
    def.material = name;
    def.rpm = 0.5 * (min_rpm + max_rpm);
    spread_prediction result{};
    const spread_status status = spread_predict(tables, &def, &result, trays.data(), trays.size());
    spread::fuzz::check_status(kHarness, status, "spread_predict");
    if (status == SPREAD_OK) spread::fuzz::check_prediction(kHarness, result, trays.data(), trays.size());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static spread::fuzz::TempInputFile file("spread_fuzz_capi_open");
  if (!file.write(data, size)) spread::fuzz::fail(kHarness, "cannot write " + file.path());
  spread_tables* tables = nullptr;
  const spread_status status = spread_open(file.path().c_str(), &tables);
  spread::fuzz::check_status(kHarness, status, "spread_open");
  if (status != SPREAD_OK) {
    if (tables != nullptr) spread::fuzz::fail(kHarness, "spread_open failed but returned a handle");
    return 0;
  }
  exercise(tables);
  spread_close(tables);
  return 0;
}
