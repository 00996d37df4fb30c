#pragma once
// The ECU on LCM: command_t in, status_t out every loop step, heartbeat_t once a second.
// Bad payloads are counted by the ECU as faults (wrong fingerprint, undecodable).
#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "firmware_sim/ecu/fixed_rate_loop.hpp"
#include "lcm_link/lcm_channels.hpp"
#include "spread/command_t.hpp"
#include "spread/heartbeat_t.hpp"
#include "spread/status_t.hpp"

namespace spread::firmware {

struct LcmLinkCounters {
  std::uint64_t commands_received = 0;   // payloads on the command channel
  std::uint64_t commands_accepted = 0;
  std::uint64_t statuses_published = 0;
  std::uint64_t heartbeats_published = 0;
  std::uint64_t publish_failures = 0;
};

class LcmEcuLink final : public LoopIo {
 public:
  // Throws std::runtime_error when `lcm` is not usable (bad URL, no multicast route, ...).
  LcmEcuLink(lcm::LCM& lcm, Ecu& ecu, lcm_link::LcmChannels channels, std::string node_name = "firmware_sim");
  ~LcmEcuLink() override;
  LcmEcuLink(const LcmEcuLink&) = delete;
  LcmEcuLink& operator=(const LcmEcuLink&) = delete;

  // For the heartbeat's loop figures (optional).
  void attach_loop(const FixedRateLoop* loop) { loop_ = loop; }

  void pump(Nanoseconds max_wait) override;
  void after_step(const EcuStatus& status) override;
  int wait_fd() const override { return lcm_.getFileno(); }

  const LcmLinkCounters& counters() const { return counters_; }
  const lcm_link::LcmChannels& channels() const { return channels_; }

 private:
  void on_command(const lcm::ReceiveBuffer* buffer, const std::string& channel);
  void publish_encoded(const std::string& channel, int size);
  void fill_status(const EcuStatus& status);

  lcm::LCM& lcm_;
  Ecu& ecu_;
  lcm_link::LcmChannels channels_;
  std::string node_name_;
  lcm::Subscription* subscription_ = nullptr;
  const FixedRateLoop* loop_ = nullptr;
  LcmLinkCounters counters_;
  // Reused between messages so that the steady state does not allocate.
  spread::command_t command_{};
  spread::status_t status_{};
  spread::heartbeat_t heartbeat_{};
  std::vector<std::uint8_t> encode_buffer_;
  std::optional<Nanoseconds> last_heartbeat_;
};

// Fills an EcuCommand viewing `message` (valid while `message` lives).
EcuCommand to_ecu_command(const spread::command_t& message);

}  // namespace spread::firmware
