#pragma once
// The timing and arbitration of one classical CAN bus, without I/O: spread-canbus offers each sender's
// next frame, and the pacer says which frame ends on the bus when. As on a real bus (CAN 2.0 Part B;
// ISO 11898-1): one frame at a time, each holding the bus for its bit count (can_frame_bits.hpp) at the
// bit rate; when the bus falls idle, the frames waiting then arbitrate and the lowest arbitration key
// (the lower identifier) goes next; a frame that becomes ready while the bus is busy waits for the end of
// the frame on the wire. Each sender has one transmit buffer, so its own frames keep their order.
// Frames tied on the key (two nodes with one identifier, which ISO 11783-5 addresses rule out) go by
// readiness, then by the order the senders were offered.
#include <linux/can.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <vector>

namespace spread::isobus::can {

inline constexpr std::uint32_t kIsobusBitRate = 250000;  // ISO 11783-2: 250 kbit/s

class CanBusPacer {
 public:
  using Nanoseconds = std::chrono::nanoseconds;

  struct Transmitted {
    can_frame frame{};
    std::uint64_t sender = 0;
    Nanoseconds start{};  // start of frame on the bus
    Nanoseconds end{};    // end of its intermission: the bus is free again
  };

  explicit CanBusPacer(std::uint32_t bit_rate = kIsobusBitRate);

  std::uint32_t bit_rate() const { return bit_rate_; }
  // How long `frame` holds the bus at this bit rate.
  Nanoseconds frame_time(const can_frame& frame) const;

  // `sender` has `frame` ready to send from `ready` on. At most one frame per sender: has_frame() first.
  void offer(std::uint64_t sender, const can_frame& frame, Nanoseconds ready);
  bool has_frame(std::uint64_t sender) const { return waiting_.count(sender) != 0; }
  // The sender left: its waiting frame is dropped (a frame already on the bus still ends normally).
  void withdraw(std::uint64_t sender) { waiting_.erase(sender); }
  std::size_t waiting() const { return waiting_.size(); }

  // Runs the bus up to `now`: returns the frames that ended by then, in bus order. Each time a sender's
  // frame wins arbitration, `on_sent(sender, start)` lets the caller offer that sender's next frame
  // (ready at `start`: it was queued behind), so that it contends when the bus is free again.
  std::vector<Transmitted> advance(Nanoseconds now,
                                   const std::function<void(std::uint64_t sender, Nanoseconds start)>& on_sent);
  // When the frame on the bus ends (nothing: the bus is idle).
  std::optional<Nanoseconds> next_end() const;
  // Bit times carried so far (frames that ended), for the bus load.
  std::uint64_t bits_carried() const { return bits_carried_; }

 private:
  struct Waiting {
    can_frame frame{};
    Nanoseconds ready{};
    std::uint64_t order = 0;
  };
  struct OnBus {
    Transmitted transmitted;
    int bits = 0;
  };
  std::uint32_t bit_rate_;
  std::map<std::uint64_t, Waiting> waiting_;
  std::optional<OnBus> on_bus_;
  Nanoseconds free_since_{};  // end of the last frame (the bus idle since then)
  std::uint64_t offers_ = 0;
  std::uint64_t bits_carried_ = 0;
};

}  // namespace spread::isobus::can
