#include "libspread/analysis/metrics/input_checks.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace spread::metrics::detail {

void require_valid_trays(const TrayLayout& trays, const char* function) {
  if (!(std::isfinite(trays.tray_width_m) && trays.tray_width_m > 0.0)) {
    throw std::invalid_argument(std::string(function) + ": tray_width_m must be finite and > 0, got " +
                                std::to_string(trays.tray_width_m));
  }
  if (trays.tray_count < 0) {
    throw std::invalid_argument(std::string(function) + ": tray_count must be >= 0, got " +
                                std::to_string(trays.tray_count));
  }
}

void require_tray_span(std::size_t span_size, const TrayLayout& trays, const char* function,
                       const char* span_name) {
  require_valid_trays(trays, function);
  if (span_size != static_cast<std::size_t>(trays.tray_count)) {
    throw std::invalid_argument(std::string(function) + ": " + span_name + " has " +
                                std::to_string(span_size) + " entries but the layout has " +
                                std::to_string(trays.tray_count) + " trays");
  }
}

void require_same_size(std::size_t a, std::size_t b, const char* function, const char* a_name,
                       const char* b_name) {
  if (a != b) {
    throw std::invalid_argument(std::string(function) + ": " + a_name + " (" + std::to_string(a) +
                                " entries) and " + b_name + " (" + std::to_string(b) +
                                " entries) must have the same size");
  }
}

void require_valid_machine(const MachineLayout& machine, const char* function) {
  if (machine.disc_count != 1 && machine.disc_count != 2) {
    throw std::invalid_argument(std::string(function) + ": disc_count must be 1 or 2, got " +
                                std::to_string(machine.disc_count));
  }
  if (!std::isfinite(machine.disc_spacing_m) || machine.disc_spacing_m < 0.0) {
    throw std::invalid_argument(std::string(function) + ": disc_spacing_m must be finite and >= 0, got " +
                                std::to_string(machine.disc_spacing_m));
  }
}

}  // namespace spread::metrics::detail
