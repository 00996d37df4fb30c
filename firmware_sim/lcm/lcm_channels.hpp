#pragma once
// LCM channel names. All three share a configurable prefix so that several simulated machines (or
// test cases) can share one LCM network: prefix "SPREAD_" gives SPREAD_COMMAND, SPREAD_STATUS,
// SPREAD_HEARTBEAT.
#include <string>
#include <string_view>

namespace spread::firmware::lcm_link {

inline constexpr std::string_view kDefaultChannelPrefix = "SPREAD_";

struct LcmChannels {
  std::string command;    // command_t, tractor -> ECU
  std::string status;     // status_t, ECU -> tractor, every loop step
  std::string heartbeat;  // heartbeat_t, ECU -> tractor, 1 Hz
};

inline LcmChannels channels_with_prefix(std::string_view prefix) {
  const std::string p(prefix);
  return {p + "COMMAND", p + "STATUS", p + "HEARTBEAT"};
}

}  // namespace spread::firmware::lcm_link
