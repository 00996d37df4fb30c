#pragma once
// The three ways spread-tractor talks to the ECU. Each returns the process exit code.
#include <string>
#include <vector>

namespace spread::tractor {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;
inline constexpr int kExitRejected = 3;  // the ECU rejected the command or never answered

struct LcmSessionOptions {
  std::string url;                 // LCM URL ("" = LCM's default)
  std::string channel_prefix;
  std::string command_channel;     // full channel names; "" = prefix + COMMAND / STATUS / HEARTBEAT
  std::string status_channel;
  std::string heartbeat_channel;
  bool send = false;               // send commands (else only monitor)
  std::string mode = "manual";     // manual | auto
  double rate_kg_ha = 0.0;
  double width_m = 0.0;
  double speed_m_s = 0.0;
  std::string material;
  double rpm = 0.0;
  int sections = 8;
  std::vector<int> sections_off;   // 1-based section numbers to close
  std::string work_state = "on";  // master switch asked for: on or off
  std::string border = "off";      // off | left | right | field-left | field-right
  double border_gap_m = 0.0;       // [m]
  bool wind_compensation = false;
  std::vector<double> wind_m_s;    // across (to the right), along (forward) [m/s]; empty: still air
  double send_hz = 5.0;            // command repetition [Hz]
  double duration_s = 0.0;         // 0: until Ctrl-C (or --once)
  bool once = false;               // send one command, print the status that reflects it, exit
  double once_timeout_s = 3.0;     // --once gives up after this long [s]
  double print_interval_s = 1.0;   // status lines at most this often [s]
  bool heartbeats = false;         // also print heartbeats
};

struct CanSessionOptions {
  std::string interface;
  int ecu_address = 0x80;
  int own_address = 0x81;
  std::vector<std::string> set_values;  // "DDI=VALUE" in the DDI's raw unit
  std::vector<int> requests;            // DDIs to request
  bool acknowledge = false;             // use set-value-and-acknowledge (0xA)
  double speed_m_s = -1.0;              // broadcast ground-based speed at send_hz when >= 0
  double send_hz = 10.0;
  double duration_s = 2.0;
  double wait_for_ecu_s = 3.0;          // wait this long for the ECU's address claim first (0: do not wait)
};

// The task-controller role (ISO 11783-10 server) on a bus: claims an address as a TC, takes the ECU's pool,
// activates it, sends the set-points below once activated, requests actual values and logs what the ECU
// reports. A set-point left at its "unset" value is not sent.
struct TcSessionOptions {
  std::string interface;
  int preferred_address = 0xF7;        // the address ISO 11783 reserves for the (first) task controller
  double speed_m_s = -1.0;             // broadcast ground-based speed every 100 ms when >= 0 [m/s]
  double rate_kg_ha = -1.0;            // DDI 6 when >= 0 [kg/ha]
  double width_m = -1.0;               // DDI 66 when >= 0 [m]
  double rpm = -1.0;                   // DDI 389 when >= 0 [r/min]
  std::string sections;                // DDI 290 pattern, section 1 first ("11110000"); "" = not sent
  // Section switches later in the session: "SECONDS:PATTERN", sent that long after the pool's activation
  // (a headland or a wedge reached); "" = none.
  std::vector<std::string> sections_later;
  // Further set-values on activation, "DDI=VALUE" (raw process-data value), sent before the work state:
  // e.g. the proprietary border and wind DDIs (docs/can-integration.md).
  std::vector<std::string> extra_set_points;
  std::string work_state;              // DDI 289: "on", "off" or "" (not sent)
  double request_interval_s = 1.0;     // actual values (7, 141, 161, 390) are requested this often [s]
  int measure_ms = 0;                  // > 0: ask the ECU to report them itself (measurement commands:
                                       // time interval, and on change for 141/161) instead of polling
  double duration_s = 10.0;            // run this long [s] (0: until Ctrl-C)
  double connect_timeout_s = 15.0;     // give up (exit 3) when no client activated a pool by then [s]
  bool print_ddop = false;             // print the received pool as a tree
  std::string log_path;                // as-applied CSV ("" = none)
  std::size_t max_pool_bytes = 65536;  // larger pools are refused
  bool quiet_values = false;           // do not print each reported value (the log still has them)
};

struct ReplayOptions {
  std::string log_path;
  std::string interface;  // empty: only print the decoded log
};

int run_lcm_session(const LcmSessionOptions& options);
int run_can_session(const CanSessionOptions& options);
int run_replay(const ReplayOptions& options);
int run_tc_session(const TcSessionOptions& options);

// Set by SIGINT/SIGTERM handlers in main.
bool stop_requested();

}  // namespace spread::tractor
