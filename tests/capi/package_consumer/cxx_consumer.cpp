// A C++ program using the installed C API, as a controller's C++ application would: linked with the
// static archive and its own C++ runtime linked statically (-static-libstdc++; tests/capi/package_test.sh).
// It uses std::string and exceptions itself, so its own copies of the C++ runtime's inline and template
// code meet the archive's in one link. Prints what the C example prints first (the working width), or the
// status of a failed open, as package_test.sh's check_run expects.
// Run: ./cxx_consumer TABLES.sqlite
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "spread/spread.h"

namespace {

[[noreturn]] void fail(std::string what, spread_status status) {
  what.insert(0, "spread: ");
  what.append(": ");
  what += spread_status_str(status);
  throw std::runtime_error(what);
}

std::string describe(spread_tables* tables) {
  const char* material = nullptr;
  double min_rpm = 0.0, max_rpm = 0.0;
  spread_status status = spread_material_name(tables, 0, &material);
  if (status != SPREAD_OK) fail("first material", status);
  status = spread_material_rpm_range(tables, 0, &min_rpm, &max_rpm);
  if (status != SPREAD_OK) fail("rpm range", status);

  spread_prediction_def def = spread_prediction_def_default();
  def.material = material;
  def.rpm = 0.5 * (min_rpm + max_rpm);
  size_t capacity = 0;
  status = spread_transverse_bound(tables, def.tray_width_m, &capacity);
  if (status != SPREAD_OK) fail("transverse bound", status);
  std::vector<double> trays(capacity);
  spread_prediction result;
  status = spread_predict(tables, &def, &result, trays.data(), trays.size());
  if (status != SPREAD_OK) fail(std::string(material).append(" prediction"), status);

  std::string line = material;
  line.replace(0, 0, "C++: ");
  line += " at " + std::to_string(static_cast<int>(def.rpm)) + " rpm: working width " +
          std::to_string(result.working_width_to_and_fro_m);
  return line.replace(line.size() - 4, 4, "") + " m (to-and-fro)";  // std::to_string prints 6 decimals
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s TABLES.sqlite\n", argv[0]);
    return 2;
  }
  spread_tables* tables = nullptr;
  try {
    const spread_status status = spread_open(argv[1], &tables);
    if (status != SPREAD_OK) fail(argv[1], status);
    std::puts(describe(tables).c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    spread_close(tables);
    return 1;
  }
  spread_close(tables);
  return 0;
}
