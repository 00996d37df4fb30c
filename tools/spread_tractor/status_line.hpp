#pragma once
// One-line renderings of the ECU's LCM messages for the terminal.
#include <string>

#include "spread/heartbeat_t.hpp"
#include "spread/status_t.hpp"

namespace spread::tractor {

std::string format_status(const spread::status_t& status);
std::string format_heartbeat(const spread::heartbeat_t& heartbeat);
// Names of the active fault bits, e.g. "setpoint_out_of_range,stale_sequence" ("none" when 0).
std::string format_fault_codes(std::int32_t fault_codes);

}  // namespace spread::tractor
