#include <algorithm>
#include <charconv>
#include <chrono>
#include <iostream>
#include <stdexcept>
#include <thread>

#include "isobus/address_claim.hpp"
#include "isobus/can/candump_log.hpp"
#include "isobus/can/unix_can_bus.hpp"
#include "isobus/frame_description.hpp"
#include "isobus/iso_name.hpp"
#include "isobus/isobus_id.hpp"
#include "isobus/network_link.hpp"
#include "isobus/process_data.hpp"
#include "isobus/speed_messages.hpp"
#include "isobus/tc_messages.hpp"
#include "isobus/tc_partner.hpp"
#include "tools/spread_tractor/sessions.hpp"

namespace spread::tractor {
namespace {

using namespace isobus;
using namespace isobus::can;
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
  isobus::IsoName name;
  name.self_configurable = true;
  name.device_class = isobus::kDeviceClassNonSpecific;
  name.function = isobus::kFunctionTaskController;
  name.identity_number = 0x81;
  return isobus::encode_name(name);
}

// Prints what reaches us for `wait`. With a network link (the session's address claim, ISO 11783-5), every
// frame goes through it first: requests for the claim are answered, a contender for our address is met by
// NAME (we move, being self-configurable), our NAME from another node is contended, and the claim's
// timers run. Without one (replay) frames are only printed.
void drain(CanFramePort& port, Clock::duration wait, NetworkLink* network) {
  const auto end = Clock::now() + wait;
  can_frame frame{};
  while (Clock::now() < end && !stop_requested()) {
    if (network != nullptr) network->service();
    const auto slice = std::min(end, Clock::now() + std::chrono::milliseconds(10));  // the claim's timers
    if (!port.wait_readable(std::chrono::duration_cast<std::chrono::nanoseconds>(slice - Clock::now()))) continue;
    while (port.read(frame) == ReadOutcome::kFrame) {
      // Show what concerns us: frames addressed to us or broadcast by others.
      const IsobusId id = decode_id(frame.can_id & CAN_EFF_MASK);
      if (network != nullptr) network->handle(id, frame);
      std::cout << "rx " << describe_frame(frame) << std::endl;
    }
  }
}

// Asks every node for its address claim (ISO 11783-5 §4.4.3: request for PGN 0xEE00, answered by our own
// claim too) until the ECU answers, then waits out the 250 ms in which its claim can still be contested
// (§4.4.2), so that set-points are sent to an ECU that is on the bus and owns its address. The request is
// repeated because the ECU may join the bus after us.
bool wait_for_address_claim(CanFramePort& port, NetworkLink& network, std::uint8_t ecu, double timeout_s) {
  const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout_s));
  while (Clock::now() < end && !stop_requested()) {
    network.service();
    if (network.has_address()) network.request_address_claims();
    const auto retry = std::min(end, Clock::now() + std::chrono::milliseconds(250));
    can_frame frame{};
    while (Clock::now() < retry) {
      network.service();
      const auto slice = std::min(retry, Clock::now() + std::chrono::milliseconds(10));
      if (!port.wait_readable(std::chrono::duration_cast<std::chrono::nanoseconds>(slice - Clock::now()))) continue;
      while (port.read(frame) == ReadOutcome::kFrame) {
        const IsobusId id = decode_id(frame.can_id & CAN_EFF_MASK);
        network.handle(id, frame);
        if (id.pgn != 0xEE00 || id.source != ecu) continue;
        std::cout << "rx " << describe_frame(frame) << std::endl;
        drain(port, std::chrono::milliseconds(250), &network);  // answering requests meanwhile
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
  const auto ecu = static_cast<std::uint8_t>(o.ecu_address);
  // Our own claim first, as a task controller (ISO 11783-5, the same network code as the ECU's): it stands
  // after 250 ms uncontested (§4.4.2); a lower NAME on our address moves us (the NAME is
  // self-configurable), and until a claim stands we send nothing else.
  SteadyClock clock;
  NetworkLink network(clock, port, task_controller_name(), static_cast<std::uint8_t>(o.own_address));
  network.start();
  drain(port, std::chrono::milliseconds(260), &network);
  if (o.wait_for_ecu_s > 0.0 && !wait_for_address_claim(port, network, ecu, o.wait_for_ecu_s)) {
    std::cerr << "spread-tractor: warning: no address claim from 0x" << std::hex << int{ecu} << std::dec
              << " within " << o.wait_for_ecu_s << " s; sending anyway\n";
  }
  if (!network.has_address()) {
    std::cerr << "spread-tractor: error: no address of our own (claim " << int{network.address()}
              << " contested and none free)\n";
    return kExitFailure;
  }
  // Every claim once more (ours answers the request), then the TC status: the ECU learns our NAME even if
  // it joined after our first claim, and the status that follows makes us its partner TC (ISO 11783-10).
  network.request_address_claims();
  const auto first_status = isobus::encode_tc_status(true);
  port.send(make_frame(encode_id({kProcessDataPriority, kProcessDataPgn, kGlobalAddress, network.address()}),
                       first_status.data(), 8));
  auto send_pd = [&](ProcessDataCommand command, std::uint16_t ddi, std::int32_t value) {
    if (!network.has_address()) return;  // ISO 11783-5 §4.4.2: nothing but claims without a standing claim
    const ProcessDataBytes bytes = encode_process_data({static_cast<std::uint8_t>(command), 0, ddi, value});
    const can_frame frame =
        make_frame(encode_id({kProcessDataPriority, kProcessDataPgn, ecu, network.address()}), bytes.data(), 8);
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
    const bool may_send = network.has_address();
    if (Clock::now() >= next_tc_status) {
      const auto status = isobus::encode_tc_status(true);
      if (may_send) {
        port.send(make_frame(encode_id({kProcessDataPriority, kProcessDataPgn, kGlobalAddress, network.address()}),
                             status.data(), 8));
      }
      next_tc_status += std::chrono::seconds(2);
    }
    if (o.speed_m_s >= 0.0 && may_send) {
      const auto bytes = encode_speed(o.speed_m_s, distance_mm, Direction::kForward);
      distance_mm += static_cast<std::uint32_t>(o.speed_m_s * 1000.0 / o.send_hz);
      port.send(make_frame(encode_id({3, kGroundBasedSpeedPgn, kGlobalAddress, network.address()}), bytes.data(), 8));
    }
    drain(port, period, &network);
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
  drain(port, std::chrono::milliseconds(500), nullptr);
  return log.errors.empty() ? kExitOk : kExitFailure;
}

}  // namespace spread::tractor
