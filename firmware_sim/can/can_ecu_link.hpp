#pragma once
// The ECU on an ISOBUS: turns received frames into ECU set-points and answers, and drives the
// transport from the fixed-rate loop. Answers go to whatever CanFrameSink is given (a bus port, a
// recording, both), so the same code runs on can0, on the virtual bus and in log replay.
#include <array>
#include <cstdint>
#include <optional>

#include "firmware_sim/ecu/fixed_rate_loop.hpp"
#include "isobus/can/can_frame_port.hpp"
#include "isobus/can/candump_log.hpp"
#include "isobus/iso_name.hpp"
#include "isobus/measurement_triggers.hpp"
#include "isobus/network_link.hpp"
#include "isobus/process_data.hpp"
#include "isobus/tc_client.hpp"
#include "isobus/tc_partner.hpp"
#include "isobus/transport_protocol.hpp"

namespace spread::firmware::can {

inline constexpr std::uint32_t kRequestPgn = 0xEA00;         // request for a PGN (3 data bytes)
inline constexpr std::uint32_t kAddressClaimedPgn = isobus::kAddressClaimedPgn;  // data = 64-bit NAME

struct CanEcuSettings {
  std::uint8_t address = 0x80;   // this ECU's preferred source address (the one it claims first)
  // The machine as its device descriptor object pool describes it to a task controller: the sections
  // divide this nominal working width evenly.
  double nominal_width_m = 24.0;  // [m]
  // ISO 11783-5 NAME: not self-configurable, industry group 2 (agriculture), device class 5
  // (fertilisers), function 128 (rate control), identity 0x1234, manufacturer 0 (see isobus/iso_name.hpp).
  std::uint64_t name = isobus::encode_name(isobus::IsoName{});
  // Each speed source is believed for this long after its last valid message (ISO 11783-7 sends them
  // every 100 ms: three missed). Machine selected speed wins over ground-based (radar/GNSS), which wins
  // over wheel-based (wheels slip); a lost source hands over to the next, none left means no speed.
  Nanoseconds speed_timeout = std::chrono::milliseconds(300);
};

struct CanLinkCounters {
  std::uint64_t frames_received = 0;
  std::uint64_t frames_not_for_us = 0;     // other destinations, our own echo, PGNs we do not use
  std::uint64_t process_data_handled = 0;  // PGN 0xCB00 frames addressed to us or global
  std::uint64_t responses_sent = 0;
  std::uint64_t send_failures = 0;
  std::uint64_t speed_messages = 0;        // accepted speed broadcasts
  std::uint64_t speed_not_available = 0;   // speed broadcasts saying "error" / "not available"
  std::uint64_t frames_ignored = 0;        // standard (11-bit) and remote frames: legal, not ISOBUS messages
  std::uint64_t error_frames = 0;          // error frames reported by the CAN controller
  std::uint64_t task_controller_status = 0;  // TC status messages (process data command 0xE)
  std::uint64_t transport_frames_sent = 0;   // TP/ETP frames (the pool transfer, DM1 with several faults)
  std::uint64_t dm1_sent = 0;                // DM1 messages (one a second)
  std::uint64_t measurements_sent = 0;       // values sent by a measurement trigger (commands 4-8)
  // Process data (and TC status) from a node that is not the partner task controller: ignored, and
  // counted as fault can_not_from_task_controller (ISO 11783-10: the client obeys its partner TC only).
  std::uint64_t not_from_partner = 0;
  std::uint64_t other_task_controllers = 0;  // TC status of a second, claimed TC: ignored, no fault
  // NACKs (or access denied) of our process data from the partner TC: it no longer knows our working set.
  std::uint64_t tc_refusals = 0;
  // Process data from the partner after our address changed or it refused us, before the pool was
  // active again: ignored.
  std::uint64_t before_reconnection = 0;
};

// The speed sources a tractor broadcasts, in order of precedence.
enum class SpeedSource : std::uint8_t { kMachineSelected = 0, kGroundBased = 1, kWheelBased = 2 };
inline constexpr std::size_t kSpeedSourceCount = 3;

class CanEcuProcessor {
 public:
  CanEcuProcessor(Ecu& ecu, const Clock& clock, isobus::can::CanFrameSink& tx, const CanEcuSettings& settings = {});

  // Reports a read that did not yield a frame: truncated/oversized records are malformed input.
  void handle_read_outcome(isobus::can::ReadOutcome outcome);
  void handle_frame(const can_frame& frame);
  // Starts the ISO 11783-5 address claim (a live bus). Until its claim stands the ECU sends nothing else
  // and ignores process data; see isobus::NetworkLink for the mode without a claim (replay).
  void start_address_claim();
  // Timers of the network layer (claim settle time, delayed cannot-claim); called by the loop I/O.
  void service();
  // False while the ECU has no standing address claim: it then neither answers nor applies process data,
  // and the work state was switched off when the address was lost. The ECU core reads it to keep metering
  // closed (metering must not continue without a bus address).
  bool has_address() const { return network_.has_address(); }
  const isobus::NetworkLink& network() const { return network_; }
  // The task-controller client: connection state, the TC's address, why the last connection ended.
  const isobus::TaskControllerClient& task_controller_client() const { return tc_client_; }
  // The partner TC: the only node whose process data and TC status the ECU takes.
  const isobus::TaskControllerPartner& task_controller_partner() const { return partner_; }
  const isobus::TransportProtocol& transport() const { return transport_; }
  const isobus::MeasurementTriggers& measurement_triggers() const { return triggers_; }

  const CanLinkCounters& counters() const { return counters_; }
  const CanEcuSettings& settings() const { return settings_; }

 private:
  void handle_process_data(const can_frame& frame, std::uint8_t source, bool addressed_to_us);
  // TC status: from the partner it keeps the TC alive and drives the TC client; from others it is ignored.
  void handle_tc_status(const can_frame& frame, std::uint8_t source);
  // The partner TC is gone: metering stops as for a silent TC, the TC client's connection ends.
  void partner_lost(Nanoseconds now);
  // ISO 11783-3 acknowledgement (PGN 0xE800): a NACK of our process data from the partner TC ends the
  // TC session (metering stops as on TC loss; the client reconnects).
  void handle_acknowledgement(const can_frame& frame, std::uint8_t source, bool to_us);
  // The pool follows the working width set (sections, widths, offsets); replaced at the TC on a change.
  void follow_working_width(Nanoseconds now);
  // True from a loss of our address (or the TC's refusal) until the pool is active again.
  bool rejoining() const { return rejoin_pending_ && !tc_client_.connected(); }
  void handle_speed(const can_frame& frame, SpeedSource source);
  std::optional<std::int32_t> actual_value(std::uint16_t ddi, const EcuStatus& status) const;
  // Applies a set-value; returns the PDACK error bits (0 = accepted).
  std::uint8_t apply_set_value(const isobus::ProcessData& message);
  void send(std::uint32_t pgn, std::uint8_t destination, std::uint8_t priority, const std::uint8_t* data);
  // Sends what the TC client and the transport protocol have queued.
  void flush_isobus(Nanoseconds now);
  // DM1: the active faults, once a second (ISO 11783-12).
  void send_dm1(Nanoseconds now);
  // Values the task controller asked for by measurement commands (ISO 11783-10, commands 4-8).
  void send_measurements(Nanoseconds now);

  Ecu& ecu_;
  const Clock& clock_;
  isobus::can::CanFrameSink& tx_;
  CanEcuSettings settings_;
  CanLinkCounters counters_;
  struct SpeedReading {
    std::optional<Nanoseconds> time;  // last valid message; none: never, or the source said error / n.a.
    double speed_m_s = 0.0;
    TravelDirection direction = TravelDirection::kUnknown;
  };
  std::array<SpeedReading, kSpeedSourceCount> speeds_{};
  isobus::NetworkLink network_;
  isobus::TransportProtocol transport_;
  isobus::TaskControllerClient tc_client_;
  isobus::TaskControllerPartner partner_;
  std::optional<Nanoseconds> next_dm1_;
  isobus::MeasurementTriggers triggers_;
  std::optional<Nanoseconds> last_measurement_time_;
  bool tc_was_connected_ = false;
  // Our address was lost or changed, or the TC refused us: the working set must connect again (working-set
  // master, pool, activation) before process data flows either way.
  bool rejoin_pending_ = false;
  double pool_width_m_;  // the working width the pool's sections divide [m]
  // DDI 160 as the TC set it: 1 while the TC switches the sections automatically (ISO 11783-10 section
  // control), 0 (manual) at start and again when the TC connection ends.
  std::int32_t section_control_state_ = 0;
};

// Loop I/O over a frame port: reads every pending frame each tick (recording rx and tx when asked).
class CanPortIo final : public LoopIo {
 public:
  CanPortIo(isobus::can::CanFramePort& port, Ecu& ecu, const Clock& clock, const CanEcuSettings& settings = {},
            isobus::can::CanFrameSink* recorder = nullptr);
  void pump(Nanoseconds max_wait) override;
  void after_step(const EcuStatus&) override { processor_.service(); }
  // -1 once the bus has gone away: a closed socket is always "readable" and would make the loop spin.
  int wait_fd() const override { return bus_closed_ ? -1 : port_.fd(); }
  CanEcuProcessor& processor() { return processor_; }
  // The other end closed (a spread-canbus that stopped, a socketpair peer that left).
  bool bus_closed() const { return bus_closed_; }

 private:
  isobus::can::CanFramePort& port_;
  bool bus_closed_ = false;
  isobus::can::CanFrameSink* recorder_;
  isobus::can::TeeSink tx_;
  CanEcuProcessor processor_;
};

// Loop I/O replaying a candump log: each record is delivered once the clock has advanced past its
// time offset from the first record (replay start = the clock's time at construction).
class CandumpReplayIo final : public LoopIo {
 public:
  CandumpReplayIo(const isobus::can::CandumpLog& log, CanEcuProcessor& processor, const Clock& clock,
                  isobus::can::CanFrameSink* recorder = nullptr);
  void pump(Nanoseconds max_wait) override;
  void after_step(const EcuStatus&) override {}
  bool finished() const { return next_ >= log_.records.size(); }
  // Time from replay start to the last record.
  Nanoseconds span() const;

 private:
  const isobus::can::CandumpLog& log_;
  CanEcuProcessor& processor_;
  const Clock& clock_;
  isobus::can::CanFrameSink* recorder_;
  Nanoseconds start_;
  std::size_t next_ = 0;
};

}  // namespace spread::firmware::can
