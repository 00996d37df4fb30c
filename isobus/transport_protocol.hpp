#pragma once
// ISO 11783-3 §5.10 transport protocol (TP: 9-1785 bytes, RTS/CTS to one node or BAM to all) and
// ISO 11783-6 extended transport protocol (ETP: 1786-117,440,505 bytes, RTS/CTS/DPO to one node), both
// directions, as state machines without I/O: the caller feeds received TP/ETP frames and the time, and
// sends the frames take_frames() returns. Sessions end completed, aborted (by either side, with the
// reason of the connection-abort message) or timed out.
//
// Receiver choices where the standard leaves room: a packet number already received (duplicate) is
// ignored; packets after a gap (a lost or out-of-order packet) are not kept, and when the window's last
// packet arrives a CTS asks again from the first missing one — at most kMaxRetransmitRequests times per
// session, then the session is aborted (reason 5). Data are stored in packet order only.
// The receiver answers at once (well inside Tr = 200 ms) and never holds the connection, so it never sends
// the CTS(0) "hold" that Th governs; the sender honours a peer's hold (T4).
#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace spread::isobus {

using Nanoseconds = std::chrono::nanoseconds;

inline constexpr std::uint32_t kTpConnectionManagementPgn = 0xEC00;  // TP.CM
inline constexpr std::uint32_t kTpDataTransferPgn = 0xEB00;          // TP.DT
inline constexpr std::uint32_t kEtpConnectionManagementPgn = 0xC800; // ETP.CM
inline constexpr std::uint32_t kEtpDataTransferPgn = 0xC700;         // ETP.DT
inline constexpr std::uint8_t kTransportPriority = 7;

inline constexpr std::size_t kTpMinBytes = 9;           // 8 bytes or fewer go in one frame
inline constexpr std::size_t kTpMaxBytes = 1785;        // 255 packets × 7 bytes
inline constexpr std::size_t kEtpMinBytes = kTpMaxBytes + 1;
inline constexpr std::size_t kEtpMaxBytes = 117440505;  // (2^24 - 1) packets × 7 bytes
inline constexpr std::size_t kBytesPerPacket = 7;

// Timeouts of ISO 11783-3 §5.10.2.4 (the same values as SAE J1939-21 §5.10.2.4).
inline constexpr Nanoseconds kTr = std::chrono::milliseconds(200);   // response time a node must keep
inline constexpr Nanoseconds kTh = std::chrono::milliseconds(500);   // CTS(0) hold must be renewed within
inline constexpr Nanoseconds kT1 = std::chrono::milliseconds(750);   // receiver: between data packets
inline constexpr Nanoseconds kT2 = std::chrono::milliseconds(1250);  // receiver: CTS sent, no data yet
inline constexpr Nanoseconds kT3 = std::chrono::milliseconds(1250);  // sender: last packet sent, no CTS/EoMA
inline constexpr Nanoseconds kT4 = std::chrono::milliseconds(1050);  // sender: CTS(0) hold, no next CTS
// BAM packets go out 50-200 ms apart (§5.10.3.5) so that receivers without flow control keep up.
inline constexpr Nanoseconds kBamPacketInterval = std::chrono::milliseconds(50);
inline constexpr int kMaxRetransmitRequests = 2;

// Connection-abort reasons (ISO 11783-3 Table 5; the ETP ones from ISO 11783-6).
enum class AbortReason : std::uint8_t {
  kNone = 0,
  kAlreadyInSession = 1,         // cannot support another connection
  kResourcesNeeded = 2,          // no room: message larger than this receiver takes
  kTimeout = 3,
  kCtsWhileTransferring = 4,
  kRetransmitLimit = 5,
  kUnexpectedDataPacket = 6,
  kBadSequenceNumber = 7,
  kDuplicateSequenceNumber = 8,
  kUnexpectedDpo = 9,            // ETP
  kUnexpectedDpoPgn = 10,        // ETP
  kDpoPacketsAboveCts = 11,      // ETP
  kBadDpoOffset = 12,            // ETP
  kUnexpectedCtsPgn = 14,        // ETP
  kCtsPacketsBeyondMessage = 15, // ETP (used for TP too: a CTS asking for packets that do not exist)
  kOther = 250,
};

// One CAN frame of the protocol (8 data bytes, unused ones 0xFF).
struct TransportFrame {
  std::uint8_t priority = kTransportPriority;
  std::uint32_t pgn = 0;
  std::uint8_t source = 0xFE;
  std::uint8_t destination = 0xFF;
  std::array<std::uint8_t, 8> data{};
};

struct TransportMessage {
  std::uint32_t pgn = 0;           // the PGN carried
  std::uint8_t source = 0xFE;
  std::uint8_t destination = 0xFF; // 0xFF: broadcast (BAM)
  std::vector<std::uint8_t> data;
};

enum class TransportMode : std::uint8_t { kBam, kTp, kEtp };
enum class TransportOutcome : std::uint8_t { kCompleted, kAbortedByUs, kAbortedByPeer, kTimedOut };

// How a session ended, for the sender's caller (did the message arrive?) and for counters/logs.
struct TransportSessionEnd {
  bool sending = false;
  TransportMode mode = TransportMode::kTp;
  std::uint32_t pgn = 0;
  std::uint8_t peer = 0xFF;
  TransportOutcome outcome = TransportOutcome::kCompleted;
  AbortReason reason = AbortReason::kNone;
};

struct TransportLimits {
  std::size_t max_receive_bytes = std::size_t{1} << 20;  // larger RTS are refused (abort reason 2)
  std::size_t max_sessions = 8;                          // concurrent sessions, both directions
  std::uint8_t packets_per_cts = 16;                     // window this receiver grants per CTS (1-255)
};

struct TransportCounters {
  std::uint64_t messages_sent = 0;
  std::uint64_t messages_received = 0;
  std::uint64_t aborts_sent = 0;
  std::uint64_t aborts_received = 0;
  std::uint64_t timeouts = 0;
  std::uint64_t duplicates_ignored = 0;
  std::uint64_t retransmit_requests = 0;
  std::uint64_t frames_ignored = 0;  // malformed, for another node, or for no session
};

class TransportProtocol {
 public:
  explicit TransportProtocol(std::uint8_t own_address, TransportLimits limits = {});

  // The address claim may move us: sessions of the old address are dropped without a word (§4.4.2: no
  // message after losing an address).
  void set_address(std::uint8_t address);
  std::uint8_t address() const { return address_; }

  // Starts sending `message` (source = our address): BAM when the destination is global, else TP or ETP by
  // size. False (nothing sent) for a size outside 9..1785 (BAM/TP) or 1786..117,440,505 (ETP), a BAM above
  // 1785 bytes, a session already open to that destination, or no free session.
  bool send(const TransportMessage& message, Nanoseconds now);
  // Any received frame: TP/ETP frames for us (or BAM) are used, everything else is ignored.
  void handle_frame(const TransportFrame& frame, Nanoseconds now);
  // Timeouts and BAM pacing.
  void update(Nanoseconds now);

  std::vector<TransportFrame> take_frames() { return std::exchange(out_, {}); }
  std::vector<TransportMessage> take_received() { return std::exchange(received_, {}); }
  std::vector<TransportSessionEnd> take_ended() { return std::exchange(ended_, {}); }
  std::size_t session_count() const { return sessions_.size(); }
  const TransportCounters& counters() const { return counters_; }

 private:
  enum class State : std::uint8_t {
    kSendBam,       // sender, BAM: next packet due at `deadline`
    kWaitCts,       // sender: RTS or a window sent, CTS (or EoMA) awaited until `deadline`
    kHeld,          // sender: CTS(0) received, the next CTS awaited (T4)
    kWaitEoma,      // sender: every packet sent (a CTS may still ask for some again)
    kWaitDpo,       // ETP receiver: CTS sent, DPO awaited
    kReceiving,     // receiver: CTS (or BAM) seen, data packets awaited
  };
  struct Session {
    bool sending = false;
    TransportMode mode = TransportMode::kTp;
    State state = State::kReceiving;
    std::uint32_t pgn = 0;
    std::uint8_t peer = 0xFF;         // the other node (0xFF for a BAM we send)
    std::vector<std::uint8_t> data;
    std::uint32_t total_packets = 0;
    std::uint32_t next_packet = 1;    // 1-based absolute packet number expected / to send next
    std::uint32_t window_end = 0;     // last absolute packet of the current CTS window
    std::uint32_t dpo_offset = 0;     // ETP: absolute packet number = offset + sequence number
    std::uint8_t peer_max_per_cts = 0xFF;  // TP: the sender's limit from its RTS
    int retransmit_requests = 0;
    Nanoseconds deadline{};
    bool done = false;                // ended; removed at the end of the current call
  };

  Session* find(bool sending, std::uint8_t peer, bool bam);
  void handle_cm(const TransportFrame& frame, bool extended, Nanoseconds now);
  void handle_dpo(Session& s, const TransportFrame& frame, Nanoseconds now);
  void handle_dt(const TransportFrame& frame, bool extended, Nanoseconds now);
  void handle_rts(const TransportFrame& frame, bool extended, Nanoseconds now);
  void handle_bam(const TransportFrame& frame, Nanoseconds now);
  void handle_cts(Session& s, const TransportFrame& frame, bool extended, Nanoseconds now);
  void send_cts(Session& s, std::uint32_t next, Nanoseconds now);
  void send_window(Session& s, std::uint32_t first, std::uint32_t count, Nanoseconds now);
  void send_packet(const Session& s, std::uint32_t absolute, std::uint8_t sequence);
  void send_abort(std::uint8_t peer, std::uint32_t pgn, bool extended, AbortReason reason);
  void abort(Session& s, AbortReason reason);
  void end(Session& s, TransportOutcome outcome, AbortReason reason);
  void prune();
  void complete_reception(Session& s);
  void emit(std::uint32_t pgn, std::uint8_t destination, const std::array<std::uint8_t, 8>& data);

  std::uint8_t address_;
  TransportLimits limits_;
  std::vector<Session> sessions_;
  std::vector<TransportFrame> out_;
  std::vector<TransportMessage> received_;
  std::vector<TransportSessionEnd> ended_;
  TransportCounters counters_;
};

}  // namespace spread::isobus
