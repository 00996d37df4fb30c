#include "isobus/tc_client.hpp"

#include <algorithm>
#include <utility>

namespace spread::isobus {

const char* tc_client_state_name(TcClientState state) {
  switch (state) {
    case TcClientState::kWaitForTc: return "wait_for_tc";
    case TcClientState::kWaitVersion: return "wait_version";
    case TcClientState::kWaitStructureLabel: return "wait_structure_label";
    case TcClientState::kWaitLocalizationLabel: return "wait_localization_label";
    case TcClientState::kWaitTransferAnswer: return "wait_transfer_answer";
    case TcClientState::kWaitPoolAnswer: return "wait_pool_answer";
    case TcClientState::kWaitActivateAnswer: return "wait_activate_answer";
    case TcClientState::kWaitDeactivateAnswer: return "wait_deactivate_answer";
    case TcClientState::kConnected: return "connected";
    case TcClientState::kRetryWait: return "retry_wait";
  }
  return "unknown";
}

TaskControllerClient::TaskControllerClient(std::vector<std::uint8_t> pool, std::array<std::uint8_t, 7> structure_label,
                                           std::array<std::uint8_t, 7> localization_label, TcClientSettings settings,
                                           std::vector<std::uint8_t> pool_version3)
    : pool_(std::move(pool)),
      pool_version3_(std::move(pool_version3)),
      structure_label_(structure_label),
      localization_label_(localization_label),
      settings_(settings) {}

const std::vector<std::uint8_t>& TaskControllerClient::pool_for_tc() const {
  return tc_version_ < 4 && !pool_version3_.empty() ? pool_version3_ : pool_;
}

void TaskControllerClient::send(std::uint32_t pgn, std::uint8_t destination, std::span<const std::uint8_t> data) {
  out_.push_back(TcOutgoing{pgn, destination, std::vector<std::uint8_t>(data.begin(), data.end())});
}

std::vector<TcOutgoing> TaskControllerClient::take_outgoing() { return std::exchange(out_, {}); }

void TaskControllerClient::expect(TcClientState state, Nanoseconds now, Nanoseconds timeout) {
  state_ = state;
  deadline_ = now + timeout;
}

void TaskControllerClient::end_connection(std::string why, Nanoseconds now) {
  pool_change_pending_ = false;  // the next connection transfers the current pool anyway
  last_error_ = std::move(why);
  state_ = TcClientState::kRetryWait;
  deadline_ = now + settings_.retry_delay;
  tc_.reset();
}

void TaskControllerClient::drop(std::string why, Nanoseconds now) {
  if (tc_) end_connection(std::move(why), now);
}

void TaskControllerClient::restart(std::string why) {
  if (tc_ || state_ == TcClientState::kRetryWait) last_error_ = std::move(why);
  state_ = TcClientState::kWaitForTc;
  tc_.reset();
  out_.clear();
  pool_change_pending_ = false;  // messages of the old session, from an address we no longer hold
}

void TaskControllerClient::connect(std::uint8_t tc, Nanoseconds now) {
  if (state_ != TcClientState::kWaitForTc) return;
  // ISO 11783-10 (connection procedure): the working set names itself with the working-set master
  // message (one member, this ECU) before any other message to the TC, then asks the TC's version.
  tc_ = tc;
  last_tc_status_ = now;
  send(kWorkingSetMasterPgn, 0xFF, encode_working_set_master(1));
  send_tc(tc_frame(TcMessage::kRequestVersion));
  expect(TcClientState::kWaitVersion, now, settings_.answer_timeout);
}

void TaskControllerClient::replace_pool(std::vector<std::uint8_t> pool, std::array<std::uint8_t, 7> structure_label,
                                        std::array<std::uint8_t, 7> localization_label,
                                        std::vector<std::uint8_t> pool_version3, Nanoseconds now) {
  pool_ = std::move(pool);
  pool_version3_ = std::move(pool_version3);
  structure_label_ = structure_label;
  localization_label_ = localization_label;
  structure_known_ = false;  // a label compared before the change named the old pool
  switch (state_) {
    case TcClientState::kConnected:
      begin_pool_change(now);
      return;
    case TcClientState::kWaitTransferAnswer:
    case TcClientState::kWaitPoolAnswer:
    case TcClientState::kWaitActivateAnswer:
    case TcClientState::kWaitDeactivateAnswer:
      pool_change_pending_ = true;  // the old pool is on its way: change it once it is active
      return;
    default:
      return;  // not yet as far as the pool: the connection takes the new one
  }
}

void TaskControllerClient::begin_pool_change(Nanoseconds now) {
  // ISO 11783-10 (change of the device descriptor): the client deactivates its pool, transfers the new one
  // and activates it; the TC then knows the machine by the new pool's structure label and geometry.
  pool_change_pending_ = false;
  ++pool_changes_;
  send_tc(encode_activate(false));
  expect(TcClientState::kWaitDeactivateAnswer, now, settings_.answer_timeout);
}

void TaskControllerClient::handle_message(std::uint8_t source, std::span<const std::uint8_t> data, Nanoseconds now) {
  const auto kind = tc_message_kind(data);
  if (!kind) return;
  if (*kind == TcMessage::kTcStatus) {
    if (state_ == TcClientState::kWaitForTc) {
      connect(source, now);  // a TC is there
    } else if (tc_ && source == *tc_) {
      last_tc_status_ = now;
    }
    return;
  }
  if (!tc_ || source != *tc_) return;  // only the TC we are connecting to
  if (data.size() < 8 && *kind != TcMessage::kPoolTransfer) return;  // single-frame messages have 8 bytes
  switch (*kind) {
    case TcMessage::kRequestVersion: {
      // The TC asks our capabilities: answered in any state (ISO 11783-10 technical capabilities).
      send_tc(encode_version(settings_.version));
      return;
    }
    case TcMessage::kVersion:
      if (state_ != TcClientState::kWaitVersion) return;
      tc_version_ = data[1];
      send_tc(tc_frame(TcMessage::kRequestStructureLabel));
      expect(TcClientState::kWaitStructureLabel, now, settings_.answer_timeout);
      return;
    case TcMessage::kStructureLabel:
      if (state_ != TcClientState::kWaitStructureLabel) return;
      structure_known_ = std::equal(structure_label_.begin(), structure_label_.end(), data.begin() + 1);
      send_tc(tc_frame(TcMessage::kRequestLocalizationLabel));
      expect(TcClientState::kWaitLocalizationLabel, now, settings_.answer_timeout);
      return;
    case TcMessage::kLocalizationLabel: {
      if (state_ != TcClientState::kWaitLocalizationLabel) return;
      // A pool the TC holds under both our labels is activated as it is; anything else is sent again
      // (a changed language or unit system changes the pool's designators and presentations).
      const bool known =
          structure_known_ && std::equal(localization_label_.begin(), localization_label_.end(), data.begin() + 1);
      if (known) {
        send_tc(encode_activate(true));
        expect(TcClientState::kWaitActivateAnswer, now, settings_.answer_timeout);
      } else {
        send_tc(encode_request_pool_transfer(static_cast<std::uint32_t>(pool_for_tc().size())));
        expect(TcClientState::kWaitTransferAnswer, now, settings_.answer_timeout);
      }
      return;
    }
    case TcMessage::kRequestPoolTransferResponse:
      if (state_ != TcClientState::kWaitTransferAnswer) return;
      if (data[1] != 0) {
        end_connection("the TC has no room for the " + std::to_string(pool_for_tc().size()) + "-byte pool", now);
        return;
      }
      {
        const std::vector<std::uint8_t> message = encode_pool_transfer(pool_for_tc());
        send(0xCB00, *tc_, message);
      }
      // The transfer itself takes time on a loaded bus (TP windows of 7-byte packets).
      expect(TcClientState::kWaitPoolAnswer, now, 5 * settings_.answer_timeout);
      return;
    case TcMessage::kPoolTransferResponse:
      if (state_ != TcClientState::kWaitPoolAnswer) return;
      if (data[1] != 0) {
        end_connection("the TC refused the pool (error bits " + std::to_string(data[1]) + ")", now);
        return;
      }
      send_tc(encode_activate(true));
      expect(TcClientState::kWaitActivateAnswer, now, settings_.answer_timeout);
      return;
    case TcMessage::kActivatePoolResponse:
      if (state_ == TcClientState::kWaitDeactivateAnswer) {
        if (data[1] != 0) {
          end_connection("the TC could not deactivate the pool (error bits " + std::to_string(data[1]) + ")", now);
          return;
        }
        send_tc(encode_request_pool_transfer(static_cast<std::uint32_t>(pool_for_tc().size())));
        expect(TcClientState::kWaitTransferAnswer, now, settings_.answer_timeout);
        return;
      }
      if (state_ != TcClientState::kWaitActivateAnswer) return;
      if (data[1] != 0) {
        end_connection("the TC could not activate the pool (error bits " + std::to_string(data[1]) +
                           ", object " + std::to_string(data[4] | (data[5] << 8)) + ")",
                       now);
        return;
      }
      state_ = TcClientState::kConnected;
      ++connections_;
      last_error_.clear();
      next_client_task_ = now;  // the first client task message goes out with the next update
      if (pool_change_pending_) begin_pool_change(now);
      return;
    default:
      return;
  }
}

void TaskControllerClient::update(Nanoseconds now) {
  switch (state_) {
    case TcClientState::kWaitForTc:
      return;
    case TcClientState::kRetryWait:
      if (now >= deadline_) state_ = TcClientState::kWaitForTc;
      return;
    case TcClientState::kConnected:
      if (now - last_tc_status_ > kTcPartnerTimeout) {
        end_connection("the TC status stopped", now);
        return;
      }
      if (now >= next_client_task_) {
        send_tc(encode_client_task(true));
        next_client_task_ = now + kTcStatusInterval;
      }
      return;
    default:
      if (now - last_tc_status_ > kTcPartnerTimeout) {
        end_connection("the TC status stopped", now);
      } else if (now > deadline_) {
        end_connection(std::string("no answer from the TC in state ") + tc_client_state_name(state_), now);
      }
      return;
  }
}

}  // namespace spread::isobus
