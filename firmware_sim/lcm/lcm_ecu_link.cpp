#include "firmware_sim/lcm/lcm_ecu_link.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "lcm_link/lcm_payload.hpp"

namespace spread::firmware {
// The messages, their channels and their checked decoding are the link's (lcm_link/).
using namespace lcm_link;

namespace {

std::int64_t to_microseconds(Nanoseconds t) {
  return std::chrono::duration_cast<std::chrono::microseconds>(t).count();
}

std::int64_t count_of(const EcuStatus& s, Fault f) {
  return static_cast<std::int64_t>(s.fault_counts[static_cast<std::size_t>(f)]);
}

}  // namespace

EcuCommand to_ecu_command(const spread::command_t& m) {
  EcuCommand c;
  c.sequence = m.sequence;
  c.mode = m.mode;
  c.rate_setpoint_kg_ha = m.rate_setpoint_kg_ha;
  c.width_setpoint_m = m.width_setpoint_m;
  c.ground_speed_m_s = m.ground_speed_m_s;
  c.rpm_setpoint = m.rpm_setpoint;
  c.work_state = m.work_state;
  c.material = m.material;
  c.section_count = m.num_sections;
  const std::size_t n = std::min<std::size_t>({m.section_on.size(), static_cast<std::size_t>(kMaxSections),
                                               static_cast<std::size_t>(std::max<int>(m.num_sections, 0))});
  for (std::size_t i = 0; i < n; ++i) c.section_on[i] = m.section_on[i];
  c.border_mode = m.border_mode;
  c.border_gap_m = m.border_gap_m;
  c.wind_compensation = m.wind_compensation;
  c.wind_x_m_s = m.wind_m_s[0];
  c.wind_y_m_s = m.wind_m_s[1];
  return c;
}

LcmEcuLink::LcmEcuLink(lcm::LCM& lcm, Ecu& ecu, LcmChannels channels, std::string node_name)
    : lcm_(lcm), ecu_(ecu), channels_(std::move(channels)), node_name_(std::move(node_name)) {
  if (!lcm_.good()) throw std::runtime_error("LCM: the LCM instance could not be created (check the LCM URL)");
  subscription_ = lcm_.subscribe(channels_.command, &LcmEcuLink::on_command, this);
  if (subscription_ == nullptr) throw std::runtime_error("LCM: cannot subscribe to channel " + channels_.command);
  status_.num_fault_counts = static_cast<std::int8_t>(kFaultCount);
  status_.fault_counts.assign(kFaultCount, 0);
  status_.section_on.reserve(kMaxSections);
  status_.section_actual_on.reserve(kMaxSections);
  status_.material.reserve(64);
  heartbeat_.node = node_name_;
  encode_buffer_.resize(4096);
}

LcmEcuLink::~LcmEcuLink() {
  if (subscription_ != nullptr) lcm_.unsubscribe(subscription_);
}

void LcmEcuLink::on_command(const lcm::ReceiveBuffer* buffer, const std::string&) {
  ++counters_.commands_received;
  switch (decode_checked(buffer->data, buffer->data_size, command_)) {
    case DecodeOutcome::kWrongFingerprint:
      ecu_.record_fault(Fault::kLcmWrongFingerprint);
      return;
    case DecodeOutcome::kUndecodable:
      ecu_.record_fault(Fault::kLcmUndecodable);
      return;
    case DecodeOutcome::kDecoded:
      break;
  }
  if (!ecu_.apply_command(to_ecu_command(command_))) ++counters_.commands_accepted;
}

void LcmEcuLink::pump(Nanoseconds max_wait) {
  if (max_wait > Nanoseconds::zero()) {
    const auto ms = std::chrono::ceil<std::chrono::milliseconds>(max_wait).count();
    if (lcm_.handleTimeout(static_cast<int>(ms)) <= 0) return;
  }
  // Drain whatever else is already queued without waiting.
  while (lcm_.handleTimeout(0) > 0) {
  }
}

void LcmEcuLink::publish_encoded(const std::string& channel, int size) {
  if (size < 0 || lcm_.publish(channel, encode_buffer_.data(), static_cast<unsigned>(size)) != 0) {
    ++counters_.publish_failures;
  }
}

void LcmEcuLink::fill_status(const EcuStatus& s) {
  status_.timestamp_us = to_microseconds(s.time);
  status_.step = s.steps;
  status_.last_command_sequence = s.last_command_sequence;
  status_.mode = static_cast<std::int8_t>(s.mode);
  status_.material.assign(s.material.data(), s.material.size());
  status_.rpm_actual = s.rpm_actual;
  status_.rpm_target = s.rpm_target;
  status_.rate_setpoint_kg_ha = s.rate_setpoint_kg_ha;
  status_.rate_actual_kg_ha = s.rate_actual_kg_ha;
  status_.width_setpoint_m = s.width_setpoint_m;
  status_.width_actual_m = s.width_actual_m;
  status_.ground_speed_m_s = s.ground_speed_m_s;
  status_.mass_flow_kg_s = s.mass_flow_kg_s;
  status_.throw_width_m = s.throw_width_m;
  status_.effective_width_m = s.effective_width_m;
  status_.cv_percent = s.cv_percent;
  status_.throw_width_se_m = s.throw_width_se_m;
  status_.effective_width_se_m = s.effective_width_se_m;
  status_.cv_se_percent = s.cv_se_percent;
  status_.width_reachable = s.width_reachable;
  status_.work_state_setpoint = s.work_state_setpoint;
  status_.work_state_actual = s.work_state_actual;
  status_.num_sections = static_cast<std::int8_t>(s.section_count);
  status_.section_on.resize(static_cast<std::size_t>(s.section_count));  // within reserved capacity
  for (std::size_t i = 0; i < status_.section_on.size(); ++i) status_.section_on[i] = ((s.section_mask >> i) & 1u) != 0;
  status_.section_actual_on.resize(static_cast<std::size_t>(s.section_count));
  for (std::size_t i = 0; i < status_.section_actual_on.size(); ++i) {
    status_.section_actual_on[i] = ((s.section_actual_mask >> i) & 1u) != 0;
  }
  for (std::size_t d = 0; d < 2; ++d) {
    status_.disc_rpm_actual[d] = s.disc_rpm_actual[d];
    status_.disc_rpm_target[d] = s.disc_rpm_target[d];
    status_.disc_drop_point_turn_rad[d] = s.disc_drop_point_turn_rad[d];
    status_.disc_flow_fraction[d] = s.disc_flow_fraction[d];
  }
  status_.sides_pending = static_cast<std::int8_t>(s.sides_pending);
  status_.border_mode = static_cast<std::int8_t>(s.border_mode);
  status_.border_applied = s.border_applied;
  status_.wind_compensated = s.wind_compensated;
  status_.fault_codes = static_cast<std::int32_t>(s.fault_codes);
  status_.rejected_undecodable = count_of(s, Fault::kLcmUndecodable);
  status_.rejected_wrong_fingerprint = count_of(s, Fault::kLcmWrongFingerprint);
  status_.rejected_invalid = count_of(s, Fault::kNotANumber) + count_of(s, Fault::kSetpointOutOfRange) +
                             count_of(s, Fault::kUnknownMode) + count_of(s, Fault::kUnknownMaterial) +
                             count_of(s, Fault::kAutomaticUnavailable);
  status_.rejected_stale = count_of(s, Fault::kStaleSequence) + count_of(s, Fault::kSequenceJump);
  status_.can_malformed_frames = count_of(s, Fault::kCanMalformedFrame);
  status_.can_rejected_process_data = count_of(s, Fault::kCanUnknownDdi) +
                                      count_of(s, Fault::kCanUnsupportedCommand) +
                                      count_of(s, Fault::kCanNotSettable);
  for (std::size_t i = 0; i < kFaultCount; ++i) status_.fault_counts[i] = static_cast<std::int64_t>(s.fault_counts[i]);
}

void LcmEcuLink::after_step(const EcuStatus& s) {
  fill_status(s);
  const int size = status_.getEncodedSize();
  if (static_cast<std::size_t>(size) > encode_buffer_.size()) encode_buffer_.resize(static_cast<std::size_t>(size));
  publish_encoded(channels_.status, status_.encode(encode_buffer_.data(), 0, static_cast<int>(encode_buffer_.size())));
  ++counters_.statuses_published;

  if (!last_heartbeat_ || s.time - *last_heartbeat_ >= std::chrono::seconds(1)) {
    last_heartbeat_ = s.time;
    heartbeat_.timestamp_us = to_microseconds(s.time);
    heartbeat_.sequence = static_cast<std::int64_t>(counters_.heartbeats_published);
    heartbeat_.fault_codes = static_cast<std::int32_t>(s.fault_codes);
    if (loop_ != nullptr) {
      heartbeat_.loop_rate_mhz =
          static_cast<std::int32_t>(std::llround(1e12 / static_cast<double>(loop_->period().count())));
      heartbeat_.loop_ticks = loop_->statistics().ticks;
      heartbeat_.loop_overruns = loop_->statistics().overruns;
    }
    publish_encoded(channels_.heartbeat,
                    heartbeat_.encode(encode_buffer_.data(), 0, static_cast<int>(encode_buffer_.size())));
    ++counters_.heartbeats_published;
  }
}

}  // namespace spread::firmware
