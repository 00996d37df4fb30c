// Fuzz harness: spread_predict() with fuzzed definition fields on a real table, built once at start-up
// from scenes/default.toml by the lookup_builder library (analytic launch source, 3 rpm rows).
// Each field is either raw bytes (every bit pattern: NaN, Inf, denormals, huge) or drawn from a
// plausible range, chosen by a flag bit, so the fuzzer reaches both the refusals and the physics.
// Checked: documented statuses only (never SPREAD_ERROR_INTERNAL), BUFFER_TOO_SMALL leaves the buffer
// untouched, and every accepted prediction is finite and conserves mass over the trays.
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "fuzz/capi_invariants.hpp"
#include "fuzz/fuzz_input.hpp"
#include "libspread/io/scene/scene.hpp"
#include "lookup_builder/table_build.hpp"
#include "spread/spread.h"

namespace {

constexpr const char* kHarness = "fuzz_capi_predict";

struct Fixture {
  std::string path;
  spread_tables* tables = nullptr;
  std::vector<std::string> names;
  std::vector<double> min_rpm, max_rpm;
};
Fixture* fixture = nullptr;

void remove_table() {
  if (fixture == nullptr) return;
  spread_close(fixture->tables);
  std::remove(fixture->path.c_str());
}

void build_fixture() {
  fixture = new Fixture;
  fixture->path = "/tmp/spread_fuzz_capi_predict_" + std::to_string(::getpid()) + ".sqlite";
  std::remove(fixture->path.c_str());
  const spread::scene::Scene scene = spread::scene::load_scene_file(
      SPREAD_SOURCE_DIR "/scenes/default.toml",
      {"sweep.source=\"analytic\"", "sweep.samples_per_run=32", "sweep.rpm=[450.0, 600.0, 750.0]"});
  spread::lookup::BuildOptions options;
  options.output_path = fixture->path;
  spread::lookup::build_tables(scene, options);
  if (spread_open(fixture->path.c_str(), &fixture->tables) != SPREAD_OK) spread::fuzz::fail(kHarness, "fixture table does not open");
  std::atexit(remove_table);
  int32_t count = 0;
  spread_material_count(fixture->tables, &count);
  for (int32_t i = 0; i < count; ++i) {
    const char* name = nullptr;
    double low = 0.0;
    double high = 0.0;
    spread_material_name(fixture->tables, i, &name);
    spread_material_rpm_range(fixture->tables, i, &low, &high);
    fixture->names.emplace_back(name);
    fixture->min_rpm.push_back(low);
    fixture->max_rpm.push_back(high);
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  build_fixture();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  spread::fuzz::FuzzInput in(data, size);
  const auto raw = in.take<std::uint8_t>();  // bit k set: field k takes raw bytes
  const auto pick = [&](int bit) { return (raw >> bit) & 1u; };

  spread_prediction_def def = spread_prediction_def_default();
  std::string fuzzed_name;
  const auto material = in.take<std::uint8_t>();
  const std::size_t material_count = fixture->names.size();
  std::size_t material_index = material % (material_count + 2);
  if (material_index < material_count) {
    def.material = fixture->names[material_index].c_str();
  } else if (material_index == material_count) {
    def.material = nullptr;
    material_index = 0;
  } else {
    fuzzed_name = in.take_string(80);
    def.material = fuzzed_name.c_str();
    material_index = 0;
  }
  const double low = fixture->min_rpm[material_index];
  const double high = fixture->max_rpm[material_index];
  // Plausible rpm: 10 % either side of the table range, so the range check is crossed both ways.
  def.rpm = pick(0) ? in.take_raw_double() : low - 0.1 * (high - low) + 1.2 * (high - low) * (in.take<std::uint16_t>() / 65535.0);
  def.disc_height_m = pick(1) ? in.take_raw_double() : (in.take<std::uint8_t>() == 0 ? NAN : in.take<std::uint8_t>() * 0.01);
  for (double& w : def.wind_m_s) w = pick(2) ? in.take_raw_double() : in.take<std::int8_t>() * 0.25;
  def.cv_target_percent = pick(3) ? in.take_raw_double() : in.take<std::uint8_t>() * 0.5;
  def.effects = pick(4) ? in.take<std::uint32_t>() : in.take<std::uint8_t>() & SPREAD_EFFECT_ALL;
  def.bout_width_m = pick(5) ? in.take_raw_double() : in.take<std::uint8_t>() * 0.25;
  def.tray_width_m = pick(6) ? in.take_raw_double() : 0.02 + in.take<std::uint8_t>() * 0.01;
  if (pick(7)) def.struct_size = in.take<std::uint32_t>();
  // Outside the landing grid's domain: refused, or (opted in) every sample flown.
  def.fly_outside_domain = in.take<std::uint8_t>() & 1u;

  std::size_t bound = 0;
  const spread_status bound_status = spread_transverse_bound(fixture->tables, def.tray_width_m, &bound);
  spread::fuzz::check_status(kHarness, bound_status, "spread_transverse_bound");
  // Buffer: none, one too small, or the bound. A sentinel shows whether a refused call wrote to it.
  const auto buffer_choice = in.take<std::uint8_t>() % 3;
  const std::size_t capacity = bound_status != SPREAD_OK ? 0 : (buffer_choice == 1 && bound > 0 ? bound - 1 : bound);
  constexpr double kSentinel = -12345.0;
  std::vector<double> trays(capacity + 1, kSentinel);
  double* buffer = buffer_choice == 0 ? nullptr : trays.data();

  spread_prediction result{};
  const spread_status status = spread_predict(fixture->tables, &def, &result, buffer, capacity);
  spread::fuzz::check_status(kHarness, status, "spread_predict");
  if (status == SPREAD_OK) {
    if (bound_status != SPREAD_OK) spread::fuzz::fail(kHarness, "a tray width the bound query refused was accepted");
    spread::fuzz::check_prediction(kHarness, result, buffer, capacity);
  } else if (buffer != nullptr) {
    for (double v : trays) {
      if (v != kSentinel) spread::fuzz::fail(kHarness, std::string("refused call wrote to the buffer: ") + spread_status_str(status));
    }
  }
  if (trays.back() != kSentinel) spread::fuzz::fail(kHarness, "wrote past the buffer's capacity");
  return 0;
}
