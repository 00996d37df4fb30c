#pragma once
// ISO 11783-11 data dictionary identifiers this ECU implements (docs/design.md §6), with their units.
#include <cstdint>

namespace spread::isobus {

enum class Ddi : std::uint16_t {
  kSetpointMassPerArea = 6,          // [mg/m²] = kg/ha * 100, settable
  kActualMassPerArea = 7,            // [mg/m²]
  kSetpointWorkingWidth = 66,        // [mm], settable
  kActualWorkingWidth = 67,          // [mm] width of the open sections
  kMaximumWorkingWidth = 70,         // [mm]
  kActualWorkState = 141,            // 0 off, 1 on
  kSetpointWorkState = 289,          // 0 off, 1 on, settable
  kSectionControlState = 160,       // 0 manual (off), 1 automatic (on); settable by the TC
  kActualCondensedWorkState1_16 = 161,    // 2 bits per section, section 1 in bits 0-1: 00 off 01 on 11 n/a
  kSetpointCondensedWorkState1_16 = 290,  // same layout, settable; 11 = leave unchanged / not installed
  kSetpointRevolutions = 389,        // [r/min * 1e-4] (value = rpm * 10000), settable in manual mode
  kActualRevolutions = 390,          // [r/min * 1e-4]
  kActualSpeed = 397,                // [mm/s]
  // Manufacturer-proprietary DDIs (ISO 11783-11 leaves 57344-65534 to manufacturers): the data
  // dictionary has none for border spreading or a spreader's wind compensation. All settable, on the
  // discs' element; docs/can-integration.md "Border spreading and wind" lists them.
  kSetpointBorderMode = 57344,        // 0 off, 1 left border, 2 right border, 3 left field edge, 4 right field edge
  kSetpointBorderGap = 57345,         // [mm] the edge line this far inside the bout's edge
  kSetpointWindCompensation = 57346,  // 0 off, 1 on
  kSetpointWindAcross = 57347,        // [mm/s] measured wind across the travel, to the right
  kSetpointWindAlong = 57348,         // [mm/s] measured wind along the travel, forward
  // The product in the hopper (on the bin's element): the number k of the k-th material of the ECU's
  // launch table, which the pool lists as one property each (kProductNumber, designator = the material's
  // name). 0 = none known yet; settable 1..n. ISO 11783-10's product structure (a product per bin, chosen
  // in the task) needs a task and ISOXML; a number on the bin is what a TC without tasks can set.
  kSetpointProduct = 57349,
  kProductNumber = 57350,             // property: the number of the product its designator names
};

inline constexpr double kRevolutionsScale = 1e4;  // counts per r/min for DDI 389/390

}  // namespace spread::isobus
