#pragma once
// Argument checks shared by the metrics functions: each throws std::invalid_argument naming the
// function and the offending input (programming errors, not data conditions).
#include <cstddef>

#include "libspread/analysis/metrics/metrics.hpp"

namespace spread::metrics::detail {

void require_valid_trays(const TrayLayout& trays, const char* function);
void require_tray_span(std::size_t span_size, const TrayLayout& trays, const char* function,
                       const char* span_name);
void require_same_size(std::size_t a, std::size_t b, const char* function, const char* a_name,
                       const char* b_name);
void require_valid_machine(const MachineLayout& machine, const char* function);

}  // namespace spread::metrics::detail
