// spread-tractor: the tractor side of firmware_sim. Sends set-points and prints the ECU's status over
// LCM or over an ISOBUS (SocketCAN or a spread-canbus socket), acts as the ISO 11783-10 task controller,
// or replays a candump log. Usage examples: docs/can-integration.md
// and docs/messages.md.
#include <CLI/CLI.hpp>

#include <atomic>
#include <csignal>
#include <iostream>

#include "lcm_link/lcm_channels.hpp"
#include "tools/spread_tractor/sessions.hpp"

namespace {
std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) { g_stop.store(true); }
}  // namespace

bool spread::tractor::stop_requested() { return g_stop.load(); }

int main(int argc, char** argv) {
  using namespace spread::tractor;
  CLI::App app{"spread-tractor: talk to the firmware_sim spreader ECU over LCM or CAN"};
  app.require_subcommand(1);

  LcmSessionOptions lcm_options;
  lcm_options.channel_prefix = std::string(spread::lcm_link::kDefaultChannelPrefix);
  auto* lcm = app.add_subcommand("lcm", "send command_t set-points and print status_t (omit set-points to monitor)");
  lcm->add_option("--lcm-url", lcm_options.url, "LCM URL (default: LCM's default udpm)");
  lcm->add_option("--channel-prefix", lcm_options.channel_prefix, "channel prefix")->capture_default_str();
  lcm->add_option("--command-channel", lcm_options.command_channel, "full name of the command_t channel (overrides the prefix)");
  lcm->add_option("--status-channel", lcm_options.status_channel, "full name of the status_t channel (overrides the prefix)");
  lcm->add_option("--heartbeat-channel", lcm_options.heartbeat_channel,
                  "full name of the heartbeat_t channel (overrides the prefix)");
  lcm->add_option("--mode", lcm_options.mode, "manual or auto")->check(CLI::IsMember({"manual", "auto"}))->capture_default_str();
  auto* rate = lcm->add_option("--rate", lcm_options.rate_kg_ha, "application rate set-point [kg/ha]");
  auto* width = lcm->add_option("--width", lcm_options.width_m, "working width set-point [m]");
  auto* speed = lcm->add_option("--speed", lcm_options.speed_m_s, "ground speed [m/s]");
  auto* material = lcm->add_option("--material", lcm_options.material, "material name as in the tables");
  auto* rpm = lcm->add_option("--rpm", lcm_options.rpm, "disc speed set-point, manual mode [r/min]");
  auto* sections = lcm->add_option("--sections", lcm_options.sections, "sections in use (1..16)")->capture_default_str();
  auto* off = lcm->add_option("--off", lcm_options.sections_off, "sections to close, 1-based (e.g. --off 7 8)");
  auto* border = lcm->add_option("--border", lcm_options.border,
                                 "border spreading on one side: off, left, right (a road, water: nothing over the "
                                 "edge line), field-left, field-right (another field: full rate to it)")
                     ->check(CLI::IsMember({"off", "left", "right", "field-left", "field-right"}));
  auto* gap = lcm->add_option("--border-gap", lcm_options.border_gap_m,
                              "the edge line this far inside the bout's edge [m] (water: 1 with a border device, 3 without)");
  auto* compensate = lcm->add_flag("--wind-compensation", lcm_options.wind_compensation,
                                   "set each disc apart for the measured wind (the ECU needs its tables)");
  auto* wind = lcm->add_option("--wind", lcm_options.wind_m_s, "measured wind: across (to the right), along (forward) [m/s]")
                   ->expected(2)
                   ->delimiter(',');
  auto* work = lcm->add_option("--work-state", lcm_options.work_state,
                               "master switch: on or off (the ECU applies a change, not a repeat)")
                   ->check(CLI::IsMember({"on", "off"}))
                   ->capture_default_str();
  lcm->add_option("--hz", lcm_options.send_hz, "command repetition rate [Hz]")->check(CLI::Range(0.1, 100.0))->capture_default_str();
  lcm->add_option("--duration", lcm_options.duration_s, "run this long [s] (0: until Ctrl-C)")->check(CLI::NonNegativeNumber);
  lcm->add_flag("--once", lcm_options.once, "send one command, print the status that shows it accepted, exit (3: rejected)");
  lcm->add_option("--timeout", lcm_options.once_timeout_s, "--once gives up after this long [s]")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  lcm->add_option("--print-interval", lcm_options.print_interval_s, "print a status line at most this often [s]")
      ->capture_default_str();
  lcm->add_flag("--heartbeats", lcm_options.heartbeats, "print heartbeats too");

  CanSessionOptions can_options;
  auto* can = app.add_subcommand("can", "send ISOBUS process data / speed to the ECU and print its answers");
  can->add_option("--iface", can_options.interface, "SocketCAN interface (can0) or spread-canbus socket (unix:PATH)")->required();
  can->add_option("--ecu", can_options.ecu_address, "ECU source address")->check(CLI::Range(0, 253))->capture_default_str();
  can->add_option("--address", can_options.own_address, "our source address")->check(CLI::Range(0, 253))->capture_default_str();
  can->add_option("--set", can_options.set_values, "set-value DDI=VALUE in raw DDI units (e.g. 6=20000 for 200 kg/ha)");
  can->add_option("--request", can_options.requests, "request the value of these DDIs (e.g. 390 67)");
  can->add_flag("--ack", can_options.acknowledge, "send set-values with acknowledge (command 0xA)");
  can->add_option("--speed", can_options.speed_m_s, "broadcast ground-based speed (PGN 0xFE49) [m/s]");
  can->add_option("--hz", can_options.send_hz, "speed broadcast rate [Hz]")->check(CLI::Range(0.1, 100.0))->capture_default_str();
  can->add_option("--duration", can_options.duration_s, "listen this long for answers [s]")->capture_default_str();
  can->add_option("--wait-for-ecu", can_options.wait_for_ecu_s,
                  "first wait this long for the ECU's address claim [s] (0: send at once)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();

  ReplayOptions replay_options;
  auto* replay = app.add_subcommand("replay", "print a candump log decoded, or send it onto a CAN interface in real time");
  replay->add_option("log", replay_options.log_path, "candump log file")->required()->check(CLI::ExistingFile);
  replay->add_option("--iface", replay_options.interface, "send onto this SocketCAN interface or unix:PATH bus (default: only print)");

  TcSessionOptions tc_options;
  auto* tc = app.add_subcommand("tc", "be the ISO 11783-10 task controller: take the ECU's pool, activate it, send "
                                      "set-points, request and log actual values");
  tc->add_option("--iface", tc_options.interface, "SocketCAN interface (can0) or spread-canbus socket (unix:PATH)")
      ->required();
  tc->add_option("--address", tc_options.preferred_address, "preferred source address of the TC")
      ->check(CLI::Range(0, 253))
      ->capture_default_str();
  tc->add_option("--speed", tc_options.speed_m_s, "broadcast ground-based speed (PGN 0xFE49) every 100 ms [m/s]")
      ->check(CLI::NonNegativeNumber);
  tc->add_option("--rate", tc_options.rate_kg_ha, "application rate set-point, DDI 6 [kg/ha]")->check(CLI::NonNegativeNumber);
  tc->add_option("--width", tc_options.width_m, "working width set-point, DDI 66 [m]")->check(CLI::NonNegativeNumber);
  tc->add_option("--rpm", tc_options.rpm, "disc speed set-point, DDI 389 [r/min]")->check(CLI::NonNegativeNumber);
  tc->add_option("--sections", tc_options.sections,
                 "section pattern, section 1 first, 1 on 0 off (e.g. 11110000): condensed work state DDI 290");
  tc->add_option("--set", tc_options.extra_set_points,
                 "DDI=VALUE: one more set-value on activation, raw (repeatable; e.g. --set 57344=1 for a left border)");
  tc->add_option("--sections-later", tc_options.sections_later,
                 "SECONDS:PATTERN: switch the sections to PATTERN (DDI 290) that long after activation (repeatable)");
  tc->add_option("--work-state", tc_options.work_state, "master work state set-point, DDI 289")
      ->check(CLI::IsMember({"on", "off"}));
  tc->add_option("--request-interval", tc_options.request_interval_s,
                 "request DDIs 7, 141, 161 and 390 this often [s]")
      ->check(CLI::Range(0.05, 3600.0))
      ->capture_default_str();
  tc->add_option("--measure-ms", tc_options.measure_ms,
                 "instead of polling, ask the ECU to report DDIs 7, 141, 161, 390 every N ms and 141/161 on "
                 "every change (ISO 11783-10 measurement commands); 0 = poll")
      ->check(CLI::Range(0, 60000))
      ->capture_default_str();
  tc->add_option("--duration", tc_options.duration_s, "run this long [s] (0: until Ctrl-C)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  tc->add_option("--connect-timeout", tc_options.connect_timeout_s,
                 "exit 3 when no client has activated a pool by then [s]")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  tc->add_flag("--print-ddop", tc_options.print_ddop, "print the client's device descriptor object pool as a tree");
  tc->add_option("--log", tc_options.log_path, "write the as-applied log (every value the client reports) as CSV");
  tc->add_option("--max-pool-bytes", tc_options.max_pool_bytes, "refuse pools larger than this [bytes]")
      ->check(CLI::Range(std::size_t{1}, std::size_t{1} << 24))
      ->capture_default_str();
  tc->add_flag("--quiet-values", tc_options.quiet_values, "do not print each reported value (the log keeps them)");

  CLI11_PARSE(app, argc, argv);
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  try {
    if (lcm->parsed()) {
      lcm_options.send = rate->count() + width->count() + speed->count() + material->count() + rpm->count() +
                             sections->count() + off->count() + work->count() + border->count() + gap->count() +
                                     compensate->count() + wind->count() >
                                 0 ||
                         lcm_options.mode != "manual";
      if (lcm_options.once && !lcm_options.send) {
        std::cerr << "spread-tractor: error: --once needs set-points to send (e.g. --rate 200 --width 24)\n";
        return kExitUsage;
      }
      return run_lcm_session(lcm_options);
    }
    if (can->parsed()) return run_can_session(can_options);
    if (replay->parsed()) return run_replay(replay_options);
    if (tc->parsed()) return run_tc_session(tc_options);
  } catch (const std::exception& e) {
    std::cerr << "spread-tractor: error: " << e.what() << "\n";
    return kExitFailure;
  }
  return kExitUsage;
}
