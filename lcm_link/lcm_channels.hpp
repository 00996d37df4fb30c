#pragma once
// LCM channel names. All three share a configurable prefix so that several simulated machines (or
// test cases) can share one LCM network: prefix "SPREAD_" gives SPREAD_COMMAND, SPREAD_STATUS,
// SPREAD_HEARTBEAT.
#include <string>
#include <string_view>

namespace spread::lcm_link {

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

// The prefix's names, each replaced by a full name when one is given (non-empty): the command-line
// options --command-channel, --status-channel, --heartbeat-channel of firmware_sim and spread-tractor,
// for a bus whose channel names do not share a prefix.
inline LcmChannels channels_from(std::string_view prefix, const std::string& command, const std::string& status,
                                 const std::string& heartbeat) {
  LcmChannels channels = channels_with_prefix(prefix);
  if (!command.empty()) channels.command = command;
  if (!status.empty()) channels.status = status;
  if (!heartbeat.empty()) channels.heartbeat = heartbeat;
  return channels;
}

}  // namespace spread::lcm_link
