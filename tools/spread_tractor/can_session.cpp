#include <algorithm>
#include <charconv>
#include <chrono>
#include <iostream>
#include <stdexcept>
#include <thread>

#include "firmware_sim/can/candump_log.hpp"
#include "firmware_sim/can/frame_description.hpp"
#include "firmware_sim/can/isobus_id.hpp"
#include "firmware_sim/can/process_data.hpp"
#include "firmware_sim/can/unix_can_bus.hpp"
#include "firmware_sim/can/speed_messages.hpp"
#include "firmware_sim/isobus/address_claim.hpp"
#include "firmware_sim/isobus/iso_name.hpp"
#include "firmware_sim/isobus/tc_messages.hpp"
#include "firmware_sim/isobus/tc_partner.hpp"
#include "tools/spread_tractor/sessions.hpp"

namespace spread::tractor {
namespace {

using namespace firmware::can;
using Clock = std::chrono::steady_clock;

bool parse_int(std::string_view text, long long& value) {
  int base = 10;
  if (text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) {
    text.remove_prefix(2);
    base = 16;
  }
  bool negative = false;
  if (!text.empty() && text.front() == '-') {
    negative = true;
    text.remove_prefix(1);
  }
  const auto r = std::from_chars(text.data(), text.data() + text.size(), value, base);
  if (r.ec != std::errc{} || r.ptr != text.data() + text.size()) return false;
  if (negative) value = -value;
  return true;
}

// The tractor acts as the ECU's task controller, and the ECU takes process data only from a node whose
// address claim carries a TC's NAME (ISO 11783-1: industry group 2, device class 0, function 130).
std::uint64_t task_controller_name() {
  firmware::isobus::IsoName name;
  name.self_configurable = true;
  name.device_class = firmware::isobus::kDeviceClassNonSpecific;
  name.function = firmware::isobus::kFunctionTaskController;
  name.identity_number = 0x81;
  return firmware::isobus::encode_name(name);
}

void send_address_claim(CanFramePort& port, std::uint8_t own) {
  const auto name = firmware::isobus::name_to_bytes(task_controller_name());
  port.send(make_frame(encode_id({6, firmware::isobus::kAddressClaimedPgn, kGlobalAddress, own}), name.data(), 8));
}

// A request for the address claim (to all or to us) is answered with our claim (ISO 11783-5 §4.4.3): the
// ECU asks once its own claim stands, to learn which NAME holds which address.
void answer_claim_request(CanFramePort& port, const can_frame& frame, std::uint8_t own) {
  const IsobusId id = decode_id(frame.can_id & CAN_EFF_MASK);
  if (id.pgn != 0xEA00 || frame.len < 3 || (id.destination != kGlobalAddress && id.destination != own)) return;
  const std::uint32_t pgn = frame.data[0] | (frame.data[1] << 8) | (std::uint32_t{frame.data[2]} << 16);
  if (pgn == firmware::isobus::kAddressClaimedPgn) send_address_claim(port, own);
}

void drain(CanFramePort& port, Clock::duration wait, std::uint8_t own_address) {
  const auto end = Clock::now() + wait;
  can_frame frame{};
  while (Clock::now() < end && !stop_requested()) {
    if (!port.wait_readable(std::chrono::duration_cast<std::chrono::nanoseconds>(end - Clock::now()))) continue;
    while (port.read(frame) == ReadOutcome::kFrame) {
      // Show what concerns us: frames addressed to us or broadcast by others.
      const IsobusId id = decode_id(frame.can_id & CAN_EFF_MASK);
      if (id.source == own_address) continue;
      answer_claim_request(port, frame, own_address);
      std::cout << "rx " << describe_frame(frame) << std::endl;
    }
  }
}

// Asks every node for its address claim (ISO 11783-5 §4.4.3: request for PGN 0xEE00) until the ECU
// answers, then waits out the 250 ms in which its claim can still be contested (§4.4.2), so that set-points
// are sent to an ECU that is on the bus and owns its address. The request is repeated because the ECU may
// join the bus after us.
bool wait_for_address_claim(CanFramePort& port, std::uint8_t own, std::uint8_t ecu, double timeout_s) {
  const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout_s));
  const std::uint8_t request[8] = {0x00, 0xEE, 0x00, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF};
  while (Clock::now() < end && !stop_requested()) {
    port.send(make_frame(encode_id({6, 0xEA00, kGlobalAddress, own}), request, 3));
    // The global request asks us too (ISO 11783-5 §4.4.3): our claim answers it, or a node that drops
    // whoever has not claimed soon after a global request would drop us.
    send_address_claim(port, own);
    const auto retry = std::min(end, Clock::now() + std::chrono::milliseconds(250));
    can_frame frame{};
    while (Clock::now() < retry) {
      if (!port.wait_readable(std::chrono::duration_cast<std::chrono::nanoseconds>(retry - Clock::now()))) continue;
      while (port.read(frame) == ReadOutcome::kFrame) {
        answer_claim_request(port, frame, own);
        const IsobusId id = decode_id(frame.can_id & CAN_EFF_MASK);
        if (id.pgn != 0xEE00 || id.source != ecu) continue;
        std::cout << "rx " << describe_frame(frame) << std::endl;
        drain(port, std::chrono::milliseconds(250), own);  // answering requests meanwhile
        return true;
      }
    }
  }
  return false;
}

}  // namespace

int run_can_session(const CanSessionOptions& o) {
  struct PlannedSet {
    std::uint16_t ddi;
    std::int32_t value;
  };
  std::vector<PlannedSet> sets;
  for (const auto& text : o.set_values) {
    const auto eq = text.find('=');
    long long ddi = 0;
    long long value = 0;
    if (eq == std::string::npos || !parse_int(std::string_view(text).substr(0, eq), ddi) ||
        !parse_int(std::string_view(text).substr(eq + 1), value) || ddi < 0 || ddi > 0xFFFF ||
        value < INT32_MIN || value > INT32_MAX) {
      std::cerr << "spread-tractor: error: --set '" << text << "' is not DDI=VALUE (integers, raw DDI units)\n";
      return kExitUsage;
    }
    sets.push_back({static_cast<std::uint16_t>(ddi), static_cast<std::int32_t>(value)});
  }
  CanFramePort port = open_can_bus(o.interface);
  const auto own = static_cast<std::uint8_t>(o.own_address);
  const auto ecu = static_cast<std::uint8_t>(o.ecu_address);
  // Our own claim first, as a task controller; it stands after 250 ms uncontested (§4.4.2). (This simple
  // TC does not defend its address: a contender is left to the TC role, spread-tractor tc.)
  send_address_claim(port, own);
  drain(port, std::chrono::milliseconds(250), own);
  if (o.wait_for_ecu_s > 0.0 && !wait_for_address_claim(port, own, ecu, o.wait_for_ecu_s)) {
    std::cerr << "spread-tractor: warning: no address claim from 0x" << std::hex << int{ecu} << std::dec
              << " within " << o.wait_for_ecu_s << " s; sending anyway\n";
  }
  // Our claim once more, then the TC status: the ECU learns our NAME from the claim even if it joined after
  // our first one, and the status that follows it on the bus makes us its partner TC (ISO 11783-10).
  send_address_claim(port, own);
  const auto first_status = firmware::isobus::encode_tc_status(true);
  port.send(
      make_frame(encode_id({kProcessDataPriority, kProcessDataPgn, kGlobalAddress, own}), first_status.data(), 8));
  auto send_pd = [&](ProcessDataCommand command, std::uint16_t ddi, std::int32_t value) {
    const ProcessDataBytes bytes = encode_process_data({static_cast<std::uint8_t>(command), 0, ddi, value});
    const can_frame frame = make_frame(encode_id({kProcessDataPriority, kProcessDataPgn, ecu, own}), bytes.data(), 8);
    std::cout << "tx " << describe_frame(frame) << std::endl;
    if (!port.send(frame)) std::cerr << "spread-tractor: warning: CAN write failed\n";
  };
  for (const auto& s : sets) {
    send_pd(o.acknowledge ? ProcessDataCommand::kSetValueAndAcknowledge : ProcessDataCommand::kValue, s.ddi, s.value);
  }
  for (const int ddi : o.requests) send_pd(ProcessDataCommand::kRequestValue, static_cast<std::uint16_t>(ddi), 0);

  const auto start = Clock::now();
  const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / o.send_hz));
  std::uint32_t distance_mm = 0;
  auto next_tc_status = start + std::chrono::seconds(2);
  while (!stop_requested() && Clock::now() - start < std::chrono::duration<double>(o.duration_s)) {
    // As the task controller: its status every 2 s (ISO 11783-10), which keeps the work state it set alive.
    if (Clock::now() >= next_tc_status) {
      const auto status = firmware::isobus::encode_tc_status(true);
      port.send(make_frame(encode_id({kProcessDataPriority, kProcessDataPgn, kGlobalAddress, own}), status.data(), 8));
      next_tc_status += std::chrono::seconds(2);
    }
    if (o.speed_m_s >= 0.0) {
      const auto bytes = encode_speed(o.speed_m_s, distance_mm, Direction::kForward);
      distance_mm += static_cast<std::uint32_t>(o.speed_m_s * 1000.0 / o.send_hz);
      port.send(make_frame(encode_id({3, kGroundBasedSpeedPgn, kGlobalAddress, own}), bytes.data(), 8));
    }
    drain(port, period, own);
  }
  return kExitOk;
}

int run_replay(const ReplayOptions& o) {
  const CandumpLog log = read_candump_file(o.log_path);
  for (const auto& e : log.errors) std::cerr << "spread-tractor: " << o.log_path << ": " << e << "\n";
  if (o.interface.empty()) {
    // Dry run: what the log says, decoded.
    for (const auto& r : log.records) {
      std::cout << format_candump_line(r.time, r.interface, r.frame) << "  " << describe_frame(r.frame) << "\n";
    }
    return log.errors.empty() ? kExitOk : kExitFailure;
  }
  CanFramePort port = open_can_bus(o.interface);
  const auto start = Clock::now();
  for (const auto& r : log.records) {
    if (stop_requested()) break;
    const auto due = start + std::chrono::duration_cast<Clock::duration>(r.time - log.records.front().time);
    std::this_thread::sleep_until(due);
    std::cout << "tx " << describe_frame(r.frame) << std::endl;
    if (!port.send(r.frame)) std::cerr << "spread-tractor: warning: CAN write failed (line " << r.line << ")\n";
    can_frame frame{};
    while (port.read(frame) == ReadOutcome::kFrame) std::cout << "rx " << describe_frame(frame) << std::endl;
  }
  drain(port, std::chrono::milliseconds(500), 0xFE);
  return log.errors.empty() ? kExitOk : kExitFailure;
}

}  // namespace spread::tractor
