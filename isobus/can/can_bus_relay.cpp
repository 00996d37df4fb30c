#include "isobus/can/can_bus_relay.hpp"

#include <fcntl.h>
#include <linux/can.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "isobus/can/can_frame_bits.hpp"

namespace spread::isobus::can {
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

CanBusRelay::CanBusRelay(std::string path, CanBusTiming timing) : path_(std::move(path)), timing_(timing) {
  if (timing_.bit_rate == 0) throw std::runtime_error("spread-canbus: the bit rate must be above 0");
  if (timing_.paced) pacer_.emplace(timing_.bit_rate);
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

std::chrono::nanoseconds CanBusRelay::now() const {
  return std::chrono::steady_clock::now().time_since_epoch();
}

double CanBusRelay::bus_load(std::uint64_t bits, std::chrono::nanoseconds elapsed) const {
  if (elapsed.count() <= 0) return 0.0;
  return static_cast<double>(bits) / timing_.bit_rate / std::chrono::duration<double>(elapsed).count();
}

bool CanBusRelay::run_once(std::chrono::milliseconds timeout, const sigset_t* signal_mask) {
  std::chrono::nanoseconds wait = timeout;
  if (pacer_) {
    run_bus(now());
    // Wake when the frame on the bus ends, to deliver it and start the next one.
    if (const auto end = pacer_->next_end()) wait = std::clamp(*end - now(), std::chrono::nanoseconds(0), wait);
  }
  std::vector<pollfd> fds;
  fds.reserve(clients_.size() + 1);
  fds.push_back({listen_fd_, POLLIN, 0});
  for (const Client& c : clients_) {
    // Paced, a client whose frame waits for the bus is not read (its further frames wait in its socket),
    // but still polled for its departure (POLLHUP is reported whatever the events asked).
    const bool holding = pacer_ && pacer_->has_frame(c.id);
    fds.push_back({c.fd, static_cast<short>(holding ? 0 : POLLIN), 0});
  }
  const timespec ts{static_cast<time_t>(wait.count() / 1'000'000'000),
                    static_cast<long>(wait.count() % 1'000'000'000)};
  const int ready = ::ppoll(fds.data(), fds.size(), &ts, signal_mask);
  if (ready < 0) {
    if (errno == EINTR) return false;
    throw errno_error("poll()");
  }
  const std::chrono::nanoseconds woke = now();
  // Clients first (their indices match fds[1..]), then newcomers: a frame sent before a client joined is
  // not delivered to it, as on a real bus.
  for (std::size_t i = 0; i + 1 < fds.size(); ++i) {
    const short revents = fds[i + 1].revents;
    if ((revents & (POLLHUP | POLLERR | POLLNVAL)) != 0) {
      // The client left (or died): the frames still queued in its socket never reached the bus, and a
      // node that is switched off or unplugged loses its transmit queue at once (ISO 11898-1: a frame
      // exists on the bus only once it is sent). Read and dropped unsent, not relayed.
      leave(clients_[i]);
    } else if ((revents & POLLIN) != 0) {
      read_client(i, woke);
    }
  }
  if (pacer_) run_bus(woke);
  remove_gone_clients();
  if ((fds[0].revents & POLLIN) != 0) accept_clients();
  return true;
}

void CanBusRelay::leave(Client& client) {
  client.gone = true;
  unsigned char buffer[sizeof(can_frame) + 1];
  std::size_t got = 0;
  // Bounded: a socket holds at most its receive buffer's worth of datagrams.
  for (int n = 0; n < 1 << 16 && receive_datagram(client.fd, buffer, sizeof(buffer), got) == Received::kDatagram; ++n) {
    if (got == sizeof(can_frame)) ++counters_.lost_with_sender;
  }
}

bool CanBusRelay::departed(const Client& client) const {
  pollfd p{client.fd, 0, 0};
  return ::poll(&p, 1, 0) > 0 && (p.revents & (POLLHUP | POLLERR | POLLNVAL)) != 0;
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
    clients_.push_back({fd, next_client_id_++, 0, 0, false});
    ++counters_.clients_accepted;
  }
}

CanBusRelay::Read CanBusRelay::read_frame(Client& client, can_frame& frame) {
  // Bounded, so that a client sending nothing but malformed datagrams cannot hold the relay.
  constexpr int kMaxDatagrams = 64;
  for (int n = 0; n < kMaxDatagrams; ++n) {
    unsigned char buffer[sizeof(can_frame) + 1];
    std::size_t got = 0;
    const Received outcome = receive_datagram(client.fd, buffer, sizeof(buffer), got);
    if (outcome == Received::kNothing) return Read::kNothing;
    if (outcome != Received::kDatagram) {  // end of stream (it left or shut down) or a socket error
      client.gone = true;
      return Read::kGone;
    }
    if (got != sizeof(can_frame)) {  // an empty datagram too: malformed, its sender stays on the bus
      ++counters_.wrong_size_datagrams;
      continue;
    }
    std::memcpy(&frame, buffer, sizeof(frame));
    if (frame.len > CAN_MAX_DLEN) {
      ++counters_.invalid_frames;
      continue;
    }
    ++client.frames_in;
    return Read::kFrame;
  }
  return Read::kNothing;
}

void CanBusRelay::read_client(std::size_t index, std::chrono::nanoseconds now) {
  Client& client = clients_[index];
  can_frame frame{};
  if (pacer_) {
    // One frame into the client's transmit buffer; it goes out when it wins the bus.
    if (!pacer_->has_frame(client.id) && read_frame(client, frame) == Read::kFrame) {
      pacer_->offer(client.id, frame, now);
    }
    return;
  }
  // Drain what this client has queued, but at most a burst per wake-up so that one chatty client cannot
  // starve the others' turn in the poll set.
  constexpr int kBurst = 64;
  for (int n = 0; n < kBurst && read_frame(client, frame) == Read::kFrame; ++n) {
    ++counters_.frames_relayed;
    counters_.bits += static_cast<std::uint64_t>(can_frame_bit_count(frame));
    fan_out(client.id, frame);
  }
}

void CanBusRelay::run_bus(std::chrono::nanoseconds now) {
  const auto refill = [this](std::uint64_t sender, std::chrono::nanoseconds start) {
    // The sender's frame is on the bus: its next one (already queued in its socket) is ready from the
    // start of this one and contends when the bus is free again.
    for (Client& c : clients_) {
      if (c.id != sender || c.gone) continue;
      if (departed(c)) {
        leave(c);  // its queued frames go with it, not onto the bus
        continue;
      }
      can_frame next{};
      if (read_frame(c, next) == Read::kFrame) pacer_->offer(c.id, next, start);
    }
  };
  for (const CanBusPacer::Transmitted& t : pacer_->advance(now, refill)) {
    ++counters_.frames_relayed;
    counters_.bits += static_cast<std::uint64_t>(can_frame_bit_count(t.frame));
    fan_out(t.sender, t.frame);
  }
}

void CanBusRelay::fan_out(std::uint64_t from, const can_frame& frame) {
  for (Client& to : clients_) {
    if (to.id == from || to.gone) continue;
    // MSG_NOSIGNAL: a receiver that just left must not kill the bus with SIGPIPE.
    const ssize_t sent = ::send(to.fd, &frame, sizeof(can_frame), MSG_DONTWAIT | MSG_NOSIGNAL);
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
      if (pacer_ && pacer_->has_frame(clients_[i].id)) {
        pacer_->withdraw(clients_[i].id);  // a node that leaves takes its unsent frame with it
        ++counters_.withdrawn;
      }
      ::close(clients_[i].fd);
      clients_.erase(clients_.begin() + static_cast<std::ptrdiff_t>(i));
      ++counters_.clients_left;
    } else {
      ++i;
    }
  }
}

}  // namespace spread::isobus::can
