#include "firmware_sim/can/can_bus_relay.hpp"

#include <fcntl.h>
#include <linux/can.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace spread::firmware::can {
namespace {

sockaddr_un make_address(const std::string& path) {
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  if (path.empty() || path.size() >= sizeof(address.sun_path)) {
    throw std::runtime_error("spread-canbus: socket path '" + path + "' is empty or longer than " +
                             std::to_string(sizeof(address.sun_path) - 1) + " bytes");
  }
  std::memcpy(address.sun_path, path.c_str(), path.size() + 1);
  return address;
}

std::runtime_error errno_error(const std::string& what) {
  return std::runtime_error("spread-canbus: " + what + ": " + std::strerror(errno));
}

// True when a server accepts connections at `address` (a live bus); false for a stale socket file.
bool someone_serves(const sockaddr_un& address) {
  const int probe = ::socket(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0);
  if (probe < 0) throw errno_error("socket()");
  const bool live = ::connect(probe, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) == 0;
  ::close(probe);
  return live;
}

// A receiver's socket buffer holds this many bytes of queued frames before its frames are dropped: about
// 1 s of a fully loaded 250 kbit/s ISOBUS (~2,000 frames/s at ~500 bytes of kernel bookkeeping each) so a
// briefly busy client loses nothing. The kernel caps it at net.core.wmem_max.
constexpr int kSendBufferBytes = 1 << 20;

// What one recvmsg() on a client's SEQPACKET socket found.
enum class Received { kDatagram, kNothing, kEndOfStream, kError };

// Reads one datagram into `buffer` (its real length in `length`, even when longer than the buffer). recv()
// returns 0 both for an empty datagram and for the peer's end of stream; with SO_PASSCRED set on the
// socket, every datagram taken off the queue carries an SCM_CREDENTIALS message (unix(7)), end of stream
// none, which tells the two apart.
Received receive_datagram(int fd, unsigned char* buffer, std::size_t size, std::size_t& length) {
  iovec io{buffer, size};
  alignas(cmsghdr) unsigned char control[CMSG_SPACE(sizeof(ucred))];
  msghdr message{};
  message.msg_iov = &io;
  message.msg_iovlen = 1;
  message.msg_control = control;
  message.msg_controllen = sizeof(control);
  // MSG_TRUNC: the return value is the datagram's real length, so longer ones are recognised too.
  const ssize_t got = ::recvmsg(fd, &message, MSG_DONTWAIT | MSG_TRUNC);
  if (got < 0) {
    return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR ? Received::kNothing : Received::kError;
  }
  length = static_cast<std::size_t>(got);
  if (got == 0 && CMSG_FIRSTHDR(&message) == nullptr && (message.msg_flags & MSG_CTRUNC) == 0) {
    return Received::kEndOfStream;
  }
  return Received::kDatagram;
}

}  // namespace

CanBusRelay::CanBusRelay(std::string path) : path_(std::move(path)) {
  const sockaddr_un address = make_address(path_);
  struct stat existing{};
  if (::lstat(path_.c_str(), &existing) == 0) {
    if (!S_ISSOCK(existing.st_mode)) {
      throw std::runtime_error("spread-canbus: '" + path_ + "' exists and is not a socket; refusing to replace it");
    }
    if (someone_serves(address)) {
      throw std::runtime_error("spread-canbus: a bus is already served at '" + path_ + "'");
    }
    // Nobody answers: the socket file of a server that died without cleaning up. Take its place.
    if (::unlink(path_.c_str()) != 0 && errno != ENOENT) throw errno_error("cannot remove stale socket '" + path_ + "'");
  }
  listen_fd_ = ::socket(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (listen_fd_ < 0) throw errno_error("socket(AF_UNIX, SOCK_SEQPACKET)");
  if (::bind(listen_fd_, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) != 0) {
    const auto error = errno_error("bind('" + path_ + "')");
    ::close(listen_fd_);
    throw error;
  }
  struct stat mine{};
  if (::stat(path_.c_str(), &mine) == 0) {
    device_ = mine.st_dev;
    inode_ = mine.st_ino;
  }
  if (::listen(listen_fd_, 64) != 0) {
    const auto error = errno_error("listen()");
    ::close(listen_fd_);
    ::unlink(path_.c_str());
    throw error;
  }
}

CanBusRelay::~CanBusRelay() {
  for (const Client& c : clients_) ::close(c.fd);
  if (listen_fd_ >= 0) ::close(listen_fd_);
  struct stat now{};
  if (::stat(path_.c_str(), &now) == 0 && now.st_dev == device_ && now.st_ino == inode_) ::unlink(path_.c_str());
}

std::vector<std::uint64_t> CanBusRelay::drops_per_client() const {
  std::vector<std::uint64_t> out;
  for (const Client& c : clients_) out.push_back(c.dropped_full);
  return out;
}

bool CanBusRelay::run_once(std::chrono::milliseconds timeout, const sigset_t* signal_mask) {
  std::vector<pollfd> fds;
  fds.reserve(clients_.size() + 1);
  fds.push_back({listen_fd_, POLLIN, 0});
  for (const Client& c : clients_) fds.push_back({c.fd, POLLIN, 0});
  int ready = 0;
  if (signal_mask != nullptr) {
    timespec ts{static_cast<time_t>(timeout.count() / 1000), static_cast<long>((timeout.count() % 1000) * 1000000)};
    ready = ::ppoll(fds.data(), fds.size(), &ts, signal_mask);
  } else {
    ready = ::poll(fds.data(), fds.size(), static_cast<int>(timeout.count()));
  }
  if (ready < 0) {
    if (errno == EINTR) return false;
    throw errno_error("poll()");
  }
  // Clients first (their indices match fds[1..]), then newcomers: a frame sent before a client joined is
  // not delivered to it, as on a real bus.
  for (std::size_t i = 0; i + 1 < fds.size(); ++i) {
    const short revents = fds[i + 1].revents;
    if ((revents & POLLIN) != 0) {
      read_client(i);
    } else if ((revents & (POLLHUP | POLLERR | POLLNVAL)) != 0) {
      clients_[i].gone = true;
    }
  }
  remove_gone_clients();
  if ((fds[0].revents & POLLIN) != 0) accept_clients();
  return true;
}

void CanBusRelay::accept_clients() {
  for (;;) {
    const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR || errno == ECONNABORTED) return;
      if (errno == EMFILE || errno == ENFILE) return;  // out of descriptors: the client waits in the backlog
      throw errno_error("accept()");
    }
    ::setsockopt(fd, SOL_SOCKET, SO_SNDBUF, &kSendBufferBytes, sizeof(kSendBufferBytes));
    const int on = 1;  // credentials on every datagram: how an empty one is told from end of stream
    if (::setsockopt(fd, SOL_SOCKET, SO_PASSCRED, &on, sizeof(on)) != 0) {
      ::close(fd);
      throw errno_error("setsockopt(SO_PASSCRED)");
    }
    clients_.push_back({fd, 0, 0, false});
    ++counters_.clients_accepted;
  }
}

void CanBusRelay::read_client(std::size_t index) {
  // Drain what this client has queued, but at most a burst per wake-up so that one chatty client cannot
  // starve the others' turn in the poll set (a CAN bus arbitrates per frame, not per node).
  constexpr int kBurst = 64;
  for (int n = 0; n < kBurst; ++n) {
    unsigned char buffer[sizeof(can_frame) + 1];
    std::size_t got = 0;
    const Received outcome = receive_datagram(clients_[index].fd, buffer, sizeof(buffer), got);
    if (outcome == Received::kNothing) return;
    if (outcome != Received::kDatagram) {  // end of stream (it left or shut down) or a socket error
      clients_[index].gone = true;
      return;
    }
    if (got != sizeof(can_frame)) {  // an empty datagram too: malformed, its sender stays on the bus
      ++counters_.wrong_size_datagrams;
      continue;
    }
    can_frame frame;
    std::memcpy(&frame, buffer, sizeof(frame));
    if (frame.len > CAN_MAX_DLEN) {
      ++counters_.invalid_frames;
      continue;
    }
    ++clients_[index].frames_in;
    ++counters_.frames_relayed;
    fan_out(index, buffer);
  }
}

void CanBusRelay::fan_out(std::size_t from, const unsigned char* frame) {
  for (std::size_t i = 0; i < clients_.size(); ++i) {
    Client& to = clients_[i];
    if (i == from || to.gone) continue;
    // MSG_NOSIGNAL: a receiver that just left must not kill the bus with SIGPIPE.
    const ssize_t sent = ::send(to.fd, frame, sizeof(can_frame), MSG_DONTWAIT | MSG_NOSIGNAL);
    if (sent == static_cast<ssize_t>(sizeof(can_frame))) {
      ++counters_.deliveries;
    } else if (sent < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == ENOBUFS)) {
      ++to.dropped_full;
      ++counters_.dropped_full;
    } else {
      to.gone = true;  // EPIPE / ECONNRESET: it left; removed after this round
    }
  }
}

void CanBusRelay::remove_gone_clients() {
  for (std::size_t i = 0; i < clients_.size();) {
    if (clients_[i].gone) {
      ::close(clients_[i].fd);
      clients_.erase(clients_.begin() + static_cast<std::ptrdiff_t>(i));
      ++counters_.clients_left;
    } else {
      ++i;
    }
  }
}

}  // namespace spread::firmware::can
