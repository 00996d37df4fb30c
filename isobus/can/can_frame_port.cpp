#include "isobus/can/can_frame_port.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

namespace spread::isobus::can {

CanFramePort::CanFramePort(int fd) : fd_(fd) {
  if (fd_ >= 0) {
    const int flags = ::fcntl(fd_, F_GETFL, 0);
    if (flags >= 0) ::fcntl(fd_, F_SETFL, flags | O_NONBLOCK);
  }
}

CanFramePort::~CanFramePort() { close_fd(); }

CanFramePort::CanFramePort(CanFramePort&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)),
      last_errno_(other.last_errno_),
      frames_read_(other.frames_read_),
      frames_written_(other.frames_written_) {}

CanFramePort& CanFramePort::operator=(CanFramePort&& other) noexcept {
  if (this != &other) {
    close_fd();
    fd_ = std::exchange(other.fd_, -1);
    last_errno_ = other.last_errno_;
    frames_read_ = other.frames_read_;
    frames_written_ = other.frames_written_;
  }
  return *this;
}

void CanFramePort::close_fd() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

ReadOutcome CanFramePort::read(can_frame& frame) {
  if (fd_ < 0) return ReadOutcome::kClosed;
  // One byte more than a frame: a longer record shows up as MSG_TRUNC instead of passing as valid.
  unsigned char buffer[sizeof(can_frame) + 1];
  const ssize_t n = ::recv(fd_, buffer, sizeof(buffer), MSG_DONTWAIT | MSG_TRUNC);
  if (n < 0) {
    if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) return ReadOutcome::kNothing;
    last_errno_ = errno;
    return ReadOutcome::kError;
  }
  if (n == 0) return ReadOutcome::kClosed;
  if (static_cast<std::size_t>(n) < sizeof(can_frame)) return ReadOutcome::kTruncated;
  if (static_cast<std::size_t>(n) > sizeof(can_frame)) return ReadOutcome::kOversized;
  std::memcpy(&frame, buffer, sizeof(can_frame));
  ++frames_read_;
  return ReadOutcome::kFrame;
}

bool CanFramePort::send(const can_frame& frame) {
  if (!send_raw(&frame, sizeof(frame))) return false;
  ++frames_written_;
  return true;
}

bool CanFramePort::send_raw(const void* data, std::size_t size) {
  if (fd_ < 0) return false;
  // MSG_NOSIGNAL: a closed virtual-bus peer must not kill the process with SIGPIPE.
  const ssize_t n = ::send(fd_, data, size, MSG_DONTWAIT | MSG_NOSIGNAL);
  if (n < 0) {
    last_errno_ = errno;
    return false;
  }
  return static_cast<std::size_t>(n) == size;
}

bool CanFramePort::wait_readable(std::chrono::nanoseconds timeout) {
  if (fd_ < 0) return false;
  pollfd p{fd_, POLLIN, 0};
  const auto ms = std::chrono::ceil<std::chrono::milliseconds>(timeout).count();
  const int r = ::poll(&p, 1, static_cast<int>(ms < 0 ? 0 : ms));
  return r > 0 && (p.revents & (POLLIN | POLLHUP)) != 0;
}

can_frame make_frame(std::uint32_t id29, const std::uint8_t* data, std::uint8_t length) {
  can_frame f{};
  f.can_id = (id29 & CAN_EFF_MASK) | CAN_EFF_FLAG;
  f.len = length > CAN_MAX_DLEN ? static_cast<std::uint8_t>(CAN_MAX_DLEN) : length;
  if (data != nullptr) std::memcpy(f.data, data, f.len);
  return f;
}

}  // namespace spread::isobus::can
