#include "isobus/can/can_bus_pacer.hpp"

#include <algorithm>
#include <stdexcept>
#include <tuple>

#include "isobus/can/can_frame_bits.hpp"

namespace spread::isobus::can {

CanBusPacer::CanBusPacer(std::uint32_t bit_rate) : bit_rate_(bit_rate) {
  if (bit_rate_ == 0) throw std::invalid_argument("CAN bit rate must be above 0");
}

CanBusPacer::Nanoseconds CanBusPacer::frame_time(const can_frame& frame) const {
  return Nanoseconds(static_cast<std::int64_t>(can_frame_bit_count(frame)) * 1'000'000'000LL / bit_rate_);
}

void CanBusPacer::offer(std::uint64_t sender, const can_frame& frame, Nanoseconds ready) {
  waiting_[sender] = Waiting{frame, ready, offers_++};
}

std::optional<CanBusPacer::Nanoseconds> CanBusPacer::next_end() const {
  if (!on_bus_) return std::nullopt;
  return on_bus_->transmitted.end;
}

std::vector<CanBusPacer::Transmitted> CanBusPacer::advance(
    Nanoseconds now, const std::function<void(std::uint64_t, Nanoseconds)>& on_sent) {
  std::vector<Transmitted> ended;
  for (;;) {
    if (on_bus_) {
      if (now < on_bus_->transmitted.end) break;
      free_since_ = on_bus_->transmitted.end;
      bits_carried_ += static_cast<std::uint64_t>(on_bus_->bits);
      ended.push_back(on_bus_->transmitted);
      on_bus_.reset();
    }
    if (waiting_.empty()) break;
    // The bus starts its next frame when it is free and a frame is ready; the frames ready by then
    // arbitrate. (The caller may run late: frames that were ready while it slept still go back to back.)
    Nanoseconds start = waiting_.begin()->second.ready;
    for (const auto& [sender, w] : waiting_) start = std::min(start, w.ready);
    start = std::max(start, free_since_);
    if (start > now) break;
    auto winner = waiting_.end();
    for (auto it = waiting_.begin(); it != waiting_.end(); ++it) {
      if (it->second.ready > start) continue;
      const auto rank = [](const Waiting& w) {
        return std::make_tuple(can_arbitration_key(w.frame), w.ready, w.order);
      };
      if (winner == waiting_.end() || rank(it->second) < rank(winner->second)) winner = it;
    }
    const int bits = can_frame_bit_count(winner->second.frame);
    const Nanoseconds length(static_cast<std::int64_t>(bits) * 1'000'000'000LL / bit_rate_);
    on_bus_ = OnBus{Transmitted{winner->second.frame, winner->first, start, start + length}, bits};
    const std::uint64_t sender = winner->first;
    waiting_.erase(winner);
    if (on_sent) on_sent(sender, start);
  }
  return ended;
}

}  // namespace spread::isobus::can
