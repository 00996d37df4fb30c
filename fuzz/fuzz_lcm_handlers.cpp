// Fuzz harness: the LCM message handlers of the ECU and of the tractor side (firmware_sim/lcm, lcm_link), through
// the real subscriptions on an in-process memq:// LCM instance.
// Input: byte 0 picks the channel (command / status / heartbeat), the rest is the payload as it would
// arrive from the network. Checked: the checked decoding never crashes or throws, an undecodable or
// foreign command is counted as a fault and changes nothing, and the ECU state stays valid.
#include <lcm/lcm-cpp.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>

#include "libspread/control/ecu.hpp"
#include "firmware_sim/lcm/lcm_ecu_link.hpp"
#include "fuzz/ecu_invariants.hpp"
#include "fuzz/fuzz_input.hpp"
#include "lcm_link/lcm_tractor_link.hpp"

namespace {

constexpr const char* kHarness = "fuzz_lcm_handlers";
namespace lcm_link = spread::lcm_link;

lcm::LCM& shared_lcm() {
  // One instance for the whole run: creating an LCM instance is far costlier than a message.
  static lcm::LCM instance("memq://");
  return instance;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  lcm::LCM& lcm = shared_lcm();
  if (!lcm.good()) spread::fuzz::fail(kHarness, "memq:// LCM instance not usable");
  const lcm_link::LcmChannels channels = lcm_link::channels_with_prefix("FUZZ_");
  spread::ManualClock clock;
  const spread::firmware::EcuParameters parameters;
  spread::firmware::Ecu ecu(clock, parameters);
  spread::firmware::LcmEcuLink ecu_link(lcm, ecu, channels);
  lcm_link::LcmTractorLink tractor(lcm, channels);

  const std::uint8_t* payload = data + 1;
  const auto payload_size = static_cast<unsigned>(size - 1);
  const std::string* channel = &channels.command;
  if (data[0] % 3 == 1) channel = &channels.status;
  if (data[0] % 3 == 2) channel = &channels.heartbeat;
  const std::int64_t sequence_before = ecu.status().last_command_sequence;
  lcm.publish(*channel, payload, payload_size);
  ecu_link.pump(spread::Nanoseconds::zero());  // delivers to every subscriber on the instance

  const spread::firmware::LcmLinkCounters& counters = ecu_link.counters();
  if (counters.commands_accepted > counters.commands_received) spread::fuzz::fail(kHarness, "accepted more than received");
  if (counters.commands_accepted == 0 && ecu.status().last_command_sequence != sequence_before) {
    spread::fuzz::fail(kHarness, "a rejected command changed the ECU's state");
  }
  // One loop step publishes a status and a heartbeat: the tractor side decodes what the ECU encoded.
  clock.advance(std::chrono::milliseconds(50));
  ecu.step(0.05);
  ecu_link.after_step(ecu.status());
  tractor.handle(spread::Nanoseconds::zero());
  spread::fuzz::check_ecu_status(kHarness, ecu);
  return 0;
}
