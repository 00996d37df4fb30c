#pragma once
// Frame-level I/O on a file descriptor carrying `struct can_frame` records: a SocketCAN CAN_RAW
// socket on a real bus, or one end of socketpair(AF_UNIX, SOCK_SEQPACKET) as a virtual bus in tests
// (both preserve record boundaries, so the same read/write/poll code serves both).
#include <linux/can.h>

#include <chrono>
#include <cstdint>

namespace spread::isobus::can {

enum class ReadOutcome {
  kFrame,       // one complete frame read
  kNothing,     // no frame pending
  kTruncated,   // a record shorter than struct can_frame (counted as malformed by the caller)
  kOversized,   // a record longer than struct can_frame (e.g. CAN FD): rest discarded
  kClosed,      // the peer closed the virtual bus
  kError,       // read error (errno kept in last_errno())
};

class CanFrameSink {
 public:
  virtual ~CanFrameSink() = default;
  virtual bool send(const can_frame& frame) = 0;
};

class CanFramePort final : public CanFrameSink {
 public:
  CanFramePort() = default;
  explicit CanFramePort(int fd);  // takes ownership; the fd is set non-blocking
  ~CanFramePort() override;
  CanFramePort(CanFramePort&& other) noexcept;
  CanFramePort& operator=(CanFramePort&& other) noexcept;
  CanFramePort(const CanFramePort&) = delete;
  CanFramePort& operator=(const CanFramePort&) = delete;

  bool is_open() const { return fd_ >= 0; }
  int fd() const { return fd_; }
  int last_errno() const { return last_errno_; }

  ReadOutcome read(can_frame& frame);
  bool send(const can_frame& frame) override;
  // Writes raw bytes as one record (tests use it to inject truncated frames).
  bool send_raw(const void* data, std::size_t size);
  // True when a record is ready within `timeout` (0: just check).
  bool wait_readable(std::chrono::nanoseconds timeout);

  std::uint64_t frames_read() const { return frames_read_; }
  std::uint64_t frames_written() const { return frames_written_; }

 private:
  void close_fd();
  int fd_ = -1;
  int last_errno_ = 0;
  std::uint64_t frames_read_ = 0;
  std::uint64_t frames_written_ = 0;
};

// Convenience: an extended-id data frame with 8 bytes.
can_frame make_frame(std::uint32_t id29, const std::uint8_t* data, std::uint8_t length);

}  // namespace spread::isobus::can
