#pragma once
// The server side of spread-canbus: a virtual CAN bus on a Unix SOCK_SEQPACKET socket. Every datagram a
// client sends is one 16-byte `struct can_frame` (SocketCAN layout); each valid frame is delivered to every
// OTHER connected client, as a vcan interface delivers a CAN_RAW socket's frame to the host's other CAN_RAW
// sockets (the sender does not get its own frame back: CAN_RAW_RECV_OWN_MSGS is off by default).
// A client that leaves (closes, exits or is killed) takes the frames still queued in its socket with it,
// as a node switched off loses its transmit queue; only frames the bus already took reach the others.
// One thread, poll(): a client that does not read never blocks the bus — when its socket buffer is full the
// frame is dropped for that client only and counted, as a CAN controller with a full receive FIFO would.
// Unpaced (the default), a frame is passed on as soon as it is read. Paced, the bus runs at a bit rate
// with arbitration by identifier (can_bus_pacer.hpp): a client's next frame is read only once its previous
// one went out, so a sender faster than the bus waits in its own socket, as a node waits for the bus.
#include <signal.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "isobus/can/can_bus_pacer.hpp"

namespace spread::isobus::can {

struct CanBusTiming {
  bool paced = false;                     // false: relay at once, true: one frame at a time at bit_rate
  std::uint32_t bit_rate = kIsobusBitRate;  // bit/s: pacing, and the bus load reported in both modes
};

struct CanBusRelayCounters {
  std::uint64_t clients_accepted = 0;
  std::uint64_t clients_left = 0;
  std::uint64_t frames_relayed = 0;        // valid frames received (each is fanned out once)
  std::uint64_t deliveries = 0;            // frames written to a receiving client
  std::uint64_t wrong_size_datagrams = 0;  // datagrams of other than sizeof(can_frame) bytes: dropped
  std::uint64_t invalid_frames = 0;        // 16 bytes but DLC > 8 (a CAN_RAW write would fail): dropped
  std::uint64_t dropped_full = 0;          // deliveries skipped because the receiver's buffer was full
  std::uint64_t bits = 0;                  // bit times of the frames relayed (can_frame_bits.hpp)
  std::uint64_t withdrawn = 0;             // paced: frames waiting for the bus when their sender left
  std::uint64_t lost_with_sender = 0;      // frames still queued in a client's socket when it left: dropped
};

class CanBusRelay {
 public:
  // Binds and listens at `path`. A socket file nobody serves (a crashed server's) is replaced; a live
  // server at `path`, or a path that is not a socket, is refused with std::runtime_error.
  explicit CanBusRelay(std::string path, CanBusTiming timing = {});
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
  const CanBusTiming& timing() const { return timing_; }
  // Paced: frames read from their senders and waiting for the bus.
  std::size_t frames_waiting() const { return pacer_ ? pacer_->waiting() : 0; }
  // The share of `elapsed` the relayed frames would hold a bus at the bit rate (paced: did hold), for
  // the counters' `bits` since some earlier reading: (bits / bit rate) / elapsed.
  double bus_load(std::uint64_t bits, std::chrono::nanoseconds elapsed) const;
  // Per-client drops of the clients connected now, in connection order (for tests and the exit summary).
  std::vector<std::uint64_t> drops_per_client() const;

 private:
  struct Client {
    int fd = -1;
    std::uint64_t id = 0;  // stable across removals of other clients (the pacer names senders by it)
    std::uint64_t frames_in = 0;
    std::uint64_t dropped_full = 0;
    bool gone = false;
  };
  enum class Read { kFrame, kNothing, kGone };
  void accept_clients();
  void read_client(std::size_t index, std::chrono::nanoseconds now);
  // Reads this client's datagrams until a valid frame (kFrame), an empty queue, or its departure;
  // malformed datagrams on the way are counted and dropped.
  Read read_frame(Client& client, can_frame& frame);
  void run_bus(std::chrono::nanoseconds now);
  void fan_out(std::uint64_t from, const can_frame& frame);
  void remove_gone_clients();
  // The client has left: marks it gone and drops (counts) the frames still queued in its socket.
  void leave(Client& client);
  // Whether the client's end of the socket has closed (checked before taking its next frame).
  bool departed(const Client& client) const;
  std::chrono::nanoseconds now() const;

  std::string path_;
  int listen_fd_ = -1;
  dev_t device_ = 0;  // identity of the socket file we created, so the destructor never removes another's
  ino_t inode_ = 0;
  std::vector<Client> clients_;
  std::uint64_t next_client_id_ = 1;
  CanBusTiming timing_;
  std::optional<CanBusPacer> pacer_;
  CanBusRelayCounters counters_;
};

}  // namespace spread::isobus::can
