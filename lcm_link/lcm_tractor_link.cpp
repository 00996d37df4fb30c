#include "lcm_link/lcm_tractor_link.hpp"

#include <chrono>
#include <stdexcept>

#include "lcm_link/lcm_payload.hpp"

namespace spread::lcm_link {

LcmTractorLink::LcmTractorLink(lcm::LCM& lcm, LcmChannels channels) : lcm_(lcm), channels_(std::move(channels)) {
  if (!lcm_.good()) throw std::runtime_error("LCM: the LCM instance could not be created (check the LCM URL)");
  status_subscription_ = lcm_.subscribe(channels_.status, &LcmTractorLink::on_status_payload, this);
  heartbeat_subscription_ = lcm_.subscribe(channels_.heartbeat, &LcmTractorLink::on_heartbeat_payload, this);
  if (status_subscription_ == nullptr || heartbeat_subscription_ == nullptr) {
    throw std::runtime_error("LCM: cannot subscribe to " + channels_.status + " / " + channels_.heartbeat);
  }
}

LcmTractorLink::~LcmTractorLink() {
  if (status_subscription_ != nullptr) lcm_.unsubscribe(status_subscription_);
  if (heartbeat_subscription_ != nullptr) lcm_.unsubscribe(heartbeat_subscription_);
}

bool LcmTractorLink::send(const spread::command_t& command) {
  return lcm_.publish(channels_.command, &command) == 0;
}

bool LcmTractorLink::send_raw(const void* data, unsigned size) {
  return lcm_.publish(channels_.command, data, size) == 0;
}

void LcmTractorLink::on_status_payload(const lcm::ReceiveBuffer* buffer, const std::string&) {
  spread::status_t message;
  if (decode_checked(buffer->data, buffer->data_size, message) != DecodeOutcome::kDecoded) {
    ++undecodable_;
    return;
  }
  ++statuses_;
  latest_status_ = std::move(message);
  if (on_status) on_status(*latest_status_);
}

void LcmTractorLink::on_heartbeat_payload(const lcm::ReceiveBuffer* buffer, const std::string&) {
  spread::heartbeat_t message;
  if (decode_checked(buffer->data, buffer->data_size, message) != DecodeOutcome::kDecoded) {
    ++undecodable_;
    return;
  }
  ++heartbeats_;
  latest_heartbeat_ = std::move(message);
  if (on_heartbeat) on_heartbeat(*latest_heartbeat_);
}

int LcmTractorLink::handle(Nanoseconds timeout) {
  int handled = 0;
  const auto ms = std::chrono::ceil<std::chrono::milliseconds>(timeout).count();
  if (lcm_.handleTimeout(static_cast<int>(ms < 0 ? 0 : ms)) > 0) {
    ++handled;
    while (lcm_.handleTimeout(0) > 0) ++handled;
  }
  return handled;
}

bool LcmTractorLink::wait_for(const std::function<bool()>& predicate, Nanoseconds timeout) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (!predicate()) {
    const auto now = std::chrono::steady_clock::now();
    if (now >= end) return false;
    handle(std::min<Nanoseconds>(end - now, std::chrono::milliseconds(50)));
  }
  return true;
}

}  // namespace spread::lcm_link
