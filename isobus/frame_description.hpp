#pragma once
// One-line human-readable decoding of an ISOBUS frame, for the terminal tools:
//   "0x80->0x81 PD value element 0 DDI 390 actual revolutions = 750.0000 r/min"
#include <string>

#include "isobus/can/can_frame_port.hpp"

namespace spread::isobus {

std::string describe_frame(const can_frame& frame);
// Name and unit of a DDI this ECU implements ("actual revolutions", "r/min"); "unknown DDI" otherwise.
std::string ddi_name(std::uint16_t ddi);
// Value of a DDI in its display unit (e.g. DDI 390 raw 7500000 -> "750.0000 r/min").
std::string format_ddi_value(std::uint16_t ddi, std::int32_t raw);

}  // namespace spread::isobus
