#include "isobus/transport_protocol.hpp"

#include <algorithm>

namespace spread::isobus {
namespace {

// Control bytes (byte 1 of TP.CM / ETP.CM).
constexpr std::uint8_t kTpRts = 16;
constexpr std::uint8_t kTpCts = 17;
constexpr std::uint8_t kTpEoma = 19;
constexpr std::uint8_t kTpBam = 32;
constexpr std::uint8_t kEtpRts = 20;
constexpr std::uint8_t kEtpCts = 21;
constexpr std::uint8_t kEtpDpo = 22;
constexpr std::uint8_t kEtpEoma = 23;
constexpr std::uint8_t kAbort = 255;

using Bytes = std::array<std::uint8_t, 8>;

std::uint32_t get_pgn(const Bytes& d) {
  return std::uint32_t{d[5]} | (std::uint32_t{d[6]} << 8) | (std::uint32_t{d[7]} << 16);
}
void put_pgn(Bytes& d, std::uint32_t pgn) {
  d[5] = static_cast<std::uint8_t>(pgn);
  d[6] = static_cast<std::uint8_t>(pgn >> 8);
  d[7] = static_cast<std::uint8_t>(pgn >> 16);
}
std::uint32_t get24(const Bytes& d, std::size_t at) {
  return std::uint32_t{d[at]} | (std::uint32_t{d[at + 1]} << 8) | (std::uint32_t{d[at + 2]} << 16);
}
void put24(Bytes& d, std::size_t at, std::uint32_t v) {
  d[at] = static_cast<std::uint8_t>(v);
  d[at + 1] = static_cast<std::uint8_t>(v >> 8);
  d[at + 2] = static_cast<std::uint8_t>(v >> 16);
}
Bytes filled() {
  Bytes d;
  d.fill(0xFF);
  return d;
}
std::uint32_t packets_for(std::size_t bytes) {
  return static_cast<std::uint32_t>((bytes + kBytesPerPacket - 1) / kBytesPerPacket);
}

}  // namespace

TransportProtocol::TransportProtocol(std::uint8_t own_address, TransportLimits limits)
    : address_(own_address), limits_(limits) {
  if (limits_.packets_per_cts == 0) limits_.packets_per_cts = 1;
}

void TransportProtocol::set_address(std::uint8_t address) {
  if (address == address_) return;
  for (Session& s : sessions_) end(s, TransportOutcome::kAbortedByUs, AbortReason::kOther);
  prune();
  address_ = address;
}

void TransportProtocol::emit(std::uint32_t pgn, std::uint8_t destination, const Bytes& data) {
  out_.push_back({kTransportPriority, pgn, address_, destination, data});
}

void TransportProtocol::end(Session& s, TransportOutcome outcome, AbortReason reason) {
  if (s.done) return;
  s.done = true;
  ended_.push_back({s.sending, s.mode, s.pgn, s.peer, outcome, reason});
}

void TransportProtocol::prune() {
  sessions_.erase(std::remove_if(sessions_.begin(), sessions_.end(), [](const Session& s) { return s.done; }),
                  sessions_.end());
}

TransportProtocol::Session* TransportProtocol::find(bool sending, std::uint8_t peer, bool bam) {
  for (Session& s : sessions_) {
    if (!s.done && s.sending == sending && s.peer == peer && (s.mode == TransportMode::kBam) == bam) return &s;
  }
  return nullptr;
}

void TransportProtocol::send_abort(std::uint8_t peer, std::uint32_t pgn, bool extended, AbortReason reason) {
  Bytes d = filled();
  d[0] = kAbort;
  d[1] = static_cast<std::uint8_t>(reason);
  put_pgn(d, pgn);
  emit(extended ? kEtpConnectionManagementPgn : kTpConnectionManagementPgn, peer, d);
  ++counters_.aborts_sent;
}

void TransportProtocol::abort(Session& s, AbortReason reason) {
  // A BAM has no back channel: its receiver just drops it (§5.10.3.5).
  if (s.mode != TransportMode::kBam) send_abort(s.peer, s.pgn, s.mode == TransportMode::kEtp, reason);
  end(s, TransportOutcome::kAbortedByUs, reason);
}

bool TransportProtocol::send(const TransportMessage& m, Nanoseconds now) {
  const std::size_t size = m.data.size();
  const bool bam = m.destination == 0xFF;
  if (address_ >= 0xFE || m.destination == 0xFE || m.destination == address_) return false;
  if (size < kTpMinBytes || size > kEtpMaxBytes || (bam && size > kTpMaxBytes)) return false;
  if (find(true, bam ? 0xFF : m.destination, bam) != nullptr) return false;  // one session per peer
  if (sessions_.size() >= limits_.max_sessions) return false;
  Session s;
  s.sending = true;
  s.mode = bam ? TransportMode::kBam : (size > kTpMaxBytes ? TransportMode::kEtp : TransportMode::kTp);
  s.pgn = m.pgn;
  s.peer = m.destination;
  s.data = m.data;
  s.total_packets = packets_for(size);
  Bytes d = filled();
  put_pgn(d, m.pgn);
  if (s.mode == TransportMode::kEtp) {
    d[0] = kEtpRts;
    const auto n = static_cast<std::uint32_t>(size);
    d[1] = static_cast<std::uint8_t>(n);
    d[2] = static_cast<std::uint8_t>(n >> 8);
    d[3] = static_cast<std::uint8_t>(n >> 16);
    d[4] = static_cast<std::uint8_t>(n >> 24);
    emit(kEtpConnectionManagementPgn, s.peer, d);
  } else {
    d[0] = bam ? kTpBam : kTpRts;
    d[1] = static_cast<std::uint8_t>(size);
    d[2] = static_cast<std::uint8_t>(size >> 8);
    d[3] = static_cast<std::uint8_t>(s.total_packets);
    d[4] = 0xFF;  // RTS: no limit on the packets per CTS; BAM: reserved
    emit(kTpConnectionManagementPgn, s.peer, d);
  }
  s.state = bam ? State::kSendBam : State::kWaitCts;
  s.deadline = now + (bam ? kBamPacketInterval : kT3);
  sessions_.push_back(std::move(s));
  return true;
}

void TransportProtocol::send_packet(const Session& s, std::uint32_t absolute, std::uint8_t sequence) {
  Bytes d = filled();
  d[0] = sequence;
  const std::size_t offset = std::size_t{absolute - 1} * kBytesPerPacket;
  const std::size_t n = std::min(kBytesPerPacket, s.data.size() - offset);
  std::copy_n(s.data.begin() + static_cast<std::ptrdiff_t>(offset), n, d.begin() + 1);
  emit(s.mode == TransportMode::kEtp ? kEtpDataTransferPgn : kTpDataTransferPgn, s.peer, d);
}

void TransportProtocol::send_cts(Session& s, std::uint32_t next, Nanoseconds now) {
  std::uint32_t n = std::min<std::uint32_t>(limits_.packets_per_cts, s.total_packets - next + 1);
  if (s.mode == TransportMode::kTp) n = std::min<std::uint32_t>(n, std::max<std::uint8_t>(s.peer_max_per_cts, 1));
  s.window_end = next + n - 1;
  Bytes d = filled();
  put_pgn(d, s.pgn);
  d[1] = static_cast<std::uint8_t>(n);
  if (s.mode == TransportMode::kEtp) {
    d[0] = kEtpCts;
    put24(d, 2, next);
    emit(kEtpConnectionManagementPgn, s.peer, d);
    s.state = State::kWaitDpo;
  } else {
    d[0] = kTpCts;
    d[2] = static_cast<std::uint8_t>(next);
    emit(kTpConnectionManagementPgn, s.peer, d);
    s.state = State::kReceiving;
  }
  s.deadline = now + kT2;
}

void TransportProtocol::complete_reception(Session& s) {
  if (s.mode != TransportMode::kBam) {
    Bytes d = filled();
    put_pgn(d, s.pgn);
    const auto size = static_cast<std::uint32_t>(s.data.size());
    if (s.mode == TransportMode::kEtp) {
      d[0] = kEtpEoma;
      d[1] = static_cast<std::uint8_t>(size);
      d[2] = static_cast<std::uint8_t>(size >> 8);
      d[3] = static_cast<std::uint8_t>(size >> 16);
      d[4] = static_cast<std::uint8_t>(size >> 24);
      emit(kEtpConnectionManagementPgn, s.peer, d);
    } else {
      d[0] = kTpEoma;
      d[1] = static_cast<std::uint8_t>(size);
      d[2] = static_cast<std::uint8_t>(size >> 8);
      d[3] = static_cast<std::uint8_t>(s.total_packets);
      emit(kTpConnectionManagementPgn, s.peer, d);
    }
  }
  received_.push_back({s.pgn, s.peer, s.mode == TransportMode::kBam ? std::uint8_t{0xFF} : address_, std::move(s.data)});
  ++counters_.messages_received;
  end(s, TransportOutcome::kCompleted, AbortReason::kNone);
}

void TransportProtocol::handle_frame(const TransportFrame& f, Nanoseconds now) {
  const bool cm = f.pgn == kTpConnectionManagementPgn || f.pgn == kEtpConnectionManagementPgn;
  const bool dt = f.pgn == kTpDataTransferPgn || f.pgn == kEtpDataTransferPgn;
  if (!cm && !dt) return;
  const bool extended = f.pgn == kEtpConnectionManagementPgn || f.pgn == kEtpDataTransferPgn;
  const bool to_us = f.destination == address_ && address_ < 0xFE;
  // Only TP broadcasts (BAM) go to the global address; ETP is always peer to peer.
  const bool broadcast = f.destination == 0xFF && !extended;
  if ((!to_us && !broadcast) || f.source == address_ || f.source >= 0xFE) {
    ++counters_.frames_ignored;
    return;
  }
  if (cm) {
    handle_cm(f, extended, now);
  } else {
    handle_dt(f, extended, now);
  }
  prune();
}

void TransportProtocol::handle_cm(const TransportFrame& f, bool extended, Nanoseconds now) {
  const std::uint8_t control = f.data[0];
  const bool broadcast = f.destination == 0xFF;
  if (broadcast) {
    if (control == kTpBam) {
      handle_bam(f, now);
    } else {
      ++counters_.frames_ignored;  // RTS, CTS, ... must be addressed to one node
    }
    return;
  }
  const std::uint8_t rts = extended ? kEtpRts : kTpRts;
  const std::uint8_t cts = extended ? kEtpCts : kTpCts;
  const std::uint8_t eoma = extended ? kEtpEoma : kTpEoma;
  const TransportMode mode = extended ? TransportMode::kEtp : TransportMode::kTp;
  if (control == rts) {
    handle_rts(f, extended, now);
    return;
  }
  if (control == kAbort) {
    const std::uint32_t pgn = get_pgn(f.data);
    for (Session& s : sessions_) {
      if (!s.done && s.mode == mode && s.peer == f.source && s.pgn == pgn) {
        ++counters_.aborts_received;
        end(s, TransportOutcome::kAbortedByPeer, static_cast<AbortReason>(f.data[1]));
        return;
      }
    }
    ++counters_.frames_ignored;
    return;
  }
  if (control == cts || control == eoma) {
    Session* s = find(true, f.source, false);
    if (s == nullptr || s->mode != mode) {
      ++counters_.frames_ignored;
      return;
    }
    if (control == cts) {
      handle_cts(*s, f, extended, now);
    } else if (s->next_packet > s->total_packets && get_pgn(f.data) == s->pgn) {
      ++counters_.messages_sent;
      end(*s, TransportOutcome::kCompleted, AbortReason::kNone);
    } else {
      ++counters_.frames_ignored;  // EoMA before the last packet went out, or for another PGN
    }
    return;
  }
  if (extended && control == kEtpDpo) {
    Session* s = find(false, f.source, false);
    if (s == nullptr || s->mode != TransportMode::kEtp) {
      ++counters_.frames_ignored;
      return;
    }
    handle_dpo(*s, f, now);
    return;
  }
  ++counters_.frames_ignored;
}

void TransportProtocol::handle_rts(const TransportFrame& f, bool extended, Nanoseconds now) {
  const std::uint32_t pgn = get_pgn(f.data);
  std::size_t size = 0;
  std::uint32_t total = 0;
  std::uint8_t max_per_cts = 0xFF;
  if (extended) {
    size = std::size_t{f.data[1]} | (std::size_t{f.data[2]} << 8) | (std::size_t{f.data[3]} << 16) |
           (std::size_t{f.data[4]} << 24);
    total = packets_for(size);
  } else {
    size = std::size_t{f.data[1]} | (std::size_t{f.data[2]} << 8);
    total = f.data[3];
    max_per_cts = f.data[4] == 0 ? std::uint8_t{1} : f.data[4];
  }
  // A sender that starts over replaces its old session (it has given up on it).
  if (Session* old = find(false, f.source, false)) end(*old, TransportOutcome::kAbortedByPeer, AbortReason::kNone);
  const bool size_ok = extended ? (size >= kEtpMinBytes && size <= kEtpMaxBytes)
                                : (size >= kTpMinBytes && size <= kTpMaxBytes && total == packets_for(size));
  if (!size_ok) {
    send_abort(f.source, pgn, extended, AbortReason::kOther);
    return;
  }
  if (size > limits_.max_receive_bytes) {
    send_abort(f.source, pgn, extended, AbortReason::kResourcesNeeded);
    return;
  }
  prune();
  if (sessions_.size() >= limits_.max_sessions) {
    send_abort(f.source, pgn, extended, AbortReason::kAlreadyInSession);
    return;
  }
  Session s;
  s.mode = extended ? TransportMode::kEtp : TransportMode::kTp;
  s.pgn = pgn;
  s.peer = f.source;
  s.data.assign(size, 0);
  s.total_packets = total;
  s.peer_max_per_cts = max_per_cts;
  sessions_.push_back(std::move(s));
  send_cts(sessions_.back(), 1, now);
}

void TransportProtocol::handle_bam(const TransportFrame& f, Nanoseconds now) {
  const std::size_t size = std::size_t{f.data[1]} | (std::size_t{f.data[2]} << 8);
  const std::uint32_t total = f.data[3];
  // A new BAM from the same node replaces the one in progress (a node sends one BAM at a time).
  if (Session* old = find(false, f.source, true)) end(*old, TransportOutcome::kAbortedByPeer, AbortReason::kNone);
  if (size < kTpMinBytes || size > kTpMaxBytes || total != packets_for(size) || size > limits_.max_receive_bytes) {
    ++counters_.frames_ignored;
    return;
  }
  prune();
  if (sessions_.size() >= limits_.max_sessions) {
    ++counters_.frames_ignored;
    return;
  }
  Session s;
  s.mode = TransportMode::kBam;
  s.pgn = get_pgn(f.data);
  s.peer = f.source;
  s.data.assign(size, 0);
  s.total_packets = total;
  s.window_end = total;
  s.state = State::kReceiving;
  s.deadline = now + kT1;
  sessions_.push_back(std::move(s));
}

void TransportProtocol::handle_cts(Session& s, const TransportFrame& f, bool extended, Nanoseconds now) {
  if (get_pgn(f.data) != s.pgn) {
    abort(s, AbortReason::kUnexpectedCtsPgn);
    return;
  }
  const std::uint32_t n = f.data[1];
  const std::uint32_t next = extended ? get24(f.data, 2) : f.data[2];
  if (n == 0) {
    // Hold (§5.10.2.4): the receiver renews it within Th; we wait up to T4 for the next CTS.
    s.state = State::kHeld;
    s.deadline = now + kT4;
    return;
  }
  if (next == 0 || next > s.total_packets || next + n - 1 > s.total_packets) {
    abort(s, AbortReason::kCtsPacketsBeyondMessage);
    return;
  }
  if (extended) {
    Bytes d = filled();
    d[0] = kEtpDpo;
    d[1] = static_cast<std::uint8_t>(n);
    put24(d, 2, next - 1);
    put_pgn(d, s.pgn);
    emit(kEtpConnectionManagementPgn, s.peer, d);
  }
  // The whole window goes out at once: the receiver granted exactly this many packets, and the CAN
  // controller arbitrates them frame by frame with everybody else's traffic.
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t absolute = next + i;
    send_packet(s, absolute, static_cast<std::uint8_t>(extended ? i + 1 : absolute));
  }
  s.next_packet = next + n;
  s.state = s.next_packet > s.total_packets ? State::kWaitEoma : State::kWaitCts;
  s.deadline = now + kT3;
}

void TransportProtocol::handle_dpo(Session& s, const TransportFrame& f, Nanoseconds now) {
  if (s.state != State::kWaitDpo) {
    abort(s, AbortReason::kUnexpectedDpo);
    return;
  }
  if (get_pgn(f.data) != s.pgn) {
    abort(s, AbortReason::kUnexpectedDpoPgn);
    return;
  }
  const std::uint32_t n = f.data[1];
  const std::uint32_t offset = get24(f.data, 2);
  if (n == 0 || n > s.window_end - s.next_packet + 1) {
    abort(s, AbortReason::kDpoPacketsAboveCts);
    return;
  }
  if (offset != s.next_packet - 1) {
    abort(s, AbortReason::kBadDpoOffset);
    return;
  }
  s.dpo_offset = offset;
  s.window_end = offset + n;  // a DPO may announce fewer packets than the CTS allowed
  s.state = State::kReceiving;
  s.deadline = now + kT1;
}

void TransportProtocol::handle_dt(const TransportFrame& f, bool extended, Nanoseconds now) {
  const bool bam = f.destination == 0xFF;
  Session* s = find(false, f.source, bam);
  const TransportMode mode = bam ? TransportMode::kBam : (extended ? TransportMode::kEtp : TransportMode::kTp);
  if (s == nullptr || s->mode != mode) {
    ++counters_.frames_ignored;  // no session: nothing to abort (the PGN is unknown)
    return;
  }
  if (s->state == State::kWaitDpo) {
    abort(*s, AbortReason::kUnexpectedDataPacket);
    return;
  }
  const std::uint8_t sequence = f.data[0];
  const std::uint32_t absolute = (mode == TransportMode::kEtp ? s->dpo_offset : 0) + sequence;
  if (sequence == 0) {
    abort(*s, AbortReason::kBadSequenceNumber);  // packet numbers start at 1
    return;
  }
  if (absolute < s->next_packet) {
    ++counters_.duplicates_ignored;
    return;
  }
  if (absolute > s->next_packet) {
    if (mode == TransportMode::kBam) {
      abort(*s, AbortReason::kBadSequenceNumber);  // lost packet: a BAM cannot be repaired
      return;
    }
    if (absolute > s->window_end) {
      abort(*s, AbortReason::kBadSequenceNumber);  // beyond the granted window: the sender ignored our CTS
      return;
    }
    // A packet after a gap is not kept (data is stored in order only). When the window's last packet
    // arrives, every packet of the window has been sent: ask again from the first missing one.
    if (absolute < s->window_end) return;
    if (s->retransmit_requests >= kMaxRetransmitRequests) {
      abort(*s, AbortReason::kRetransmitLimit);
      return;
    }
    ++s->retransmit_requests;
    ++counters_.retransmit_requests;
    send_cts(*s, s->next_packet, now);
    return;
  }
  const std::size_t offset = std::size_t{absolute - 1} * kBytesPerPacket;
  const std::size_t n = std::min(kBytesPerPacket, s->data.size() - offset);
  std::copy_n(f.data.begin() + 1, n, s->data.begin() + static_cast<std::ptrdiff_t>(offset));
  s->next_packet = absolute + 1;
  s->deadline = now + kT1;
  if (s->next_packet > s->total_packets) {
    complete_reception(*s);
  } else if (mode != TransportMode::kBam && absolute == s->window_end) {
    send_cts(*s, s->next_packet, now);
  }
}

void TransportProtocol::update(Nanoseconds now) {
  for (Session& s : sessions_) {
    if (s.done) continue;
    if (s.state == State::kSendBam) {
      if (now < s.deadline) continue;
      send_packet(s, s.next_packet, static_cast<std::uint8_t>(s.next_packet));
      ++s.next_packet;
      if (s.next_packet > s.total_packets) {
        ++counters_.messages_sent;
        end(s, TransportOutcome::kCompleted, AbortReason::kNone);
      } else {
        s.deadline = now + kBamPacketInterval;
      }
      continue;
    }
    if (now < s.deadline) continue;
    ++counters_.timeouts;
    if (s.mode != TransportMode::kBam) send_abort(s.peer, s.pgn, s.mode == TransportMode::kEtp, AbortReason::kTimeout);
    end(s, TransportOutcome::kTimedOut, AbortReason::kTimeout);
  }
  prune();
}

}  // namespace spread::isobus
