#pragma once
// The tractor's side of the LCM link (spread-tractor, tests): publishes command_t, receives status_t
// and heartbeat_t, counts what it could not decode.
#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "lcm_link/lcm_channels.hpp"
#include "libspread/core/clock.hpp"
#include "spread/command_t.hpp"
#include "spread/heartbeat_t.hpp"
#include "spread/status_t.hpp"

namespace spread::lcm_link {

class LcmTractorLink {
 public:
  // Throws std::runtime_error when `lcm` is not usable.
  LcmTractorLink(lcm::LCM& lcm, LcmChannels channels);
  ~LcmTractorLink();
  LcmTractorLink(const LcmTractorLink&) = delete;
  LcmTractorLink& operator=(const LcmTractorLink&) = delete;

  bool send(const spread::command_t& command);
  // Sends raw bytes on the command channel (tests inject bad payloads this way).
  bool send_raw(const void* data, unsigned size);
  // Handles incoming messages for up to `timeout`; returns how many were handled.
  int handle(Nanoseconds timeout);
  // Handles messages until `predicate` holds or `timeout` passes (wall clock); true if it held.
  bool wait_for(const std::function<bool()>& predicate, Nanoseconds timeout);

  const std::optional<spread::status_t>& latest_status() const { return latest_status_; }
  const std::optional<spread::heartbeat_t>& latest_heartbeat() const { return latest_heartbeat_; }
  std::uint64_t statuses_received() const { return statuses_; }
  std::uint64_t heartbeats_received() const { return heartbeats_; }
  std::uint64_t undecodable_received() const { return undecodable_; }

  std::function<void(const spread::status_t&)> on_status;
  std::function<void(const spread::heartbeat_t&)> on_heartbeat;

 private:
  void on_status_payload(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void on_heartbeat_payload(const lcm::ReceiveBuffer* buffer, const std::string& channel);

  lcm::LCM& lcm_;
  LcmChannels channels_;
  lcm::Subscription* status_subscription_ = nullptr;
  lcm::Subscription* heartbeat_subscription_ = nullptr;
  std::optional<spread::status_t> latest_status_;
  std::optional<spread::heartbeat_t> latest_heartbeat_;
  std::uint64_t statuses_ = 0;
  std::uint64_t heartbeats_ = 0;
  std::uint64_t undecodable_ = 0;
};

}  // namespace spread::lcm_link
