#pragma once
// The ECU's task-controller client (ISO 11783-10 connection procedure) as a state machine without I/O:
// received PGN 0xCB00 messages and the time go in, messages to send come out (the caller sends those over
// 8 bytes by TP/ETP). The sequence, one step per answer:
//   TC status seen  -> working-set master message, request version
//   version         -> request structure label
//   structure label -> request localisation label
//   localisation label -> the TC holds our pool (both labels ours): activate; else request object-pool
//                      transfer
//   transfer answer -> object-pool transfer (the pool, by TP/ETP)
//   pool answer     -> activate
//   activate answer -> connected: client task message every 2 s
//   pool changed while connected (replace_pool) -> deactivate; its answer -> request object-pool transfer
//                      -> ... -> activate again (ISO 11783-10: a changed pool is deactivated, transferred and
//                      activated; the TC takes the new structure label and geometry)
// Any refusal or a TC silent for 6 s (three missed status messages) ends the connection; the client starts
// again with the next TC status after `retry_delay`. The ECU core's own supervision of the TC (work state
// off after 6 s) does not depend on this state machine.
#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "isobus/tc_messages.hpp"

namespace spread::isobus {

using Nanoseconds = std::chrono::nanoseconds;

enum class TcClientState : std::uint8_t {
  kWaitForTc,             // no TC status seen yet (or the last connection ended)
  kWaitVersion,           // request version sent
  kWaitStructureLabel,    // request structure label sent
  kWaitLocalizationLabel, // request localisation label sent
  kWaitTransferAnswer,    // request object-pool transfer sent
  kWaitPoolAnswer,        // object-pool transfer sent
  kWaitActivateAnswer,    // activate sent
  kWaitDeactivateAnswer,  // deactivate sent: the pool changed while connected
  kConnected,             // pool active: process data flows
  kRetryWait,             // refused or timed out: waiting before the next attempt
};

const char* tc_client_state_name(TcClientState state);

struct TcClientSettings {
  TcVersion version{};                                   // what this client answers to a request version
  Nanoseconds answer_timeout = std::chrono::seconds(6);  // per request; the pool transfer gets 5x
  Nanoseconds retry_delay = std::chrono::seconds(6);     // after a refusal or a timeout
};

struct TcOutgoing {
  std::uint32_t pgn = 0;            // 0xCB00 or the working-set master PGN
  std::uint8_t destination = 0xFF;  // the TC, or global
  std::vector<std::uint8_t> data;   // 8 bytes, or the object-pool transfer (by TP/ETP)
};

class TaskControllerClient {
 public:
  // `pool` is the DDOP as write_ddop gives it for version 4; the labels are the ones inside it.
  // `pool_version3`, when given, is the same pool written for version 3 (no extended structure label):
  // what a TC that answers version 3 gets (ISO 11783-10: the pool follows the lower of the two versions).
  TaskControllerClient(std::vector<std::uint8_t> pool, std::array<std::uint8_t, 7> structure_label,
                       std::array<std::uint8_t, 7> localization_label, TcClientSettings settings = {},
                       std::vector<std::uint8_t> pool_version3 = {});

  // A PGN 0xCB00 message from `source` addressed to us or to all (single frame or reassembled). Messages
  // that are not connection messages (process data values, ...) are ignored here.
  void handle_message(std::uint8_t source, std::span<const std::uint8_t> data, Nanoseconds now);
  // Timeouts and the periodic client task message.
  void update(Nanoseconds now);
  // The partner TC is gone (its address taken or released), or refuses us (a NACK of our process data):
  // the connection ends as on a timeout, and the next attempt waits `retry_delay`.
  void drop(std::string why, Nanoseconds now);
  // Our own address changed or was lost (ISO 11783-5): the TC knows our working set by an address we no
  // longer hold, so the connection ends at once, without the retry delay. connect() starts it again once
  // our address stands.
  void restart(std::string why);
  // Starts the connection with `tc` now (working-set master, request version), as a TC status from it
  // does, when no connection is running or waiting to retry.
  void connect(std::uint8_t tc, Nanoseconds now);
  // The machine changed (the working width, and so the sections' widths and offsets): the new pool and its
  // labels replace the old. Connected, the pool is deactivated, transferred again and activated; while
  // connecting, the connection goes on with the new pool (a transfer already under way is followed by
  // this change once active); otherwise the next connection uses it.
  void replace_pool(std::vector<std::uint8_t> pool, std::array<std::uint8_t, 7> structure_label,
                    std::array<std::uint8_t, 7> localization_label, std::vector<std::uint8_t> pool_version3,
                    Nanoseconds now);
  std::uint64_t pool_changes() const { return pool_changes_; }  // pools replaced while connected
  std::vector<TcOutgoing> take_outgoing();

  TcClientState state() const { return state_; }
  bool connected() const { return state_ == TcClientState::kConnected; }
  std::optional<std::uint8_t> task_controller() const { return tc_; }
  const std::string& last_error() const { return last_error_; }  // why the last connection ended
  std::uint64_t connections() const { return connections_; }     // times the pool was activated

 private:
  void send(std::uint32_t pgn, std::uint8_t destination, std::span<const std::uint8_t> data);
  void send_tc(const TcFrame& frame) { send(0xCB00, *tc_, frame); }
  void expect(TcClientState state, Nanoseconds now, Nanoseconds timeout);
  void end_connection(std::string why, Nanoseconds now);
  void begin_pool_change(Nanoseconds now);

  const std::vector<std::uint8_t>& pool_for_tc() const;

  std::vector<std::uint8_t> pool_;
  std::vector<std::uint8_t> pool_version3_;
  std::uint8_t tc_version_ = 4;  // the connected TC's version answer
  std::array<std::uint8_t, 7> structure_label_;
  std::array<std::uint8_t, 7> localization_label_;
  bool structure_known_ = false;  // the TC's structure label was ours
  TcClientSettings settings_;
  TcClientState state_ = TcClientState::kWaitForTc;
  std::optional<std::uint8_t> tc_;
  Nanoseconds deadline_{};
  Nanoseconds last_tc_status_{};
  Nanoseconds next_client_task_{};
  std::string last_error_;
  std::uint64_t connections_ = 0;
  std::uint64_t pool_changes_ = 0;
  bool pool_change_pending_ = false;  // the pool changed while the old one was being transferred
  std::vector<TcOutgoing> out_;
};

}  // namespace spread::isobus
