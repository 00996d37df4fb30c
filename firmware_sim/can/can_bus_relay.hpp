#pragma once
// The server side of spread-canbus: a virtual CAN bus on a Unix SOCK_SEQPACKET socket. Every datagram a
// client sends is one 16-byte `struct can_frame` (SocketCAN layout); each valid frame is delivered to every
// OTHER connected client, as a vcan interface delivers a CAN_RAW socket's frame to the host's other CAN_RAW
// sockets (the sender does not get its own frame back: CAN_RAW_RECV_OWN_MSGS is off by default).
// One thread, poll(): a client that does not read never blocks the bus — when its socket buffer is full the
// frame is dropped for that client only and counted, as a CAN controller with a full receive FIFO would.
#include <signal.h>

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace spread::firmware::can {

struct CanBusRelayCounters {
  std::uint64_t clients_accepted = 0;
  std::uint64_t clients_left = 0;
  std::uint64_t frames_relayed = 0;        // valid frames received (each is fanned out once)
  std::uint64_t deliveries = 0;            // frames written to a receiving client
  std::uint64_t wrong_size_datagrams = 0;  // datagrams of other than sizeof(can_frame) bytes: dropped
  std::uint64_t invalid_frames = 0;        // 16 bytes but DLC > 8 (a CAN_RAW write would fail): dropped
  std::uint64_t dropped_full = 0;          // deliveries skipped because the receiver's buffer was full
};

class CanBusRelay {
 public:
  // Binds and listens at `path`. A socket file nobody serves (a crashed server's) is replaced; a live
  // server at `path`, or a path that is not a socket, is refused with std::runtime_error.
  explicit CanBusRelay(std::string path);
  ~CanBusRelay();  // closes every socket and removes the socket file (if it is still ours)
  CanBusRelay(const CanBusRelay&) = delete;
  CanBusRelay& operator=(const CanBusRelay&) = delete;

  // Waits up to `timeout` for activity and handles all of it (accepts, frames, departures). With
  // `signal_mask`, the wait is a ppoll() under that mask, so a signal blocked elsewhere interrupts it
  // without a race. Returns false when interrupted by a signal.
  bool run_once(std::chrono::milliseconds timeout, const sigset_t* signal_mask = nullptr);

  const std::string& path() const { return path_; }
  std::size_t client_count() const { return clients_.size(); }
  const CanBusRelayCounters& counters() const { return counters_; }
  // Per-client drops of the clients connected now, in connection order (for tests and the exit summary).
  std::vector<std::uint64_t> drops_per_client() const;

 private:
  struct Client {
    int fd = -1;
    std::uint64_t frames_in = 0;
    std::uint64_t dropped_full = 0;
    bool gone = false;
  };
  void accept_clients();
  void read_client(std::size_t index);
  void fan_out(std::size_t from, const unsigned char* frame);
  void remove_gone_clients();

  std::string path_;
  int listen_fd_ = -1;
  dev_t device_ = 0;  // identity of the socket file we created, so the destructor never removes another's
  ino_t inode_ = 0;
  std::vector<Client> clients_;
  CanBusRelayCounters counters_;
};

}  // namespace spread::firmware::can
