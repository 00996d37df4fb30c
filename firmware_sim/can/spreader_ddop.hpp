#pragma once
// The device descriptor object pool of this spreader (ISO 11783-10 Annex B): what a task controller learns
// about the machine before it can drive it. Structure (element numbers in brackets; every element below the
// device names its parent by object ID, and lists only its own DPD / DPT objects):
//   DVC  device "libspread spreader", with a version-4 extended structure label
//   DET  device [0]     actual / set-point work state (141 / 289), actual speed (397)
//   DET  boom [1]       working width set-point / actual / maximum (66 / 67 / 70), condensed work state
//                       set-point / actual (290 / 161), section control state (160), offsets (134-136)
//   DET  bin [2]        application rate set-point / actual (6 / 7)
//   DET  disc [3]       disc speed set-point / actual (389 / 390)
//   DET  section [4+i]  one per section, child of the boom: X and Y offsets (134, 135), width (67)
//   DET  connector [20] child of the device: X / Y offsets (134, 135) and connector type (157) — where
//                       the machine hangs on the tractor, which a TC doing section control needs to place
//                       the sections
// and a value presentation per unit (kg/ha, m, r/min, km/h). Offsets follow ISO 11783-10: X forward,
// Y to the right in the direction of travel, from the device reference point (here the connector);
// section 1 is the leftmost.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "isobus/ddop.hpp"

namespace spread::firmware::can {

struct SpreaderDescription {
  std::string designator = "libspread spreader";
  std::string software_version = "0.1.0";
  std::string serial_number = "SIM-0001";  // the unit's serial (the ECU uses "SIM-" + its identity number)
  std::uint64_t name = 0;           // ISO 11783-5 NAME of the ECU (the working-set master)
  int section_count = 8;            // 1..16
  double working_width_m = 24.0;    // width the sections divide evenly [m] (> 0)
  double maximum_width_m = 54.0;    // DDI 70 [m]
  double boom_offset_x_m = -1.0;    // where the discs throw from, behind the reference point [m]
  // The products the ECU can spread (its launch table's materials, in order): the hopper then carries the
  // product set-point (DDI 57349) and one product-number property (DDI 57350 = k) per product, named by
  // its designator. Empty: no table, no product to choose.
  std::vector<std::string> products;
};

// At most this many products are listed (object IDs 200-263).
inline constexpr std::size_t kMaxListedProducts = 64;

// Throws std::invalid_argument naming a bad field.
isobus::Ddop make_spreader_ddop(const SpreaderDescription& description);

// Element number of the connector (after the highest possible section element, 4 + 15).
inline constexpr std::uint16_t kConnectorElement = 20;

// Whether the pool of a spreader with `section_count` sections has an element with this number.
bool spreader_has_element(std::uint16_t element, int section_count);

// Element number that carries `ddi` in the pool (nullopt: the ECU has no such process data).
std::optional<std::uint16_t> element_for_ddi(std::uint16_t ddi);

}  // namespace spread::firmware::can
