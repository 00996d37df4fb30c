#include "firmware_sim/can/can_ecu_link.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>

#include "firmware_sim/can/fault_dtc.hpp"
#include "firmware_sim/can/spreader_ddop.hpp"
#include "libspread/control/metering.hpp"
#include "isobus/ddi.hpp"
#include "isobus/isobus_id.hpp"
#include "isobus/speed_messages.hpp"

namespace spread::firmware::can {
// The ECU's side of the bus is written in the protocol's and the bus's own terms.
using namespace isobus;
using namespace isobus::can;

namespace {

std::int32_t to_int32(double value) {
  if (!std::isfinite(value)) return 0;
  const double r = std::round(value);
  if (r >= static_cast<double>(std::numeric_limits<std::int32_t>::max())) {
    return std::numeric_limits<std::int32_t>::max();
  }
  if (r <= static_cast<double>(std::numeric_limits<std::int32_t>::min())) {
    return std::numeric_limits<std::int32_t>::min();
  }
  return static_cast<std::int32_t>(r);
}

std::uint8_t pdack_bits_for(Fault fault) {
  switch (fault) {
    case Fault::kSetpointOutOfRange: return kPdackValueOutOfRange;
    // A function this device cannot run now (wind compensation without its tables): outside its range.
    case Fault::kAutomaticUnavailable: return kPdackValueOutOfRange;
    // A command that needs the product (a narrowed side, a border, wind compensation) before one is known:
    // the device cannot carry it out now.
    case Fault::kUnknownMaterial: return kPdackValueOutOfRange;
    case Fault::kNotANumber: return kPdackValueNotConform;
    case Fault::kCanNotSettable: return kPdackNotSettable;
    case Fault::kCanUnknownDdi: return kPdackDdiNotSupported;
    case Fault::kCanUnsupportedCommand: return kPdackCommandNotSupported;
    default: return kPdackValueNotConform;
  }
}

// Condensed work state: 2 bits per section, section 1 in bits 0-1 (00 off, 01 on, 11 not installed).
std::int32_t condensed_work_state(std::uint16_t mask, std::int32_t section_count) {
  std::uint32_t value = 0;
  for (int i = 0; i < kMaxSections; ++i) {
    std::uint32_t state = 3;  // not installed
    if (i < section_count) state = ((mask >> i) & 1u) != 0 ? 1u : 0u;
    value |= state << (2 * i);
  }
  return static_cast<std::int32_t>(value);
}

ProcessDataBytes frame_bytes(const can_frame& frame) {
  ProcessDataBytes b{};
  std::copy(frame.data, frame.data + 8, b.begin());
  return b;
}

}  // namespace

namespace {

struct PoolBytes {
  std::vector<std::uint8_t> version4;
  std::vector<std::uint8_t> version3;
  std::array<std::uint8_t, 7> structure_label{};
  std::array<std::uint8_t, 7> localization_label{};
};

// The pool of the machine as set: its sections divide `working_width_m` evenly, as the ECU's section
// control does (side_geometry), so a TC switching by position uses the sections the ECU works with.
PoolBytes make_pool(const Ecu& ecu, const CanEcuSettings& settings, double working_width_m) {
  SpreaderDescription d;
  d.name = settings.name;
  // The pool's serial number is the unit's: the NAME's identity number, which differs between units.
  d.serial_number = "SIM-" + std::to_string(isobus::decode_name(settings.name).identity_number);
  d.section_count = ecu.parameters().section_count;
  d.maximum_width_m = ecu.parameters().width_max_m;
  d.working_width_m = std::min(working_width_m, d.maximum_width_m);
  d.products = ecu.material_names();
  if (d.products.size() > kMaxListedProducts) d.products.resize(kMaxListedProducts);
  const isobus::Ddop pool = make_spreader_ddop(d);
  const auto& device = std::get<isobus::DeviceObject>(pool.objects.front());
  return {isobus::write_ddop(pool), isobus::write_ddop(pool, 3), device.structure_label, device.localization_label};
}

isobus::TaskControllerClient make_tc_client(const Ecu& ecu, const CanEcuSettings& settings) {
  PoolBytes p = make_pool(ecu, settings, settings.nominal_width_m);
  isobus::TcClientSettings tc;
  tc.version.sections = static_cast<std::uint8_t>(ecu.parameters().section_count);
  return isobus::TaskControllerClient(std::move(p.version4), p.structure_label, p.localization_label, tc,
                                      std::move(p.version3));
}

}  // namespace

CanEcuProcessor::CanEcuProcessor(Ecu& ecu, const Clock& clock, CanFrameSink& tx, const CanEcuSettings& settings)
    : ecu_(ecu),
      clock_(clock),
      tx_(tx),
      settings_(settings),
      network_(clock, tx, settings.name, settings.address),
      transport_(settings.address),
      tc_client_(make_tc_client(ecu, settings)),
      pool_width_m_(std::min(settings.nominal_width_m, ecu.parameters().width_max_m)) {}

void CanEcuProcessor::follow_working_width(Nanoseconds now) {
  // ISO 11783-10: the pool describes the machine as it works. A new working width moves every section's
  // width and offset, so the pool is made again and, if a TC holds the old one, replaced (deactivate,
  // transfer, activate). A width of 0 (not set) keeps the pool as it is.
  const double width_m = ecu_.status().width_setpoint_m;
  if (!(width_m > 0.0) || std::abs(width_m - pool_width_m_) < 0.0005) return;
  pool_width_m_ = width_m;
  PoolBytes p = make_pool(ecu_, settings_, width_m);
  tc_client_.replace_pool(std::move(p.version4), p.structure_label, p.localization_label, std::move(p.version3), now);
}

void CanEcuProcessor::flush_isobus(Nanoseconds now) {
  if (!network_.has_address()) return;  // nothing but claims without a standing claim
  if (transport_.address() != network_.address()) transport_.set_address(network_.address());
  for (const isobus::TcOutgoing& m : tc_client_.take_outgoing()) {
    if (m.data.size() <= 8) {
      std::uint8_t data[8];
      std::fill(std::begin(data), std::end(data), std::uint8_t{0xFF});
      std::copy(m.data.begin(), m.data.end(), data);
      send(m.pgn, m.destination, isobus::kTcMessagePriority, data);
    } else if (!transport_.send({m.pgn, network_.address(), m.destination, m.data}, now)) {
      ++counters_.send_failures;  // the client times out and tries again
    }
  }
  transport_.update(now);
  for (const isobus::TransportFrame& f : transport_.take_frames()) {
    const IsobusId id{f.priority, f.pgn, f.destination, network_.address()};
    if (tx_.send(make_frame(encode_id(id), f.data.data(), 8))) {
      ++counters_.transport_frames_sent;
    } else {
      ++counters_.send_failures;
    }
  }
  transport_.take_ended();  // the client learns the outcome from the TC's answer (or its timeout)
}

void CanEcuProcessor::send(std::uint32_t pgn, std::uint8_t destination, std::uint8_t priority,
                           const std::uint8_t* data) {
  if (!network_.has_address()) return;  // ISO 11783-5 §4.4.2: nothing but claims without a standing claim
  const IsobusId id{priority, pgn, destination, network_.address()};
  if (tx_.send(make_frame(encode_id(id), data, 8))) {
    ++counters_.responses_sent;
  } else {
    ++counters_.send_failures;
  }
}

void CanEcuProcessor::start_address_claim() { network_.start(); }

void CanEcuProcessor::service() {
  // Fail safe without an address: a spreader nobody can address or supervise closes metering (and on
  // losing the address its work state goes off); the task controller switches it on again once the ECU
  // is back on the bus.
  const bool lost = network_.service();
  ecu_.set_bus_address(network_.has_address());
  const Nanoseconds now = clock_.now();
  if (lost) {
    // Our address was taken, or we moved to another one (self-configurable): the TC knows our working
    // set by an address we no longer hold. The connection starts over from the working-set master
    // message (ISO 11783-10), and until the pool is active again no process data goes either way.
    tc_client_.restart("our address was lost or changed");
    rejoin_pending_ = true;
  }
  if (partner_.update(now, ecu_.parameters().task_controller_timeout)) partner_lost(now);
  if (rejoin_pending_ && network_.has_address() && partner_.address() &&
      tc_client_.state() == isobus::TcClientState::kWaitForTc) {
    // Back on the bus with a TC we know: start at once rather than at its next status (up to 2 s).
    tc_client_.connect(*partner_.address(), now);
  }
  follow_working_width(now);
  tc_client_.update(now);
  if (tc_client_.connected()) rejoin_pending_ = false;
  // A connection that ended takes its measurement triggers with it; the next one sets them again.
  if (tc_was_connected_ && !tc_client_.connected()) {
    triggers_.clear();
    section_control_state_ = 0;  // nobody switches the sections automatically any more
  }
  tc_was_connected_ = tc_client_.connected();
  send_measurements(now);
  send_dm1(now);
  flush_isobus(now);
}

void CanEcuProcessor::send_measurements(Nanoseconds now) {
  const EcuStatus s = ecu_.status();
  const double dt_s = last_measurement_time_ ? to_seconds(now - *last_measurement_time_) : 0.0;
  last_measurement_time_ = now;
  if (!network_.has_address() || rejoining()) return;
  triggers_.evaluate(
      now, s.ground_speed_m_s * dt_s * 1000.0, [&](std::uint16_t ddi) { return actual_value(ddi, s); },
      [&](const MeasurementSubscription& m, std::int32_t value) {
        const ProcessDataBytes out = encode_process_data(
            {static_cast<std::uint8_t>(ProcessDataCommand::kValue), m.element, m.ddi, value});
        send(kProcessDataPgn, m.requester, kProcessDataPriority, out.data());
        ++counters_.measurements_sent;
      });
}

void CanEcuProcessor::send_dm1(Nanoseconds now) {
  if (!network_.has_address()) return;
  if (next_dm1_ && now < *next_dm1_) return;
  next_dm1_ = now + std::chrono::seconds(1);
  const EcuStatus s = ecu_.status();
  std::array<isobus::Dtc, kFaultCount> active{};
  std::size_t n = 0;
  bool warning = false;
  for (std::size_t i = 0; i < kFaultCount; ++i) {
    const auto fault = static_cast<Fault>(i);
    if ((s.fault_codes & fault_bit(fault)) == 0) continue;
    active[n++] = dtc_for(fault, s.fault_counts[i]);
    // The amber lamp: a condition that holds now (metering held closed, a width out of reach), not a
    // refused message of the last seconds.
    warning = warning || is_state_fault(fault);
  }
  const std::vector<std::uint8_t> dm1 =
      isobus::encode_dm1(isobus::Lamps{false, false, warning, false}, std::span(active.data(), n));
  if (dm1.size() <= 8) {
    std::uint8_t data[8];
    std::fill(std::begin(data), std::end(data), std::uint8_t{0xFF});
    std::copy(dm1.begin(), dm1.end(), data);
    send(isobus::kDm1Pgn, kGlobalAddress, isobus::kDm1Priority, data);
  } else if (!transport_.send({isobus::kDm1Pgn, network_.address(), kGlobalAddress, dm1}, now)) {
    ++counters_.send_failures;  // the last second's BAM is still going out
    return;
  }
  ++counters_.dm1_sent;
}

void CanEcuProcessor::handle_read_outcome(ReadOutcome outcome) {
  if (outcome == ReadOutcome::kTruncated || outcome == ReadOutcome::kOversized) {
    ++counters_.frames_received;
    ecu_.record_fault(Fault::kCanMalformedFrame);
  }
}

void CanEcuProcessor::handle_frame(const can_frame& frame) {
  ++counters_.frames_received;
  if ((frame.can_id & CAN_ERR_FLAG) != 0) {
    ++counters_.error_frames;
    return;
  }
  // ISOBUS messages are extended data frames. Other nodes may legally send standard (11-bit) frames
  // (ISO 11783-3 leaves them to proprietary use) and remote frames: not ours, and no fault of ours.
  if ((frame.can_id & (CAN_RTR_FLAG)) != 0 || (frame.can_id & CAN_EFF_FLAG) == 0) {
    ++counters_.frames_ignored;
    return;
  }
  if (frame.len > CAN_MAX_DLEN) {
    ecu_.record_fault(Fault::kCanMalformedFrame);
    return;
  }
  const IsobusId id = decode_id(frame.can_id & CAN_EFF_MASK);
  // Every address claim also tells who holds which address: the partner TC is known by its NAME.
  if (id.pgn == isobus::kAddressClaimedPgn && frame.len == 8 &&
      partner_.on_address_claimed(id.source, isobus::name_from_bytes(frame.data))) {
    partner_lost(clock_.now());
  }
  // Network management first: another node's claim for our address carries our source address and must
  // not be mistaken for our own echo below.
  switch (network_.handle(id, frame)) {
    case NetworkLink::Verdict::kNotNetwork: break;
    case NetworkLink::Verdict::kHandled: return;
    case NetworkLink::Verdict::kMalformed: ecu_.record_fault(Fault::kCanMalformedFrame); return;
  }
  if (id.source == network_.address()) {
    // Our own frames never come back (CAN_RAW without RECV_OWN_MSGS, spread-canbus without echo): another
    // node is sending from our address. Not acted on; our claim goes out again (ISO 11783-5).
    ++counters_.frames_not_for_us;
    network_.on_address_violation();
    return;
  }
  const bool to_us = id.destination == network_.address();
  const bool to_all = id.destination == kGlobalAddress;
  if (!to_us && !to_all) {
    ++counters_.frames_not_for_us;
    return;
  }
  switch (id.pgn) {
    case isobus::kTpConnectionManagementPgn:
    case isobus::kTpDataTransferPgn:
    case isobus::kEtpConnectionManagementPgn:
    case isobus::kEtpDataTransferPgn: {
      // ISO 11783-3/-6 transport: the pool transfer's flow control (and any long message to us).
      isobus::TransportFrame f;
      f.priority = id.priority;
      f.pgn = id.pgn;
      f.source = id.source;
      f.destination = id.destination;
      std::fill(f.data.begin(), f.data.end(), std::uint8_t{0xFF});
      std::copy(frame.data, frame.data + std::min<std::size_t>(frame.len, 8), f.data.begin());
      const Nanoseconds now = clock_.now();
      transport_.handle_frame(f, now);
      for (const isobus::TransportMessage& m : transport_.take_received()) {
        if (m.pgn != kProcessDataPgn) continue;
        if (partner_.is_partner(m.source)) {
          tc_client_.handle_message(m.source, m.data, now);
        } else {
          ++counters_.not_from_partner;
          ecu_.record_fault(Fault::kCanNotFromTaskController);
        }
      }
      flush_isobus(now);
      return;
    }
    case kProcessDataPgn:
      if (frame.len != 8) {
        ecu_.record_fault(Fault::kCanMalformedFrame);
        return;
      }
      handle_process_data(frame, id.source, to_us);
      return;
    case kAcknowledgementPgn:
      handle_acknowledgement(frame, id.source, to_us);
      return;
    case kWheelBasedSpeedPgn:
    case kGroundBasedSpeedPgn:
    case kMachineSelectedSpeedPgn:
      if (frame.len != 8) {
        ecu_.record_fault(Fault::kCanMalformedFrame);
        return;
      }
      handle_speed(frame, id.pgn == kMachineSelectedSpeedPgn ? SpeedSource::kMachineSelected
                          : id.pgn == kGroundBasedSpeedPgn   ? SpeedSource::kGroundBased
                                                             : SpeedSource::kWheelBased);
      return;
    default:
      ++counters_.frames_not_for_us;
      return;
  }
}

void CanEcuProcessor::handle_speed(const can_frame& frame, SpeedSource source) {
  const Nanoseconds now = clock_.now();
  std::array<std::uint8_t, 8> bytes{};
  std::copy(frame.data, frame.data + 8, bytes.begin());
  const auto speed = decode_speed(bytes);
  SpeedReading& reading = speeds_[static_cast<std::size_t>(source)];
  if (speed) {
    ++counters_.speed_messages;
    reading.time = now;
    reading.speed_m_s = speed->speed_m_s;
    reading.direction = speed->direction == Direction::kReverse   ? TravelDirection::kReverse
                        : speed->direction == Direction::kForward ? TravelDirection::kForward
                                                                  : TravelDirection::kUnknown;
  } else {
    // The source itself says it has no valid speed: it is out at once, not after its timeout.
    ++counters_.speed_not_available;
    reading.time.reset();
  }
  // The best source heard within its timeout gives the speed, valid for what is left of that timeout.
  for (const SpeedReading& r : speeds_) {
    if (r.time && now - *r.time <= settings_.speed_timeout) {
      ecu_.set_ground_speed(r.speed_m_s, r.direction, settings_.speed_timeout - (now - *r.time));
      return;  // out of range is counted by the ECU
    }
  }
  ecu_.set_ground_speed_unavailable();
}

std::optional<std::int32_t> CanEcuProcessor::actual_value(std::uint16_t ddi, const EcuStatus& s) const {
  switch (static_cast<Ddi>(ddi)) {
    case Ddi::kSetpointMassPerArea: return to_int32(s.rate_setpoint_kg_ha * kMilligramPerSquareMetrePerKgPerHa);
    case Ddi::kActualMassPerArea: return to_int32(s.rate_actual_kg_ha * kMilligramPerSquareMetrePerKgPerHa);
    case Ddi::kSetpointWorkingWidth: return to_int32(s.width_setpoint_m * 1000.0);
    case Ddi::kActualWorkingWidth: return to_int32(s.width_actual_m * 1000.0);
    case Ddi::kMaximumWorkingWidth: return to_int32(ecu_.parameters().width_max_m * 1000.0);
    case Ddi::kActualWorkState: return s.work_state_actual ? 1 : 0;
    case Ddi::kSetpointWorkState: return s.work_state_setpoint ? 1 : 0;
    case Ddi::kActualCondensedWorkState1_16: {
      // What the discs actually spread, which can differ from the set-point (section control through the
      // discs, ecu_status.hpp): ISO 11783-10's actual state tells the TC.
      const auto open = static_cast<std::uint16_t>(s.work_state_actual ? s.section_actual_mask : 0u);
      return condensed_work_state(open, s.section_count);
    }
    case Ddi::kSetpointCondensedWorkState1_16: return condensed_work_state(s.section_mask, s.section_count);
    case Ddi::kSetpointRevolutions: return to_int32(s.rpm_target * kRevolutionsScale);
    case Ddi::kSetpointBorderMode: return static_cast<std::int32_t>(s.border_mode);
    case Ddi::kSetpointBorderGap: return to_int32(s.border_gap_m * 1000.0);
    case Ddi::kSetpointWindCompensation: return s.wind_compensation ? 1 : 0;
    case Ddi::kSetpointWindAcross: return to_int32(s.wind_x_m_s * 1000.0);
    case Ddi::kSetpointWindAlong: return to_int32(s.wind_y_m_s * 1000.0);
    case Ddi::kActualRevolutions: return to_int32(s.rpm_actual * kRevolutionsScale);
    case Ddi::kActualSpeed: return to_int32(s.ground_speed_m_s * 1000.0);
    case Ddi::kSectionControlState: return section_control_state_;
    case Ddi::kSetpointProduct: {
      if (!ecu_.has_predictor()) return std::nullopt;  // no table, no product to choose (not in the pool)
      const std::vector<std::string> names = ecu_.material_names();
      for (std::size_t k = 0; k < names.size(); ++k) {
        if (names[k] == s.material) return static_cast<std::int32_t>(k + 1);
      }
      return 0;  // none known yet
    }
    case Ddi::kProductNumber: return std::nullopt;  // properties of the pool, not process data
  }
  return std::nullopt;
}

std::uint8_t CanEcuProcessor::apply_set_value(const ProcessData& m) {
  Rejection rejection;
  switch (static_cast<Ddi>(m.ddi)) {
    case Ddi::kSetpointMassPerArea:
      rejection = ecu_.set_rate_setpoint(m.value / kMilligramPerSquareMetrePerKgPerHa);
      break;
    case Ddi::kSetpointWorkingWidth:
      rejection = ecu_.set_width_setpoint(m.value / 1000.0);
      break;
    case Ddi::kSetpointWorkState:
      if (m.value != 0 && m.value != 1) {
        ecu_.record_fault(Fault::kSetpointOutOfRange);
        return kPdackValueOutOfRange;
      }
      rejection = ecu_.set_work_state(m.value == 1);
      break;
    case Ddi::kSetpointCondensedWorkState1_16: {
      const EcuStatus s = ecu_.status();
      std::uint32_t mask = s.section_mask;
      const auto value = static_cast<std::uint32_t>(m.value);
      for (int i = 0; i < kMaxSections; ++i) {
        const std::uint32_t state = (value >> (2 * i)) & 3u;
        if (state == 3u) continue;  // not installed / leave unchanged
        if (i >= s.section_count && state == 0u) continue;  // "off" for a section that does not exist
        if (state == 2u || i >= s.section_count) {
          // "error" is not a set-point; switching on a section that does not exist is out of range.
          ecu_.record_fault(Fault::kSetpointOutOfRange);
          return kPdackValueOutOfRange;
        }
        mask = state == 1u ? (mask | (1u << i)) : (mask & ~(1u << i));
      }
      rejection = ecu_.set_section_mask(mask);
      break;
    }
    case Ddi::kSetpointRevolutions:
      rejection = ecu_.set_rpm_setpoint(m.value / kRevolutionsScale);
      break;
    case Ddi::kSectionControlState:
      // 0 manual, 1 automatic; 2 (error) and 3 (not installed) are states to report, not to set.
      if (m.value != 0 && m.value != 1) {
        ecu_.record_fault(Fault::kSetpointOutOfRange);
        return kPdackValueOutOfRange;
      }
      section_control_state_ = m.value;
      break;
    case Ddi::kSetpointBorderMode:
      if (m.value < 0 || m.value > 4) {
        ecu_.record_fault(Fault::kSetpointOutOfRange);
        return kPdackValueOutOfRange;
      }
      rejection = ecu_.set_border(m.value, ecu_.status().border_gap_m);
      break;
    case Ddi::kSetpointBorderGap: {
      const EcuStatus s = ecu_.status();
      rejection = ecu_.set_border(static_cast<std::int32_t>(s.border_mode), m.value / 1000.0);
      break;
    }
    case Ddi::kSetpointWindCompensation:
      if (m.value != 0 && m.value != 1) {
        ecu_.record_fault(Fault::kSetpointOutOfRange);
        return kPdackValueOutOfRange;
      }
      rejection = ecu_.set_wind_compensation(m.value == 1);
      break;
    case Ddi::kSetpointWindAcross:
      rejection = ecu_.set_wind(m.value / 1000.0, ecu_.status().wind_y_m_s);
      break;
    case Ddi::kSetpointWindAlong:
      rejection = ecu_.set_wind(ecu_.status().wind_x_m_s, m.value / 1000.0);
      break;
    case Ddi::kSetpointProduct: {
      // The k-th material of the launch table (the pool lists them); 0 or beyond the list is no product.
      const std::vector<std::string> names = ecu_.material_names();
      if (names.empty()) {
        ecu_.record_fault(Fault::kCanUnknownDdi);
        return kPdackDdiNotSupported;
      }
      if (m.value < 1 || static_cast<std::size_t>(m.value) > names.size()) {
        ecu_.record_fault(Fault::kUnknownMaterial);
        return kPdackValueOutOfRange;
      }
      rejection = ecu_.set_material(names[static_cast<std::size_t>(m.value - 1)]);
      break;
    }
    case Ddi::kActualMassPerArea:
    case Ddi::kActualWorkingWidth:
    case Ddi::kMaximumWorkingWidth:
    case Ddi::kActualWorkState:
    case Ddi::kActualCondensedWorkState1_16:
    case Ddi::kActualRevolutions:
    case Ddi::kActualSpeed:
      ecu_.record_fault(Fault::kCanNotSettable);
      return kPdackNotSettable;
    default:
      ecu_.record_fault(Fault::kCanUnknownDdi);
      return kPdackDdiNotSupported;
  }
  return rejection ? pdack_bits_for(*rejection) : std::uint8_t{kPdackNoError};
}

void CanEcuProcessor::partner_lost(Nanoseconds now) {
  ecu_.task_controller_gone();
  tc_client_.drop("the partner TC is gone: " + partner_.last_loss(), now);
}

void CanEcuProcessor::handle_acknowledgement(const can_frame& frame, std::uint8_t source, bool to_us) {
  // ISO 11783-3 §5.4.5 acknowledgement: byte 0 control, byte 4 the address acknowledged, bytes 5-7 the
  // PGN. A task controller that does not know a client's working set (it dropped us, or never heard our
  // working-set master message) answers our process data with a NACK (or access denied): the TC has
  // ended our session, whatever its status says.
  if (frame.len != 8) {
    ecu_.record_fault(Fault::kCanMalformedFrame);
    return;
  }
  const std::uint32_t pgn = std::uint32_t{frame.data[5]} | (std::uint32_t{frame.data[6]} << 8) |
                            (std::uint32_t{frame.data[7]} << 16);
  const auto control = static_cast<AckControl>(frame.data[0]);
  const bool refusal = control == AckControl::kNack || control == AckControl::kAccessDenied;
  const bool about_us = to_us || frame.data[4] == network_.address();
  if (!refusal || pgn != kProcessDataPgn || !about_us || !partner_.is_partner(source)) {
    ++counters_.frames_not_for_us;
    return;
  }
  ++counters_.tc_refusals;
  // Lost as a partner: metering stops exactly as when the TC falls silent (work state off,
  // task_controller_lost in DM1), and the client reconnects by itself after its retry delay. A storm of
  // NACKs ends one session: those that follow, while we wait to reconnect, change nothing more.
  ecu_.task_controller_gone();
  rejoin_pending_ = true;
  tc_client_.drop("the TC refused our process data (NACK): it does not know our working set", clock_.now());
}

void CanEcuProcessor::handle_tc_status(const can_frame& frame, std::uint8_t source) {
  ++counters_.task_controller_status;
  const Nanoseconds now = clock_.now();
  switch (partner_.on_tc_status(source, now)) {
    case isobus::TaskControllerPartner::Status::kPartner:
      // The TC status (every 2 s) is how the ECU core knows its TC is still there, and starts the
      // TC client's connection.
      ecu_.note_task_controller_alive();
      tc_client_.handle_message(source, std::span<const std::uint8_t>(frame.data, 8), now);
      flush_isobus(now);
      return;
    case isobus::TaskControllerPartner::Status::kOtherTc:
      ++counters_.other_task_controllers;  // a second TC on the bus: legal, not ours
      return;
    case isobus::TaskControllerPartner::Status::kNotATc:
      // A TC status from a node that never claimed an address as a task controller: it must neither
      // keep the ECU's supervision alive nor become the TC it connects to.
      ++counters_.not_from_partner;
      ecu_.record_fault(Fault::kCanNotFromTaskController);
      return;
  }
}

void CanEcuProcessor::handle_process_data(const can_frame& frame, std::uint8_t source, bool addressed_to_us) {
  // Without a standing address claim the ECU could not answer, and nobody could supervise it: process
  // data is not acted on (ISO 11783-5 §4.4.2).
  if (!network_.has_address()) {
    // Listening needs no address: the partner TC's status still says it is alive, so a hold-off or a move
    // longer than the 6 s supervision does not lose the partner the ECU is about to reconnect to.
    if ((frame.data[0] & 0x0F) == static_cast<std::uint8_t>(ProcessDataCommand::kTaskControllerStatus) &&
        partner_.is_partner(source)) {
      partner_.on_tc_status(source, clock_.now());
    }
    ++counters_.frames_not_for_us;
    return;
  }
  ++counters_.process_data_handled;
  const ProcessData m = decode_process_data(frame_bytes(frame));
  const auto command = static_cast<ProcessDataCommand>(m.command);
  if (command == ProcessDataCommand::kTaskControllerStatus) {
    handle_tc_status(frame, source);
    return;
  }
  if (command == ProcessDataCommand::kClientTask) {
    ++counters_.frames_not_for_us;  // another client's task message
    return;
  }
  if (command == ProcessDataCommand::kAcknowledge) {
    ++counters_.frames_not_for_us;  // PDACKs from others need no answer
    return;
  }
  // ISO 11783-10: an implement takes process data from its partner TC only. Anything else — values,
  // requests, measurement commands, connection messages from another node — is counted and ignored, with
  // no PDACK (the sender may not even hold an address).
  if (!partner_.is_partner(source)) {
    ++counters_.not_from_partner;
    ecu_.record_fault(Fault::kCanNotFromTaskController);
    return;
  }
  // After our address changed or the TC refused us, process data waits for the working set to be
  // connected again (ISO 11783-10: working-set master, pool, activation come first): values set now would
  // be those of a session the TC has ended.
  if (rejoining() && command != ProcessDataCommand::kTechnicalCapabilities &&
      command != ProcessDataCommand::kDeviceDescriptor) {
    ++counters_.before_reconnection;
    return;
  }
  // A negative acknowledge is only sent to a specific requester, never in answer to a broadcast.
  auto nack = [&](std::uint8_t bits) {
    if (!addressed_to_us) return;
    const ProcessDataBytes out = encode_pdack(m, bits);
    send(kProcessDataPgn, source, kProcessDataPriority, out.data());
  };
  if (command == ProcessDataCommand::kTechnicalCapabilities || command == ProcessDataCommand::kDeviceDescriptor) {
    // ISO 11783-10 connection messages go to the TC client.
    const Nanoseconds now = clock_.now();
    tc_client_.handle_message(source, std::span<const std::uint8_t>(frame.data, 8), now);
    flush_isobus(now);
    return;
  }
  const bool is_request = command == ProcessDataCommand::kRequestValue;
  const bool is_set = command == ProcessDataCommand::kValue || command == ProcessDataCommand::kSetValueAndAcknowledge;
  const bool is_measurement = m.command >= static_cast<std::uint8_t>(ProcessDataCommand::kMeasurementTimeInterval) &&
                              m.command <= static_cast<std::uint8_t>(ProcessDataCommand::kMeasurementChangeThreshold);
  if (!is_request && !is_set && !is_measurement) {
    ecu_.record_fault(Fault::kCanUnsupportedCommand);
    nack(kPdackCommandNotSupported);
    return;
  }
  // Each DDI lives on the element the device descriptor object pool gives it; element 0, the device
  // element, is accepted for every DDI as well, for tools that address the machine as a whole.
  // ISO 11783-10 PDACK: an element the pool does not have is "invalid element number"; an element it has
  // that does not carry the DDI is "DDI not supported by element".
  const auto element = element_for_ddi(m.ddi);
  if (m.element != 0 && (!element || m.element != *element)) {
    ecu_.record_fault(Fault::kCanUnknownDdi);
    nack(spreader_has_element(m.element, ecu_.parameters().section_count) ? kPdackDdiNotSupported
                                                                                  : kPdackInvalidElement);
    return;
  }
  if (is_measurement) {
    if (!actual_value(m.ddi, ecu_.status())) {
      ecu_.record_fault(Fault::kCanUnknownDdi);
      nack(kPdackDdiNotSupported);
      return;
    }
    // Intervals and the change threshold cannot be negative (0 switches the trigger off).
    const bool interval = command == ProcessDataCommand::kMeasurementTimeInterval ||
                          command == ProcessDataCommand::kMeasurementDistanceInterval ||
                          command == ProcessDataCommand::kMeasurementChangeThreshold;
    if (interval && m.value < 0) {
      ecu_.record_fault(Fault::kSetpointOutOfRange);
      nack(kPdackInvalidInterval);
      return;
    }
    if (!addressed_to_us || !triggers_.apply(source, m.command, m.element, m.ddi, m.value, clock_.now())) {
      // A trigger asked of everyone has no single receiver; a full table cannot take another.
      ecu_.record_fault(Fault::kCanUnsupportedCommand);
      nack(kPdackTriggerNotSupported);
    }
    return;
  }
  if (is_request) {
    const auto value = actual_value(m.ddi, ecu_.status());
    if (!value) {
      ecu_.record_fault(Fault::kCanUnknownDdi);
      nack(kPdackDdiNotSupported);
      return;
    }
    ProcessData answer = m;
    answer.command = static_cast<std::uint8_t>(ProcessDataCommand::kValue);
    answer.value = *value;
    const ProcessDataBytes out = encode_process_data(answer);
    // A request to the global address is answered to the global address (ISO 11783-10).
    send(kProcessDataPgn, addressed_to_us ? source : kGlobalAddress, kProcessDataPriority, out.data());
    return;
  }
  ecu_.note_task_controller_alive();  // a set-value is a sign of life of the task controller too
  const std::uint8_t errors = apply_set_value(m);
  if (errors != kPdackNoError) {
    nack(errors);
  } else if (command == ProcessDataCommand::kSetValueAndAcknowledge && addressed_to_us) {
    const ProcessDataBytes out = encode_pdack(m, kPdackNoError);
    send(kProcessDataPgn, source, kProcessDataPriority, out.data());
  }
}

CanPortIo::CanPortIo(CanFramePort& port, Ecu& ecu, const Clock& clock, const CanEcuSettings& settings,
                     CanFrameSink* recorder)
    : port_(port), recorder_(recorder), tx_(port, recorder), processor_(ecu, clock, tx_, settings) {}

void CanPortIo::pump(Nanoseconds max_wait) {
  processor_.service();  // a claim that has stood its 250 ms counts before the frames that follow it
  if (bus_closed_) {
    // Nothing will arrive any more: wait out the time like an idle bus instead of spinning on the hang-up.
    if (max_wait > Nanoseconds::zero()) std::this_thread::sleep_for(max_wait);
    return;
  }
  if (max_wait > Nanoseconds::zero() && !port_.wait_readable(max_wait)) return;
  processor_.service();
  can_frame frame{};
  for (;;) {
    const ReadOutcome outcome = port_.read(frame);
    if (outcome == ReadOutcome::kFrame) {
      if (recorder_ != nullptr) recorder_->send(frame);
      processor_.handle_frame(frame);
    } else if (outcome == ReadOutcome::kTruncated || outcome == ReadOutcome::kOversized) {
      processor_.handle_read_outcome(outcome);
    } else {
      if (outcome == ReadOutcome::kClosed) bus_closed_ = true;
      break;  // nothing pending, peer closed or error: the loop goes on
    }
  }
  processor_.service();
}

CandumpReplayIo::CandumpReplayIo(const CandumpLog& log, CanEcuProcessor& processor, const Clock& clock,
                                 CanFrameSink* recorder)
    : log_(log), processor_(processor), clock_(clock), recorder_(recorder), start_(clock.now()) {}

Nanoseconds CandumpReplayIo::span() const {
  if (log_.records.empty()) return Nanoseconds::zero();
  return log_.records.back().time - log_.records.front().time;
}

void CandumpReplayIo::pump(Nanoseconds max_wait) {
  if (finished()) return;
  const Nanoseconds first = log_.records.front().time;
  auto due = [&](std::size_t i) { return start_ + (log_.records[i].time - first); };
  if (max_wait > Nanoseconds::zero()) {
    // Real-time replay: sleep until the next record is due, but no longer than the loop allows.
    const Nanoseconds wait = std::min(max_wait, due(next_) - clock_.now());
    if (wait > Nanoseconds::zero()) std::this_thread::sleep_for(wait);
  }
  while (!finished() && due(next_) <= clock_.now()) {
    const can_frame& frame = log_.records[next_].frame;
    if (recorder_ != nullptr) recorder_->send(frame);
    processor_.handle_frame(frame);
    ++next_;
  }
}

}  // namespace spread::firmware::can
