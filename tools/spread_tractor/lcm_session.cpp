#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <stdexcept>

#include "lcm_link/lcm_tractor_link.hpp"
#include "tools/spread_tractor/sessions.hpp"
#include "tools/spread_tractor/status_line.hpp"

namespace spread::tractor {
namespace {

using Clock = std::chrono::steady_clock;

spread::command_t build_command(const LcmSessionOptions& o, std::int64_t sequence) {
  spread::command_t c{};
  c.timestamp_us =
      std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
  c.sequence = sequence;
  c.mode = o.mode == "auto" ? spread::command_t::MODE_AUTOMATIC : spread::command_t::MODE_MANUAL;
  c.rate_setpoint_kg_ha = o.rate_kg_ha;
  c.width_setpoint_m = o.width_m;
  c.ground_speed_m_s = o.speed_m_s;
  c.material = o.material;
  c.rpm_setpoint = o.rpm;
  c.work_state = o.work_state == "on";
  // Out-of-range counts are passed on as they are: the ECU is the one that judges and counts them.
  c.num_sections = static_cast<std::int8_t>(o.sections);
  c.section_on.assign(o.sections > 0 ? static_cast<std::size_t>(o.sections) : 0u, true);
  for (const int off : o.sections_off) {
    if (off >= 1 && off <= o.sections) c.section_on[static_cast<std::size_t>(off - 1)] = false;
  }
  c.border_mode = o.border == "left"          ? spread::command_t::BORDER_LEFT
                  : o.border == "right"       ? spread::command_t::BORDER_RIGHT
                  : o.border == "field-left"  ? spread::command_t::FIELD_EDGE_LEFT
                  : o.border == "field-right" ? spread::command_t::FIELD_EDGE_RIGHT
                                              : spread::command_t::BORDER_OFF;
  c.border_gap_m = o.border_gap_m;
  c.wind_compensation = o.wind_compensation;
  c.wind_m_s[0] = o.wind_m_s.size() > 0 ? o.wind_m_s[0] : 0.0;
  c.wind_m_s[1] = o.wind_m_s.size() > 1 ? o.wind_m_s[1] : 0.0;
  return c;
}

}  // namespace

int run_lcm_session(const LcmSessionOptions& o) {
  lcm::LCM lcm(o.url);
  if (!lcm.good()) {
    std::cerr << "spread-tractor: error: cannot create an LCM instance for URL '" << o.url << "'\n";
    return kExitFailure;
  }
  const lcm_link::LcmChannels channels =
      lcm_link::channels_from(o.channel_prefix, o.command_channel, o.status_channel, o.heartbeat_channel);
  lcm_link::LcmTractorLink link(lcm, channels);
  Clock::time_point last_print{};
  bool printed_any = false;
  link.on_status = [&](const spread::status_t& s) {
    const auto now = Clock::now();
    if (o.once) return;
    if (printed_any && now - last_print < std::chrono::duration<double>(o.print_interval_s)) return;
    printed_any = true;
    last_print = now;
    std::cout << format_status(s) << std::endl;
  };
  if (o.heartbeats) link.on_heartbeat = [](const spread::heartbeat_t& h) { std::cout << format_heartbeat(h) << std::endl; };

  // Sequence numbers start from the wall clock so that a restarted tractor is never taken as stale.
  std::int64_t sequence =
      std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch()).count();

  if (o.once) {
    // Resend until the ECU's status shows one of our sequence numbers, or give up. Each resend is the
    // next number: the ECU refuses a repeat, and believes a jump (a new sender) only when the next
    // command continues from it.
    const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(o.once_timeout_s));
    const std::int64_t first = sequence;
    auto ours = [&] {
      return link.latest_status() && link.latest_status()->last_command_sequence >= first &&
             link.latest_status()->last_command_sequence <= sequence;
    };
    for (bool sent = false; Clock::now() < end && !stop_requested(); sent = true) {
      if (sent) ++sequence;
      if (!link.send(build_command(o, sequence))) std::cerr << "spread-tractor: warning: LCM publish failed\n";
      if (link.wait_for(ours, std::chrono::milliseconds(300))) {
        std::cout << format_status(*link.latest_status()) << std::endl;
        return kExitOk;
      }
    }
    if (link.latest_status()) {
      std::cout << format_status(*link.latest_status()) << std::endl;
      std::cerr << "spread-tractor: the ECU did not accept the command (faults: "
                << format_fault_codes(link.latest_status()->fault_codes) << ")\n";
    } else {
      std::cerr << "spread-tractor: no status from the ECU on " << channels.status << " within " << o.once_timeout_s << " s\n";
    }
    return kExitRejected;
  }

  const auto start = Clock::now();
  const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / o.send_hz));
  auto next_send = start;
  while (!stop_requested()) {
    const auto now = Clock::now();
    if (o.duration_s > 0.0 && now - start >= std::chrono::duration<double>(o.duration_s)) break;
    if (o.send && now >= next_send) {
      link.send(build_command(o, ++sequence));
      next_send += period;
    }
    link.handle(std::chrono::milliseconds(20));
  }
  if (link.undecodable_received() > 0) {
    std::cerr << "spread-tractor: " << link.undecodable_received() << " undecodable messages received\n";
  }
  return link.statuses_received() > 0 ? kExitOk : kExitRejected;
}

}  // namespace spread::tractor
