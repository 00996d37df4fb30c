// spread-tractor tc: a task controller on a bus (ISO 11783-10 server role) with the tractor's speed
// broadcast beside it. The protocol lives in isobus/tc_server.*; this file is the I/O loop:
// address claim, frames in and out, set-points on activation, periodic value requests, output and the log.
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>
#include <string>

#include "isobus/can/unix_can_bus.hpp"
#include "isobus/ddi.hpp"
#include "isobus/frame_description.hpp"
#include "isobus/iso_name.hpp"
#include "isobus/isobus_id.hpp"
#include "isobus/network_link.hpp"
#include "isobus/speed_messages.hpp"
#include "isobus/tc_server.hpp"
#include "libspread/core/clock.hpp"
#include "tools/spread_tractor/as_applied_csv.hpp"
#include "tools/spread_tractor/ddop_tree.hpp"
#include "tools/spread_tractor/section_pattern.hpp"
#include "tools/spread_tractor/sessions.hpp"

namespace spread::tractor {
namespace {

using namespace isobus;
using namespace isobus::can;
namespace iso = isobus;

// ISO 11783-1 NAME function table: industry group 2 (agriculture), device class 0 (non-specific system),
// function 130 = task controller. Self-configurable, so a second TC on the bus does not silence this one.
std::uint64_t task_controller_name() {
  iso::IsoName name;
  name.self_configurable = true;
  name.industry_group = iso::kIndustryGroupAgriculture;
  name.device_class = 0;
  name.function = 130;
  name.identity_number = 0x7C;
  return iso::encode_name(name);
}

// Speed broadcasts every 100 ms (ISO 11783-7); the ECU drops a source after 300 ms.
constexpr Nanoseconds kSpeedInterval = std::chrono::milliseconds(100);
constexpr std::uint8_t kSpeedPriority = 3;

std::int32_t rounded(double v) {
  const double r = std::round(v);
  if (r > std::numeric_limits<std::int32_t>::max()) return std::numeric_limits<std::int32_t>::max();
  if (r < std::numeric_limits<std::int32_t>::min()) return std::numeric_limits<std::int32_t>::min();
  return static_cast<std::int32_t>(r);
}

// Actual rate, work state, section states and disc speed: what an as-applied map needs.
constexpr std::array<std::uint16_t, 4> kRequestedDdis{7, 141, 161, 390};

struct SetPoint {
  std::uint16_t ddi;
  std::int32_t value;
};

}  // namespace

int run_tc_session(const TcSessionOptions& o) {
  std::vector<SetPoint> set_points;
  if (o.rate_kg_ha >= 0.0) set_points.push_back({6, rounded(o.rate_kg_ha * 100.0)});        // mg/m²
  if (o.width_m >= 0.0) set_points.push_back({66, rounded(o.width_m * 1000.0)});            // mm
  if (o.rpm >= 0.0) set_points.push_back({389, rounded(o.rpm * kRevolutionsScale)});        // r/min × 1e-4
  if (!o.sections.empty()) {
    const auto value = condensed_work_state_from_pattern(o.sections);
    if (!value) {
      std::cerr << "spread-tractor: error: --sections '" << o.sections
                << "' is not a pattern of 1 to 16 characters 0/1 (section 1 first)\n";
      return kExitUsage;
    }
    set_points.push_back({290, *value});
  }
  for (const std::string& text : o.extra_set_points) {
    const std::size_t equals = text.find('=');
    char* ddi_end = nullptr;
    char* value_end = nullptr;
    const long ddi = equals == std::string::npos ? -1 : std::strtol(text.c_str(), &ddi_end, 10);
    const long long value = equals == std::string::npos ? 0 : std::strtoll(text.c_str() + equals + 1, &value_end, 10);
    if (equals == std::string::npos || ddi_end != text.c_str() + equals || ddi < 0 || ddi > 0xFFFF ||
        value_end == text.c_str() + equals + 1 || *value_end != '\0' || value < std::numeric_limits<std::int32_t>::min() ||
        value > std::numeric_limits<std::int32_t>::max()) {
      std::cerr << "spread-tractor: error: --set '" << text << "' is not DDI=VALUE (DDI 0..65535, a 32-bit integer)\n";
      return kExitUsage;
    }
    set_points.push_back({static_cast<std::uint16_t>(ddi), static_cast<std::int32_t>(value)});
  }
  struct LaterSections {
    Nanoseconds after;
    std::int32_t value;
    std::string pattern;
  };
  std::vector<LaterSections> later;
  for (const std::string& text : o.sections_later) {
    const std::size_t colon = text.find(':');
    char* end = nullptr;
    const double seconds = colon == std::string::npos ? -1.0 : std::strtod(text.c_str(), &end);
    const auto value = colon == std::string::npos ? std::nullopt : condensed_work_state_from_pattern(text.substr(colon + 1));
    if (colon == std::string::npos || end != text.c_str() + colon || !(seconds >= 0.0) || !std::isfinite(seconds) || !value) {
      std::cerr << "spread-tractor: error: --sections-later '" << text
                << "' is not SECONDS:PATTERN (seconds >= 0 after activation, a pattern of 1 to 16 characters 0/1)\n";
      return kExitUsage;
    }
    later.push_back({from_seconds(seconds), *value, text.substr(colon + 1)});
  }
  std::size_t next_later = 0;
  Nanoseconds activated_at{};
  // The master work state last: the ECU opens with the other set-points already in place.
  if (!o.work_state.empty()) set_points.push_back({289, o.work_state == "on" ? 1 : 0});

  std::ofstream log;
  if (!o.log_path.empty()) {
    log.open(o.log_path);
    if (!log) {
      std::cerr << "spread-tractor: error: cannot write the as-applied log " << o.log_path << "\n";
      return kExitFailure;
    }
    write_as_applied_header(log);
  }

  CanFramePort port = open_can_bus(o.interface);
  SteadyClock clock;
  NetworkLink network(clock, port, task_controller_name(), static_cast<std::uint8_t>(o.preferred_address));
  iso::TcServerConfig config;
  config.max_pool_bytes = o.max_pool_bytes;
  iso::TcServer tc(config);

  const Nanoseconds start = clock.now();
  auto since_start = [&](Nanoseconds t) { return to_seconds(t - start); };
  const Nanoseconds end = start + from_seconds(o.duration_s);
  const Nanoseconds connect_deadline = start + from_seconds(o.connect_timeout_s);
  const Nanoseconds request_interval = from_seconds(o.request_interval_s);
  Nanoseconds next_speed = start;
  Nanoseconds next_request = start;
  std::uint32_t distance_mm = 0;
  std::vector<std::uint16_t> polled;  // DDIs requested every request interval (not measured by the ECU)
  bool was_active = false;
  bool ever_active = false;
  std::uint64_t send_failures = 0;
  std::uint64_t malformed_reads = 0;

  auto send = [&](const iso::TransportFrame& f) {
    const can_frame frame = make_frame(encode_id({f.priority, f.pgn, f.destination, f.source}), f.data.data(), 8);
    if (!port.send(frame)) ++send_failures;
  };
  auto report = [&](const char* what) {
    std::cerr << "spread-tractor: warning: " << what << "\n";
  };

  std::cout << "tc: claiming an address as task controller (" << iso::describe_name(network.claim().name())
            << ")" << std::endl;
  network.start();
  while (!stop_requested()) {
    const Nanoseconds now = clock.now();
    if (o.duration_s > 0.0 && now >= end) break;
    if (!ever_active && now >= connect_deadline) break;

    // Network management first: the TC may only speak with a standing claim (ISO 11783-5 §4.4.2).
    network.service();
    if (network.has_address()) {
      if (!tc.started()) {
        tc.start(network.address(), now);
        std::printf("tc: address 0x%02X claimed at %.3f s; TC status every 2 s\n", network.address(),
                    since_start(now));
        std::fflush(stdout);
      } else if (tc.address() != network.address()) {
        tc.set_address(network.address());
      }
    }

    if (network.has_address() && o.speed_m_s >= 0.0 && now >= next_speed) {
      const auto bytes = encode_speed(o.speed_m_s, distance_mm, Direction::kForward);
      distance_mm += static_cast<std::uint32_t>(std::lround(o.speed_m_s * 1000.0 * to_seconds(kSpeedInterval)));
      if (!port.send(make_frame(encode_id({kSpeedPriority, kGroundBasedSpeedPgn, kGlobalAddress, network.address()}),
                                bytes.data(), 8))) {
        ++send_failures;
      }
      next_speed += kSpeedInterval;
      if (next_speed <= now) next_speed = now + kSpeedInterval;
    }

    tc.update(now);
    for (const std::string& e : tc.take_events()) {
      std::printf("tc: %8.3f s  %s\n", since_start(now), e.c_str());
      std::fflush(stdout);
    }
    const bool active = tc.active();
    if (active && !was_active) {
      // Set-points go out on every activation: a client that reconnected starts from its defaults.
      ever_active = true;
      activated_at = now;
      next_later = 0;
      std::printf("tc: client 0x%02X active at %.3f s, %zu section(s)\n", *tc.client_address(), since_start(now),
                  tc.section_elements().size());
      std::fflush(stdout);
      if (o.print_ddop && tc.pool()) std::cout << describe_ddop_tree(*tc.pool()) << std::flush;
      for (const SetPoint& s : set_points) {
        const std::string error = tc.set_value(s.ddi, s.value);
        if (!error.empty()) {
          std::cout << "tc: set DDI " << s.ddi << " not sent: " << error << std::endl;
        } else {
          std::cout << "tc: set DDI " << s.ddi << " " << ddi_name(s.ddi) << " = " << format_ddi_value(s.ddi, s.value)
                    << " on element " << tc.elements_for_ddi(s.ddi).front() << std::endl;
        }
      }
      polled.clear();
      for (const std::uint16_t ddi : kRequestedDdis) {
        if (tc.elements_for_ddi(ddi).empty()) continue;
        if (o.measure_ms > 0) {
          // The ECU reports by itself: every measure_ms, and section and work-state switches at once.
          std::string error = tc.measure(ddi, iso::MeasurementCommand::kTimeInterval, o.measure_ms);
          if (error.empty() && (ddi == 141 || ddi == 161)) {
            error = tc.measure(ddi, iso::MeasurementCommand::kChangeThreshold, 1);
          }
          if (error.empty()) continue;
          std::cout << "tc: DDI " << ddi << " polled instead: " << error << std::endl;
        }
        polled.push_back(ddi);
      }
      next_request = now + request_interval;
    }
    was_active = active;
    while (active && next_later < later.size() && now - activated_at >= later[next_later].after) {
      const LaterSections& l = later[next_later++];
      const std::string error = tc.set_value(290, l.value);
      std::cout << "tc: " << std::fixed;
      std::cout.precision(3);
      std::cout << since_start(now) << " s  set DDI 290 " << ddi_name(290) << " = " << format_ddi_value(290, l.value)
                << (error.empty() ? "" : " not sent: " + error) << std::endl;
      std::cout.unsetf(std::ios::floatfield);
    }
    if (active && now >= next_request) {
      for (const std::uint16_t ddi : polled) (void)tc.request_value(ddi);
      next_request += request_interval;
      if (next_request <= now) next_request = now + request_interval;
    }
    for (const iso::TransportFrame& f : tc.take_frames()) {
      if (network.has_address()) send(f);
    }
    for (const iso::AsAppliedRecord& r : tc.take_as_applied()) {
      if (!o.quiet_values) {
        std::printf("tc: %8.3f s  element %u DDI %u %s = %s\n", since_start(r.time), unsigned{r.element},
                    unsigned{r.ddi}, ddi_name(r.ddi).c_str(), format_ddi_value(r.ddi, r.value).c_str());
        std::fflush(stdout);
      }
      if (log) write_as_applied_line(log, r, since_start(r.time));
    }

    // Wait for frames until the next 10 ms tick: TP answers must go out well inside Tr = 200 ms.
    if (!port.wait_readable(std::chrono::milliseconds(10))) continue;
    can_frame frame{};
    for (;;) {
      const ReadOutcome outcome = port.read(frame);
      if (outcome == ReadOutcome::kNothing) break;
      if (outcome == ReadOutcome::kClosed) {
        report("the bus closed");
        return kExitFailure;
      }
      if (outcome != ReadOutcome::kFrame) {
        ++malformed_reads;
        continue;
      }
      if ((frame.can_id & CAN_EFF_FLAG) == 0 || (frame.can_id & (CAN_RTR_FLAG | CAN_ERR_FLAG)) != 0) continue;
      const IsobusId id = decode_id(frame.can_id & CAN_EFF_MASK);
      if (id.pgn == iso::kAddressClaimedPgn && frame.len == 8) {
        tc.on_address_claimed(id.source, iso::name_from_bytes(frame.data));
      }
      const auto verdict = network.handle(id, frame);
      if (verdict == NetworkLink::Verdict::kMalformed) ++malformed_reads;
      if (verdict != NetworkLink::Verdict::kNotNetwork) continue;
      const std::size_t length = frame.len > 8 ? 8 : frame.len;
      tc.handle_frame(id.pgn, id.source, id.destination, std::span<const std::uint8_t>(frame.data, length), clock.now());
    }
  }

  const auto& c = tc.counters();
  char client[8] = "none";
  if (tc.client_address()) std::snprintf(client, sizeof client, "0x%02X", *tc.client_address());
  std::cout << "tc: summary: client " << client << " " << iso::tc_connection_state_name(tc.state())
            << ", pools accepted " << c.pools_accepted << " refused " << c.pools_refused << ", values logged "
            << c.values_logged << ", PDACK errors " << c.pdack_errors << ", client timeouts " << c.client_timeouts
            << ", malformed frames " << c.malformed_frames + malformed_reads << ", send failures " << send_failures
            << std::endl;
  if (!ever_active) {
    std::cerr << "spread-tractor: error: no client activated a pool within "
              << (o.duration_s > 0.0 && o.duration_s < o.connect_timeout_s ? o.duration_s : o.connect_timeout_s)
              << " s\n";
    return kExitRejected;
  }
  return kExitOk;
}

}  // namespace spread::tractor
