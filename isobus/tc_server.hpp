#pragma once
// The task-controller (TC) server side of ISO 11783-10, as a state machine without I/O: the caller feeds
// every received frame and the time, and sends what take_frames() returns. It lives beside the TC client's
// messages (tc_messages.hpp) and the DDOP reader because both ends of the connection must agree on them
// byte for byte; tests drive both ends in one process.
//
// One client (working set) at a time, the connection sequence of ISO 11783-10:
//   TC status every 2 s ─► client: working-set master, request version ─► TC: version, request version
//   ─► client: structure label request ─► TC: label (all 0xFF: no pool held, else the held pool's label)
//   ─► [request pool transfer (size) ─► 0 if it fits, else 1 ─► pool transfer by TP/ETP ─► parse_ddop:
//       0 or error bit 0] ─► activate ─► 0 when a valid pool is held, else error bit 0 ─► active.
// Active: the TC knows from the pool the element carrying each DDI and the section elements; set_value /
// request_value address them; every value the client reports goes to the as-applied log. The client task
// message (every 2 s) is supervised: 6 s without it (or, while connecting, without any message) and the
// client is dropped; the pool stays held, so a reconnecting client whose structure label matches skips the
// transfer (ISO 11783-10: the structure label identifies a stored pool).
#include <array>
#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "isobus/ddop.hpp"
#include "isobus/tc_messages.hpp"
#include "isobus/transport_protocol.hpp"

namespace spread::isobus {

inline constexpr std::uint32_t kTcProcessDataPgn = 0xCB00;

enum class TcConnectionState : std::uint8_t {
  kNone,           // no client yet, or the last one timed out
  kConnecting,     // version / labels exchanged, no valid pool activated yet
  kPoolReceiving,  // pool transfer granted, waiting for the pool
  kActive,         // pool activated: process data flow
  kDeactivated,    // the client deactivated its pool (it may activate again)
};
const char* tc_connection_state_name(TcConnectionState state);

struct TcServerConfig {
  TcVersion version{};                  // what this TC announces (booms, sections, channels it supports)
  std::size_t max_pool_bytes = 65536;   // larger pool-transfer requests are refused (answer 1)
  bool task_active = true;              // TC status byte 4 bit 0: a task is running, the client may work
};

// One value the client reported (value command 0x3): the as-applied log of ISO 11783-10 data logging.
struct AsAppliedRecord {
  Nanoseconds time{};
  std::uint8_t source = 0xFE;
  std::uint16_t element = 0;
  std::uint16_t ddi = 0;
  std::int32_t value = 0;
};

// Measurement commands (ISO 11783-10 process data commands 4-8): the client then reports the value by
// itself. Each needs the matching trigger method in the DDI's DPD.
enum class MeasurementCommand : std::uint8_t {
  kTimeInterval = 0x4,      // value [ms]
  kDistanceInterval = 0x5,  // value [mm]
  kMinimumThreshold = 0x6,  // report on change while at or above value
  kMaximumThreshold = 0x7,  // report on change while at or below value
  kChangeThreshold = 0x8,   // report when the value moved by at least value
};

struct TcServerCounters {
  std::uint64_t status_sent = 0;
  std::uint64_t pools_accepted = 0;
  std::uint64_t pools_refused = 0;      // parse_ddop refused, or larger than granted
  std::uint64_t client_timeouts = 0;
  std::uint64_t values_logged = 0;
  std::uint64_t pdacks_received = 0;
  std::uint64_t pdack_errors = 0;       // PDACKs with error bits
  std::uint64_t malformed_frames = 0;   // PGN 0xCB00 / 0xFE0D shorter than 8 bytes, unknown sub-commands
  std::uint64_t other_clients_ignored = 0;
};

class TcServer {
 public:
  explicit TcServer(TcServerConfig config = {});

  // Begins serving from `address` (once the caller's address claim stands, ISO 11783-5 §4.4.2): the first
  // TC status goes out at once.
  void start(std::uint8_t address, Nanoseconds now);
  // The address claim moved us: later frames go from the new address, and a connected client connects
  // again (it knew us by the old one).
  void set_address(std::uint8_t address);
  // Every address claim seen on the bus (ISO 11783-5; 0xFE: cannot claim): the TC knows its client by
  // NAME, and ends the session when the client's address is taken by another NAME or its NAME moves.
  void on_address_claimed(std::uint8_t source, std::uint64_t name);
  std::uint8_t address() const { return address_; }
  bool started() const { return started_; }

  // Every received frame (any PGN; those not for the TC are ignored). `data` is the frame's payload.
  void handle_frame(std::uint32_t pgn, std::uint8_t source, std::uint8_t destination,
                    std::span<const std::uint8_t> data, Nanoseconds now);
  // TC status every 2 s, transport timeouts, client supervision.
  void update(Nanoseconds now);

  std::vector<TransportFrame> take_frames() { return std::exchange(out_, {}); }
  // Human-readable lines about the connection (client found, pool refused and why, timeouts).
  std::vector<std::string> take_events() { return std::exchange(events_, {}); }
  std::vector<AsAppliedRecord> take_as_applied() { return std::exchange(as_applied_, {}); }

  TcConnectionState state() const { return state_; }
  bool active() const { return state_ == TcConnectionState::kActive; }
  std::optional<std::uint8_t> client_address() const { return client_; }
  std::optional<TcVersion> client_version() const { return client_version_; }
  // The pool last received and parsed (held across client timeouts).
  const std::optional<Ddop>& pool() const { return pool_; }
  const TcServerCounters& counters() const { return counters_; }

  // From the held pool: the element numbers whose process data (DPD) carry `ddi`, lowest first.
  std::vector<std::uint16_t> elements_for_ddi(std::uint16_t ddi) const;
  // Element numbers of the section-type elements, lowest first (their count is the section count).
  const std::vector<std::uint16_t>& section_elements() const { return section_elements_; }

  // Process data to the active client (ISO 11783-10 value 0x3 / request value 0x2). The element is the lowest one
  // carrying `ddi` in the pool. Returns an error text ("" = queued): not active, or no such DDI in the pool.
  std::string set_value(std::uint16_t ddi, std::int32_t value);
  std::string request_value(std::uint16_t ddi);
  // The same, on an explicit element.
  std::string set_value(std::uint16_t element, std::uint16_t ddi, std::int32_t value);
  std::string request_value(std::uint16_t element, std::uint16_t ddi);
  // A measurement command on the element carrying `ddi`; refused ("" = queued) when not active, when the
  // pool has no DPD for `ddi`, or when its DPD does not offer that trigger method.
  std::string measure(std::uint16_t ddi, MeasurementCommand command, std::int32_t value);
  // The trigger methods the pool's DPD for `ddi` offers (kTrigger* bits of ddop.hpp; 0: none or no DPD).
  std::uint8_t triggers_for_ddi(std::uint16_t ddi) const;

 private:
  void handle_tc_message(std::uint8_t source, std::span<const std::uint8_t> data, Nanoseconds now);
  void handle_process_data(std::uint8_t source, std::span<const std::uint8_t> data, Nanoseconds now);
  void handle_pool(std::uint8_t source, std::span<const std::uint8_t> pool_bytes);
  bool accept_client(std::uint8_t source, Nanoseconds now);
  void drop_client(const std::string& why);
  void send_to_client(const TcFrame& frame);
  void send_status(Nanoseconds now);
  std::string send_process_data(std::uint8_t command, std::uint16_t element, std::uint16_t ddi,
                                std::int32_t value);
  void index_pool();
  void event(std::string text) { events_.push_back(std::move(text)); }

  TcServerConfig config_;
  bool started_ = false;
  std::uint8_t address_ = 0xFE;
  TransportProtocol transport_;
  Nanoseconds next_status_{};

  TcConnectionState state_ = TcConnectionState::kNone;
  std::optional<std::uint8_t> client_;
  std::optional<std::uint64_t> client_name_;  // the NAME that claimed the client's address, when seen
  std::array<std::optional<std::uint64_t>, 254> names_{};  // the NAME last seen claiming each address
  std::optional<TcVersion> client_version_;
  Nanoseconds client_seen_{};           // last message that keeps the client alive
  std::uint32_t granted_pool_bytes_ = 0;

  std::optional<Ddop> pool_;
  std::map<std::uint16_t, std::vector<std::uint16_t>> ddi_elements_;
  std::map<std::uint16_t, std::uint8_t> ddi_triggers_;
  std::vector<std::uint16_t> section_elements_;

  std::vector<TransportFrame> out_;
  std::vector<std::string> events_;
  std::vector<AsAppliedRecord> as_applied_;
  TcServerCounters counters_;
};

}  // namespace spread::isobus
