#include "isobus/tc_server.hpp"

#include <algorithm>
#include <cstdio>
#include <unordered_map>

#include "isobus/process_data.hpp"

namespace spread::isobus {
namespace {

std::string hex8(std::uint8_t v) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "0x%02X", v);
  return buf;
}

bool is_transport_pgn(std::uint32_t pgn) {
  return pgn == kTpConnectionManagementPgn || pgn == kTpDataTransferPgn || pgn == kEtpConnectionManagementPgn ||
         pgn == kEtpDataTransferPgn;
}

constexpr std::array<std::uint8_t, 7> kNoLabel{0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF};

}  // namespace

const char* tc_connection_state_name(TcConnectionState state) {
  switch (state) {
    case TcConnectionState::kNone: return "no client";
    case TcConnectionState::kConnecting: return "connecting";
    case TcConnectionState::kPoolReceiving: return "receiving pool";
    case TcConnectionState::kActive: return "active";
    case TcConnectionState::kDeactivated: return "deactivated";
  }
  return "?";
}

TcServer::TcServer(TcServerConfig config)
    // The pool transfer message is the pool plus its sub-command byte; anything larger is refused by the
    // transport already (abort reason 2), before it fills memory.
    : config_(config), transport_(0xFE, TransportLimits{config.max_pool_bytes + 1, 8, 16}) {}

void TcServer::start(std::uint8_t address, Nanoseconds now) {
  started_ = true;
  set_address(address);
  next_status_ = now;
  update(now);
}

void TcServer::set_address(std::uint8_t address) {
  if (started_ && address != address_ && client_) {
    // The client connected to the address we held: its partner is gone (ISO 11783-5: our NAME now claims
    // another address), and it connects again from its working-set master message.
    drop_client("our address changed from " + hex8(address_) + " to " + hex8(address));
  }
  address_ = address;
  transport_.set_address(address);
}

void TcServer::drop_client(const std::string& why) {
  event("client " + hex8(*client_) + " disconnected: " + why + "; its pool kept");
  client_.reset();
  client_name_.reset();
  client_version_.reset();
  state_ = TcConnectionState::kNone;
}

void TcServer::on_address_claimed(std::uint8_t source, std::uint64_t name) {
  if (source < 0xFE) names_[source] = name;
  if (!client_) return;
  // ISO 11783-5: an address belongs to the NAME that last claimed it, and ISO 11783-10 knows a client by
  // its NAME. Another NAME at the client's address has replaced it; the client's NAME at another address
  // (or unable to claim one) has left the address its session runs on. Either way the session ends, and
  // the working set connects again from its working-set master message.
  if (source == *client_ && client_name_ && name != *client_name_) {
    drop_client("another NAME claimed its address");
  } else if (client_name_ && name == *client_name_ && source != *client_) {
    drop_client(source == 0xFE ? "it cannot claim an address" : "it moved to " + hex8(source));
  }
}

void TcServer::handle_frame(std::uint32_t pgn, std::uint8_t source, std::uint8_t destination,
                            std::span<const std::uint8_t> data, Nanoseconds now) {
  if (!started_ || source == address_) return;
  const bool for_us = destination == address_ || destination == 0xFF;
  // Any traffic from the client while it connects proves it alive: a pool transfer of a few hundred
  // packets must not make it look silent (the client task message only starts once it is connected).
  if (client_ && *client_ == source && state_ != TcConnectionState::kActive) client_seen_ = now;

  if (is_transport_pgn(pgn)) {
    if (!for_us) return;
    if (data.size() != 8) {
      ++counters_.malformed_frames;
      event("malformed transport frame from " + hex8(source) + ": " + std::to_string(data.size()) +
            " bytes instead of 8");
      return;
    }
    TransportFrame f;
    f.pgn = pgn;
    f.source = source;
    f.destination = destination;
    std::copy(data.begin(), data.end(), f.data.begin());
    transport_.handle_frame(f, now);
    // The transport's own answers first: a message is the receiver's once its session ended with the
    // end-of-message acknowledgement (ISO 11783-3 §5.10.3.3, ISO 11783-6 ETP), and the sender takes no
    // answer to the message before it (ISO 11783-10: the object-pool transfer response follows the
    // transfer).
    for (const TransportFrame& t : transport_.take_frames()) out_.push_back(t);
    for (TransportMessage& m : transport_.take_received()) {
      if (m.pgn != kTcProcessDataPgn) continue;
      if (!m.data.empty() && m.data[0] == static_cast<std::uint8_t>(TcMessage::kPoolTransfer)) {
        if (!client_ || *client_ != m.source) {
          ++counters_.other_clients_ignored;
          event("pool transfer from " + hex8(m.source) + ", which is not the connected client: ignored");
          continue;
        }
        handle_pool(m.source, std::span<const std::uint8_t>(m.data).subspan(1));
      } else {
        event("transported PGN 0xCB00 message from " + hex8(m.source) + " is not a pool transfer: ignored");
      }
    }
    update(now);
    return;
  }

  if (pgn == kWorkingSetMasterPgn) {
    // ISO 11783-7 / -1: the working-set master announces its working set before it talks to the TC.
    if (data.size() != 8) {
      ++counters_.malformed_frames;
      event("malformed working-set master message from " + hex8(source));
      return;
    }
    if (client_ && *client_ == source && state_ != TcConnectionState::kConnecting &&
        state_ != TcConnectionState::kPoolReceiving) {
      // The working set names itself again: it starts its connection over (its address changed, or it
      // lost us), and the set-points of the old session are void until its pool is active again.
      event("client " + hex8(source) + " connects again");
      client_version_.reset();
      state_ = TcConnectionState::kConnecting;
      client_seen_ = now;
      return;
    }
    accept_client(source, now);
    return;
  }

  if (pgn != kTcProcessDataPgn || destination != address_) return;
  if (data.size() != 8) {
    ++counters_.malformed_frames;
    event("malformed process data frame from " + hex8(source) + ": " + std::to_string(data.size()) +
          " bytes instead of 8");
    return;
  }
  const std::uint8_t command = data[0] & 0x0F;
  switch (command) {
    case 0x0: case 0x1: case 0xF:
      handle_tc_message(source, data, now);
      break;
    case 0x3: case 0xD:
      handle_process_data(source, data, now);
      break;
    default:
      // Set-values, measurement commands and peer control go from the TC to clients, not back.
      ++counters_.malformed_frames;
      event("process data command " + std::to_string(command) + " from " + hex8(source) + " not expected by a TC");
      break;
  }
}

bool TcServer::accept_client(std::uint8_t source, Nanoseconds now) {
  if (client_ && *client_ == source) return true;
  if (client_) {
    ++counters_.other_clients_ignored;
    event("second client " + hex8(source) + " ignored: this TC serves one working set (" + hex8(*client_) + ")");
    return false;
  }
  client_ = source;
  client_name_ = source < 0xFE ? names_[source] : std::nullopt;
  client_version_.reset();
  state_ = TcConnectionState::kConnecting;
  client_seen_ = now;
  event("client " + hex8(source) + " connecting");
  return true;
}

void TcServer::handle_tc_message(std::uint8_t source, std::span<const std::uint8_t> data, Nanoseconds now) {
  const auto kind = tc_message_kind(data);
  if (!kind) {
    ++counters_.malformed_frames;
    event("unsupported TC message " + hex8(data[0]) + " from " + hex8(source) + ": ignored");
    return;
  }
  if (*kind == TcMessage::kClientTask) {
    // ISO 11783-10: the client task message every 2 s is what keeps a connected client alive.
    if (client_ && *client_ == source) client_seen_ = now;
    return;
  }
  if (!accept_client(source, now)) return;
  switch (*kind) {
    case TcMessage::kRequestVersion:
      send_to_client(encode_version(config_.version));
      // The TC learns the client's capabilities too (ISO 11783-10 technical capabilities: both sides ask).
      if (!client_version_) send_to_client(tc_frame(TcMessage::kRequestVersion));
      break;
    case TcMessage::kVersion:
      client_version_ = decode_version(data);
      event("client " + hex8(source) + " version " + std::to_string(client_version_->version) + ", " +
            std::to_string(client_version_->booms) + " boom(s), " + std::to_string(client_version_->sections) +
            " section(s)");
      break;
    case TcMessage::kRequestStructureLabel:
    case TcMessage::kRequestLocalizationLabel: {
      // All 0xFF: no pool held, the client must transfer one (ISO 11783-10 device descriptor: the
      // structure label names a stored pool). A held pool's label lets a client that reconnects with the
      // same pool go straight to activation.
      const bool structure = *kind == TcMessage::kRequestStructureLabel;
      std::array<std::uint8_t, 7> label = kNoLabel;
      if (pool_) {
        for (const DdopObject& o : pool_->objects) {
          if (const auto* d = std::get_if<DeviceObject>(&o)) {
            label = structure ? d->structure_label : d->localization_label;
          }
        }
      }
      send_to_client(encode_label(structure ? TcMessage::kStructureLabel : TcMessage::kLocalizationLabel, label));
      break;
    }
    case TcMessage::kRequestPoolTransfer: {
      const std::uint32_t size = std::uint32_t{data[1]} | (std::uint32_t{data[2]} << 8) |
                                 (std::uint32_t{data[3]} << 16) | (std::uint32_t{data[4]} << 24);
      const bool fits = size <= config_.max_pool_bytes;
      send_to_client(encode_error_answer(TcMessage::kRequestPoolTransferResponse, fits ? 0 : 1));
      if (fits) {
        granted_pool_bytes_ = size;
        state_ = TcConnectionState::kPoolReceiving;
      } else {
        event("pool transfer of " + std::to_string(size) + " bytes refused: this TC takes at most " +
              std::to_string(config_.max_pool_bytes));
      }
      break;
    }
    case TcMessage::kPoolTransfer:
      // Only a pool of 7 bytes or fewer fits one frame, and none that small is valid; parse_ddop says why.
      handle_pool(source, data.subspan(1));
      break;
    case TcMessage::kActivatePool: {
      if (data[1] == 0x00) {
        send_to_client(encode_error_answer(TcMessage::kActivatePoolResponse, 0));
        state_ = TcConnectionState::kDeactivated;
        event("client " + hex8(source) + " deactivated its pool");
      } else if (data[1] != 0xFF) {
        ++counters_.malformed_frames;
        event("activate message with byte 1 = " + hex8(data[1]) + " (neither 0x00 nor 0xFF): ignored");
      } else if (!pool_) {
        // Error bit 0: no valid pool to activate (never received, or refused).
        send_to_client(encode_error_answer(TcMessage::kActivatePoolResponse, 0x01));
        event("activation refused: no valid pool held for client " + hex8(source));
      } else {
        send_to_client(encode_error_answer(TcMessage::kActivatePoolResponse, 0));
        state_ = TcConnectionState::kActive;
        client_seen_ = now;  // from here the client task message is supervised
        event("pool of client " + hex8(source) + " activated: " + std::to_string(section_elements_.size()) +
              " section(s)");
      }
      break;
    }
    default:
      // Answers only a TC sends (version answer aside) coming from a client: nothing to do.
      ++counters_.malformed_frames;
      event("TC message " + hex8(data[0]) + " from client " + hex8(source) + " is one a TC sends: ignored");
      break;
  }
}

void TcServer::handle_pool(std::uint8_t source, std::span<const std::uint8_t> pool_bytes) {
  TcFrame answer = tc_frame(TcMessage::kPoolTransferResponse);
  const auto size = static_cast<std::uint32_t>(pool_bytes.size());
  for (int i = 0; i < 4; ++i) answer[static_cast<std::size_t>(2 + i)] = static_cast<std::uint8_t>(size >> (8 * i));
  if (state_ != TcConnectionState::kPoolReceiving) {
    event("pool from " + hex8(source) + " arrived without a granted transfer request; parsing it anyway");
  } else if (size != granted_pool_bytes_) {
    event("pool from " + hex8(source) + " has " + std::to_string(size) + " bytes, " +
          std::to_string(granted_pool_bytes_) + " were announced");
  }
  state_ = TcConnectionState::kConnecting;
  // A new pool replaces the held one whether or not it parses: a refused pool cannot be activated.
  pool_.reset();
  ddi_elements_.clear();
  ddi_triggers_.clear();
  section_elements_.clear();
  if (size > config_.max_pool_bytes) {
    answer[1] = 0x02;  // bit 1: not enough memory
    ++counters_.pools_refused;
    event("pool from " + hex8(source) + " refused: " + std::to_string(size) + " bytes exceed the limit");
    send_to_client(answer);
    return;
  }
  // The client writes its pool for the lower of the two versions (version 4 adds the DVC's extended
  // structure label); a client that never answered our version request is taken as version 4.
  const std::uint8_t version =
      std::min(config_.version.version, client_version_ ? client_version_->version : std::uint8_t{4});
  DdopParseResult parsed = parse_ddop(pool_bytes, version);
  if (!parsed.pool) {
    answer[1] = 0x01;  // bit 0: error in the pool (ISO 11783-10 object-pool transfer response)
    ++counters_.pools_refused;
    event("pool from " + hex8(source) + " refused: " + parsed.error);
    send_to_client(answer);
    return;
  }
  pool_ = std::move(parsed.pool);
  index_pool();
  ++counters_.pools_accepted;
  answer[1] = 0x00;
  std::string label;
  for (const DdopObject& o : pool_->objects) {
    if (const auto* d = std::get_if<DeviceObject>(&o)) label = label_hex(d->structure_label);
  }
  event("pool from " + hex8(source) + " accepted: " + std::to_string(size) + " bytes, " +
        std::to_string(pool_->objects.size()) + " objects, " + std::to_string(section_elements_.size()) +
        " section(s), structure label " + label);
  send_to_client(answer);
}

void TcServer::index_pool() {
  ddi_elements_.clear();
  ddi_triggers_.clear();
  section_elements_.clear();
  std::unordered_map<std::uint16_t, const DdopObject*> by_id;
  for (const DdopObject& o : pool_->objects) by_id[object_id(o)] = &o;
  for (const DdopObject& o : pool_->objects) {
    const auto* e = std::get_if<DeviceElement>(&o);
    if (!e) continue;
    if (e->type == ElementType::kSection) section_elements_.push_back(e->element_number);
    for (const std::uint16_t child : e->children) {
      const auto it = by_id.find(child);
      if (it == by_id.end()) continue;
      if (const auto* p = std::get_if<DeviceProcessData>(it->second)) {
        ddi_elements_[p->ddi].push_back(e->element_number);
        ddi_triggers_[p->ddi] |= p->triggers;
      }
    }
  }
  std::sort(section_elements_.begin(), section_elements_.end());
  for (auto& [ddi, elements] : ddi_elements_) std::sort(elements.begin(), elements.end());
}

void TcServer::handle_process_data(std::uint8_t source, std::span<const std::uint8_t> data, Nanoseconds now) {
  if (!client_ || *client_ != source) {
    ++counters_.other_clients_ignored;
    return;
  }
  ProcessDataBytes bytes{};
  std::copy(data.begin(), data.end(), bytes.begin());
  if ((data[0] & 0x0F) == 0xD) {
    ++counters_.pdacks_received;
    const auto ack = decode_pdack(bytes);
    if (ack && ack->error_bits != 0) {
      ++counters_.pdack_errors;
      event("client " + hex8(source) + " refused command " + std::to_string(ack->acknowledged_command) +
            " on element " + std::to_string(ack->element) + " DDI " + std::to_string(ack->ddi) + ": error bits " +
            hex8(ack->error_bits));
    }
    return;
  }
  const ProcessData pd = decode_process_data(bytes);
  as_applied_.push_back({now, source, pd.element, pd.ddi, pd.value});
  ++counters_.values_logged;
}

void TcServer::update(Nanoseconds now) {
  if (!started_) return;
  transport_.update(now);
  for (const TransportSessionEnd& e : transport_.take_ended()) {
    if (e.outcome == TransportOutcome::kCompleted) continue;
    event(std::string("transport session ") + (e.sending ? "to " : "from ") + hex8(e.peer) + " ended " +
          (e.outcome == TransportOutcome::kTimedOut ? "by timeout" : "by abort") + " (reason " +
          std::to_string(static_cast<int>(e.reason)) + ")");
  }
  for (const TransportFrame& f : transport_.take_frames()) out_.push_back(f);
  if (now >= next_status_) {
    send_status(now);
    // Keep the 2 s grid; after a long stall start a new one rather than sending a burst.
    next_status_ += kTcStatusInterval;
    if (next_status_ <= now) next_status_ = now + kTcStatusInterval;
  }
  if (client_ && now - client_seen_ > kTcPartnerTimeout) {
    ++counters_.client_timeouts;
    event("client " + hex8(*client_) + " silent for " + std::to_string(kTcPartnerTimeout.count()) + " s (" +
          (state_ == TcConnectionState::kActive ? "no client task message" : "connection stalled") +
          "): disconnected, its pool kept");
    client_.reset();
    client_version_.reset();
    state_ = TcConnectionState::kNone;
  }
}

void TcServer::send_status(Nanoseconds) {
  TransportFrame f;
  f.priority = kTcMessagePriority;
  f.pgn = kTcProcessDataPgn;
  f.source = address_;
  f.destination = 0xFF;
  f.data = encode_tc_status(config_.task_active);
  out_.push_back(f);
  ++counters_.status_sent;
}

void TcServer::send_to_client(const TcFrame& frame) {
  if (!client_) return;
  TransportFrame f;
  f.priority = kTcMessagePriority;
  f.pgn = kTcProcessDataPgn;
  f.source = address_;
  f.destination = *client_;
  f.data = frame;
  out_.push_back(f);
}

std::vector<std::uint16_t> TcServer::elements_for_ddi(std::uint16_t ddi) const {
  const auto it = ddi_elements_.find(ddi);
  return it == ddi_elements_.end() ? std::vector<std::uint16_t>{} : it->second;
}

std::string TcServer::send_process_data(std::uint8_t command, std::uint16_t element, std::uint16_t ddi,
                                        std::int32_t value) {
  if (!active()) return std::string("no active client (") + tc_connection_state_name(state_) + ")";
  if (element > 0x0FFF) return "element " + std::to_string(element) + " does not fit 12 bits";
  TransportFrame f;
  f.priority = kProcessDataPriority;
  f.pgn = kTcProcessDataPgn;
  f.source = address_;
  f.destination = *client_;
  f.data = encode_process_data({command, element, ddi, value});
  out_.push_back(f);
  return "";
}

std::string TcServer::set_value(std::uint16_t ddi, std::int32_t value) {
  const auto elements = elements_for_ddi(ddi);
  if (active() && elements.empty()) return "the client's pool has no process data with DDI " + std::to_string(ddi);
  return send_process_data(static_cast<std::uint8_t>(ProcessDataCommand::kValue),
                           elements.empty() ? 0 : elements.front(), ddi, value);
}

std::string TcServer::request_value(std::uint16_t ddi) {
  const auto elements = elements_for_ddi(ddi);
  if (active() && elements.empty()) return "the client's pool has no process data with DDI " + std::to_string(ddi);
  return send_process_data(static_cast<std::uint8_t>(ProcessDataCommand::kRequestValue),
                           elements.empty() ? 0 : elements.front(), ddi, 0);
}

std::string TcServer::set_value(std::uint16_t element, std::uint16_t ddi, std::int32_t value) {
  return send_process_data(static_cast<std::uint8_t>(ProcessDataCommand::kValue), element, ddi, value);
}

std::string TcServer::request_value(std::uint16_t element, std::uint16_t ddi) {
  return send_process_data(static_cast<std::uint8_t>(ProcessDataCommand::kRequestValue), element, ddi, 0);
}

std::uint8_t TcServer::triggers_for_ddi(std::uint16_t ddi) const {
  const auto it = ddi_triggers_.find(ddi);
  return it == ddi_triggers_.end() ? 0 : it->second;
}

std::string TcServer::measure(std::uint16_t ddi, MeasurementCommand command, std::int32_t value) {
  if (!active()) return std::string("no active client (") + tc_connection_state_name(state_) + ")";
  const auto elements = elements_for_ddi(ddi);
  if (elements.empty()) return "the client's pool has no process data with DDI " + std::to_string(ddi);
  // ISO 11783-10: a TC uses only the trigger methods the DPD lists as available.
  std::uint8_t needed = 0;
  switch (command) {
    case MeasurementCommand::kTimeInterval: needed = kTriggerTimeInterval; break;
    case MeasurementCommand::kDistanceInterval: needed = kTriggerDistanceInterval; break;
    case MeasurementCommand::kMinimumThreshold:
    case MeasurementCommand::kMaximumThreshold: needed = kTriggerThresholdLimits; break;
    case MeasurementCommand::kChangeThreshold: needed = kTriggerOnChange; break;
  }
  if ((triggers_for_ddi(ddi) & needed) == 0) {
    return "the pool offers no such trigger for DDI " + std::to_string(ddi) + " (available: " +
           hex8(triggers_for_ddi(ddi)) + ")";
  }
  return send_process_data(static_cast<std::uint8_t>(command), elements.front(), ddi, value);
}

}  // namespace spread::isobus
