// Fuzz harness: CAN frame decoding and the ECU's ISOBUS process-data handler (firmware_sim/can).
// Input: a sequence of raw `struct can_frame` records (16 bytes each, as read from a CAN_RAW socket or
// the virtual bus), each followed by 1 byte: milliseconds the ECU's clock advances (a loop step).
// Checked: codec round trips (29-bit id, process data, PDACK), the processor never crashes, every frame
// it answers is a well-formed extended frame from its own address (or a cannot-claim from the null
// address after a fuzzed claim took it), and the ECU state stays valid.
#include <linux/can.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "firmware_sim/can/can_ecu_link.hpp"
#include "libspread/control/ecu.hpp"
#include "fuzz/ecu_invariants.hpp"
#include "fuzz/fuzz_input.hpp"
#include "isobus/isobus_id.hpp"
#include "isobus/process_data.hpp"
#include "isobus/speed_messages.hpp"

namespace {

constexpr const char* kHarness = "fuzz_can_frames";
namespace can = spread::isobus::can;
namespace iso = spread::isobus;
namespace ecu_can = spread::firmware::can;

// Checks every answer instead of sending it anywhere.
class CheckingSink final : public can::CanFrameSink {
 public:
  explicit CheckingSink(std::uint8_t own_address) : own_address_(own_address) {}
  bool send(const can_frame& frame) override {
    if ((frame.can_id & CAN_EFF_FLAG) == 0 || (frame.can_id & (CAN_RTR_FLAG | CAN_ERR_FLAG)) != 0) {
      spread::fuzz::fail(kHarness, "answer is not an extended data frame");
    }
    const iso::IsobusId id = iso::decode_id(frame.can_id & CAN_EFF_MASK);
    // A request (PGN 0xEA00) has 3 data bytes (ISO 11783-3): the ECU asks for every address claim once its
    // own stands.
    const bool request = id.pgn == ecu_can::kRequestPgn && frame.len == 3;
    if (frame.len != 8 && !request) spread::fuzz::fail(kHarness, "answer with DLC " + std::to_string(frame.len));
    // The one message allowed from elsewhere: cannot-claim, from the null address, after losing 0x80.
    const bool cannot_claim = id.pgn == iso::kAddressClaimedPgn && id.source == iso::kNullAddress;
    if (id.source != own_address_ && !cannot_claim) {
      spread::fuzz::fail(kHarness, "answer not sent from the ECU's own address");
    }
    return true;
  }

 private:
  std::uint8_t own_address_;
};

void check_codecs(const can_frame& frame) {
  const std::uint32_t id29 = frame.can_id & CAN_EFF_MASK;
  if (iso::encode_id(iso::decode_id(id29)) != id29) spread::fuzz::fail(kHarness, "29-bit id does not round-trip");
  iso::ProcessDataBytes bytes{};
  std::memcpy(bytes.data(), frame.data, bytes.size());
  if (iso::encode_process_data(iso::decode_process_data(bytes)) != bytes) {
    spread::fuzz::fail(kHarness, "process data bytes do not round-trip");
  }
  if (const auto pdack = iso::decode_pdack(bytes)) {
    if (pdack->acknowledged_command > 0xF) spread::fuzz::fail(kHarness, "PDACK command above 4 bits");
  }
  if (const auto speed = iso::decode_speed(bytes)) {
    if (!(speed->speed_m_s >= 0.0 && speed->speed_m_s <= 64.255)) spread::fuzz::fail(kHarness, "speed out of range");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  spread::fuzz::FuzzInput input(data, size);
  spread::ManualClock clock;
  const spread::firmware::EcuParameters parameters;
  spread::firmware::Ecu ecu(clock, parameters);
  const ecu_can::CanEcuSettings settings;
  CheckingSink sink(settings.address);
  ecu_can::CanEcuProcessor processor(ecu, clock, sink, settings);
  processor.start_address_claim();
  // Let the claim stand (250 ms, ISO 11783-5) so that the inputs reach the process-data handler.
  clock.advance(std::chrono::milliseconds(250));
  processor.service();
  // A partner task controller at 0x81 (its claim with a TC's NAME, then its status), so that the inputs'
  // process data from 0x81 reach the handler past the partner check; the inputs may still take it away.
  iso::IsoName tc;
  tc.self_configurable = true;
  tc.device_class = spread::isobus::kDeviceClassNonSpecific;
  tc.function = spread::isobus::kFunctionTaskController;
  const auto tc_name = spread::isobus::name_to_bytes(spread::isobus::encode_name(tc));
  processor.handle_frame(can::make_frame(iso::encode_id({6, iso::kAddressClaimedPgn, 0xFF, 0x81}), tc_name.data(), 8));
  const std::uint8_t status[8] = {0xFE, 0xFF, 0xFF, 0xFF, 0x01, 0xFF, 0xFF, 0xFF};
  processor.handle_frame(can::make_frame(iso::encode_id({3, iso::kProcessDataPgn, 0xFF, 0x81}), status, 8));
  while (input.remaining() > 0) {
    const can_frame frame = input.take<can_frame>();
    check_codecs(frame);
    processor.handle_frame(frame);
    const auto step_ms = input.take<std::uint8_t>();
    if (step_ms > 0) {
      clock.advance(std::chrono::milliseconds(step_ms));
      ecu.step(step_ms * 1e-3);
    }
    spread::fuzz::check_ecu_status(kHarness, ecu, step_ms > 0);
  }
  return 0;
}
