#include "firmware_sim/can/spreader_ddop.hpp"

#include <cmath>
#include <stdexcept>

#include "isobus/ddi.hpp"

namespace spread::firmware::can {
namespace {

using namespace isobus;  // the pool is built of the protocol's objects and DDIs

constexpr std::uint16_t kDeviceElement = 0;
constexpr std::uint16_t kBoomElement = 1;
constexpr std::uint16_t kBinElement = 2;
constexpr std::uint16_t kDiscElement = 3;
constexpr std::uint16_t kFirstSectionElement = 4;

// Object IDs: fixed for the fixed part, sections from 100 on (three objects each after their DET).
enum : std::uint16_t {
  kDvc = 0,
  kDetDevice = 1,
  kDetBoom = 2,
  kDetBin = 3,
  kDetDisc = 4,
  kDetConnector = 5,
  kDvpRate = 10,
  kDvpMetre = 11,
  kDvpRpm = 12,
  kDvpSpeed = 13,
  kDpdActualWorkState = 20,
  kDpdSetpointWorkState = 21,
  kDpdActualSpeed = 22,
  kDpdSetpointWidth = 30,
  kDpdActualWidth = 31,
  kDpdMaximumWidth = 32,
  kDpdSetpointCondensed = 33,
  kDpdActualCondensed = 34,
  kDptBoomX = 35,
  kDptBoomY = 36,
  kDptBoomZ = 37,
  kDpdSectionControlState = 38,
  kDpdSetpointRate = 40,
  kDpdActualRate = 41,
  kDpdSetpointRpm = 50,
  kDpdActualRpm = 51,
  kDpdBorderMode = 52,
  kDpdBorderGap = 53,
  kDpdWindCompensation = 54,
  kDpdWindAcross = 55,
  kDpdWindAlong = 56,
  kDvpWind = 14,
  kDptConnectorX = 60,
  kDptConnectorY = 61,
  kDptConnectorType = 62,
  kDpdProduct = 42,
  kFirstSection = 100,
  kFirstProduct = 200,
};

constexpr std::uint8_t kSetpoint = kPropertyDefaultSet | kPropertySettable;
// DDI 157 connector type 3: ISO 730 three-point hitch, mounted (ISO 11783-11).
constexpr std::int32_t kConnectorThreePointMounted = 3;
constexpr std::uint16_t kDdiOffsetX = 134;
constexpr std::uint16_t kDdiOffsetY = 135;
constexpr std::uint16_t kDdiOffsetZ = 136;
constexpr std::uint16_t kDdiConnectorType = 157;
// Actual values: the TC may ask for them on a time or distance interval, on thresholds or on change.
constexpr std::uint8_t kMeasured = kTriggerTimeInterval | kTriggerDistanceInterval | kTriggerThresholdLimits |
                                   kTriggerOnChange;

std::uint16_t ddi(Ddi d) { return static_cast<std::uint16_t>(d); }

std::int32_t millimetres(double metres) { return static_cast<std::int32_t>(std::lround(metres * 1000.0)); }

}  // namespace

bool spreader_has_element(std::uint16_t element, int section_count) {
  return element < kFirstSectionElement || element == kConnectorElement ||
         (element >= kFirstSectionElement && element < kFirstSectionElement + section_count);
}

std::optional<std::uint16_t> element_for_ddi(std::uint16_t value) {
  switch (static_cast<Ddi>(value)) {
    case Ddi::kActualWorkState:
    case Ddi::kSetpointWorkState:
    case Ddi::kActualSpeed:
      return kDeviceElement;
    case Ddi::kSetpointWorkingWidth:
    case Ddi::kActualWorkingWidth:
    case Ddi::kMaximumWorkingWidth:
    case Ddi::kSetpointCondensedWorkState1_16:
    case Ddi::kActualCondensedWorkState1_16:
    case Ddi::kSectionControlState:
      return kBoomElement;
    case Ddi::kSetpointMassPerArea:
    case Ddi::kActualMassPerArea:
    case Ddi::kSetpointProduct:
    case Ddi::kProductNumber:
      return kBinElement;
    case Ddi::kSetpointRevolutions:
    case Ddi::kActualRevolutions:
    case Ddi::kSetpointBorderMode:
    case Ddi::kSetpointBorderGap:
    case Ddi::kSetpointWindCompensation:
    case Ddi::kSetpointWindAcross:
    case Ddi::kSetpointWindAlong:
      return kDiscElement;
  }
  return std::nullopt;
}

isobus::Ddop make_spreader_ddop(const SpreaderDescription& d) {
  if (d.section_count < 1 || d.section_count > 16) {
    throw std::invalid_argument("SpreaderDescription.section_count: must be 1..16, got " +
                                std::to_string(d.section_count));
  }
  if (!(d.working_width_m > 0.0) || !(d.working_width_m <= d.maximum_width_m) || !std::isfinite(d.maximum_width_m)) {
    throw std::invalid_argument("SpreaderDescription.working_width_m: must lie in (0, maximum_width_m]");
  }
  if (!std::isfinite(d.boom_offset_x_m) || std::abs(d.boom_offset_x_m) > 100.0) {
    throw std::invalid_argument("SpreaderDescription.boom_offset_x_m: must be finite and within 100 m");
  }
  if (d.products.size() > kMaxListedProducts) {
    throw std::invalid_argument("SpreaderDescription.products: at most " + std::to_string(kMaxListedProducts) +
                                " products, got " + std::to_string(d.products.size()));
  }
  Ddop pool;
  auto& o = pool.objects;

  DeviceObject device;
  device.id = kDvc;
  device.designator = d.designator;
  device.software_version = d.software_version;
  device.working_set_master_name = d.name;
  device.serial_number = d.serial_number;
  // The structure label changes with the layout, so a TC holding an older pool of this machine reloads it:
  // sections, width and the layout revision (3: elements by parent ID, connector, DDI 160, the border and
  // wind DDIs) in the 7 bytes every TC version compares; the boom's X offset, the one other value the
  // pool carries, in the version-4 extended structure label.
  const auto width_cm = static_cast<std::uint32_t>(std::lround(d.working_width_m * 100.0));
  device.structure_label = {'L', 'S', 'P', static_cast<std::uint8_t>(d.section_count),
                            static_cast<std::uint8_t>(width_cm & 0xFFu), static_cast<std::uint8_t>(width_cm >> 8),
                            // Layout revision 3; with a product list, 0x40 + the number of products.
                            static_cast<std::uint8_t>(d.products.empty() ? 0x03 : 0x40 + d.products.size())};
  const auto offset_mm = static_cast<std::uint32_t>(millimetres(d.boom_offset_x_m));
  device.extended_structure_label = {'L',
                                     'S',
                                     'P',
                                     static_cast<std::uint8_t>(offset_mm),
                                     static_cast<std::uint8_t>(offset_mm >> 8),
                                     static_cast<std::uint8_t>(offset_mm >> 16),
                                     static_cast<std::uint8_t>(offset_mm >> 24)};
  // ISO 11783-6 language command bytes: "en", decimal point and 24 h, day-month-year, metric units.
  device.localization_label = {'e', 'n', 0x50, 0x00, 0x00, 0x00, 0xFF};
  o.emplace_back(device);

  // The tree: each element names its parent; its object list holds only its DPD / DPT objects.
  o.emplace_back(DeviceElement{kDetDevice, ElementType::kDevice, "Spreader", kDeviceElement, kDvc,
                               {kDpdActualWorkState, kDpdSetpointWorkState, kDpdActualSpeed}});
  o.emplace_back(DeviceElement{kDetBoom, ElementType::kFunction, "Boom", kBoomElement, kDetDevice,
                               {kDpdSetpointWidth, kDpdActualWidth, kDpdMaximumWidth, kDpdSetpointCondensed,
                                kDpdActualCondensed, kDpdSectionControlState, kDptBoomX, kDptBoomY, kDptBoomZ}});
  std::vector<std::uint16_t> bin_objects{kDpdSetpointRate, kDpdActualRate};
  if (!d.products.empty()) bin_objects.push_back(kDpdProduct);
  for (std::size_t k = 0; k < d.products.size(); ++k) bin_objects.push_back(static_cast<std::uint16_t>(kFirstProduct + k));
  o.emplace_back(DeviceElement{kDetBin, ElementType::kBin, "Hopper", kBinElement, kDetDevice, bin_objects});
  o.emplace_back(DeviceElement{kDetDisc, ElementType::kFunction, "Discs", kDiscElement, kDetDevice,
                               {kDpdSetpointRpm, kDpdActualRpm, kDpdBorderMode, kDpdBorderGap, kDpdWindCompensation,
                                kDpdWindAcross, kDpdWindAlong}});
  o.emplace_back(DeviceElement{kDetConnector, ElementType::kConnector, "Hitch", kConnectorElement, kDetDevice,
                               {kDptConnectorX, kDptConnectorY, kDptConnectorType}});

  // Presentations: raw value + offset, times scale, gives the unit shown.
  o.emplace_back(DeviceValuePresentation{kDvpRate, 0, 0.01f, 1, "kg/ha"});   // mg/m² -> kg/ha
  o.emplace_back(DeviceValuePresentation{kDvpMetre, 0, 0.001f, 2, "m"});     // mm -> m
  o.emplace_back(DeviceValuePresentation{kDvpRpm, 0, 1e-4f, 1, "r/min"});    // r/min * 1e-4 -> r/min
  o.emplace_back(DeviceValuePresentation{kDvpSpeed, 0, 0.0036f, 1, "km/h"});  // mm/s -> km/h
  o.emplace_back(DeviceValuePresentation{kDvpWind, 0, 0.001f, 1, "m/s"});     // mm/s -> m/s

  o.emplace_back(DeviceProcessData{kDpdActualWorkState, ddi(Ddi::kActualWorkState), kPropertyDefaultSet,
                                   kMeasured, "Work state", kNullObjectId});
  o.emplace_back(DeviceProcessData{kDpdSetpointWorkState, ddi(Ddi::kSetpointWorkState), kSetpoint, kTriggerOnChange,
                                   "Work state set-point", kNullObjectId});
  o.emplace_back(DeviceProcessData{kDpdActualSpeed, ddi(Ddi::kActualSpeed), 0, kMeasured, "Speed", kDvpSpeed});
  o.emplace_back(DeviceProcessData{kDpdSetpointWidth, ddi(Ddi::kSetpointWorkingWidth), kSetpoint, kTriggerOnChange,
                                   "Working width set-point", kDvpMetre});
  o.emplace_back(DeviceProcessData{kDpdActualWidth, ddi(Ddi::kActualWorkingWidth), kPropertyDefaultSet, kMeasured,
                                   "Working width", kDvpMetre});
  o.emplace_back(DeviceProcessData{kDpdMaximumWidth, ddi(Ddi::kMaximumWorkingWidth), 0, kTriggerOnChange,
                                   "Maximum working width", kDvpMetre});
  o.emplace_back(DeviceProcessData{kDpdSetpointCondensed, ddi(Ddi::kSetpointCondensedWorkState1_16), kSetpoint,
                                   kTriggerOnChange, "Sections set-point", kNullObjectId});
  o.emplace_back(DeviceProcessData{kDpdActualCondensed, ddi(Ddi::kActualCondensedWorkState1_16),
                                   kPropertyDefaultSet, kTriggerOnChange | kTriggerTimeInterval, "Sections",
                                   kNullObjectId});
  // Section control state (DDI 160): the TC says whether it switches the sections automatically.
  o.emplace_back(DeviceProcessData{kDpdSectionControlState, ddi(Ddi::kSectionControlState), kSetpoint,
                                   kTriggerOnChange | kTriggerTimeInterval, "Section control", kNullObjectId});
  o.emplace_back(DeviceProperty{kDptBoomX, kDdiOffsetX, millimetres(d.boom_offset_x_m), "Offset X", kDvpMetre});
  o.emplace_back(DeviceProperty{kDptBoomY, kDdiOffsetY, 0, "Offset Y", kDvpMetre});
  o.emplace_back(DeviceProperty{kDptBoomZ, kDdiOffsetZ, 0, "Offset Z", kDvpMetre});
  // The connector is the device reference point: its offsets are 0.
  o.emplace_back(DeviceProperty{kDptConnectorX, kDdiOffsetX, 0, "Offset X", kDvpMetre});
  o.emplace_back(DeviceProperty{kDptConnectorY, kDdiOffsetY, 0, "Offset Y", kDvpMetre});
  o.emplace_back(DeviceProperty{kDptConnectorType, kDdiConnectorType, kConnectorThreePointMounted, "Type",
                                kNullObjectId});
  o.emplace_back(DeviceProcessData{kDpdSetpointRate, ddi(Ddi::kSetpointMassPerArea), kSetpoint,
                                   kTriggerOnChange | kTriggerTimeInterval, "Rate set-point", kDvpRate});
  o.emplace_back(DeviceProcessData{kDpdActualRate, ddi(Ddi::kActualMassPerArea), kPropertyDefaultSet, kMeasured,
                                   "Rate", kDvpRate});
  if (!d.products.empty()) {
    // The product in the hopper, and the products to choose from: property k names product k.
    o.emplace_back(DeviceProcessData{kDpdProduct, ddi(Ddi::kSetpointProduct), kSetpoint, kTriggerOnChange, "Product",
                                     kNullObjectId});
    for (std::size_t k = 0; k < d.products.size(); ++k) {
      // ISO 11783-10 designators hold at most 32 bytes (version 4 pools): longer names are cut.
      o.emplace_back(DeviceProperty{static_cast<std::uint16_t>(kFirstProduct + k), ddi(Ddi::kProductNumber),
                                    static_cast<std::int32_t>(k + 1), d.products[k].substr(0, 32), kNullObjectId});
    }
  }
  o.emplace_back(DeviceProcessData{kDpdSetpointRpm, ddi(Ddi::kSetpointRevolutions), kSetpoint, kTriggerOnChange,
                                   "Disc speed set-point", kDvpRpm});
  o.emplace_back(DeviceProcessData{kDpdActualRpm, ddi(Ddi::kActualRevolutions), kPropertyDefaultSet, kMeasured,
                                   "Disc speed", kDvpRpm});
  // Border spreading and wind compensation: manufacturer-proprietary DDIs (ddi.hpp).
  o.emplace_back(DeviceProcessData{kDpdBorderMode, ddi(Ddi::kSetpointBorderMode), kSetpoint, kTriggerOnChange,
                                   "Border spreading", kNullObjectId});
  o.emplace_back(DeviceProcessData{kDpdBorderGap, ddi(Ddi::kSetpointBorderGap), kSetpoint, kTriggerOnChange,
                                   "Border gap", kDvpMetre});
  o.emplace_back(DeviceProcessData{kDpdWindCompensation, ddi(Ddi::kSetpointWindCompensation), kSetpoint,
                                   kTriggerOnChange, "Wind compensation", kNullObjectId});
  o.emplace_back(DeviceProcessData{kDpdWindAcross, ddi(Ddi::kSetpointWindAcross), kSetpoint, kTriggerOnChange,
                                   "Wind across", kDvpWind});
  o.emplace_back(DeviceProcessData{kDpdWindAlong, ddi(Ddi::kSetpointWindAlong), kSetpoint, kTriggerOnChange,
                                   "Wind along", kDvpWind});

  const double section_width_m = d.working_width_m / d.section_count;
  for (int i = 0; i < d.section_count; ++i) {
    const auto id = static_cast<std::uint16_t>(kFirstSection + 4 * i);
    const double y_m = -0.5 * d.working_width_m + (i + 0.5) * section_width_m;  // section 1 leftmost
    o.emplace_back(DeviceElement{id, ElementType::kSection, "Section " + std::to_string(i + 1),
                                 static_cast<std::uint16_t>(kFirstSectionElement + i), kDetBoom,
                                 {static_cast<std::uint16_t>(id + 1), static_cast<std::uint16_t>(id + 2),
                                  static_cast<std::uint16_t>(id + 3)}});
    o.emplace_back(DeviceProperty{static_cast<std::uint16_t>(id + 1), kDdiOffsetX, millimetres(d.boom_offset_x_m),
                                  "Offset X", kDvpMetre});
    o.emplace_back(
        DeviceProperty{static_cast<std::uint16_t>(id + 2), kDdiOffsetY, millimetres(y_m), "Offset Y", kDvpMetre});
    o.emplace_back(DeviceProperty{static_cast<std::uint16_t>(id + 3), ddi(Ddi::kActualWorkingWidth),
                                  millimetres(section_width_m), "Width", kDvpMetre});
  }
  return pool;
}

}  // namespace spread::firmware::can
