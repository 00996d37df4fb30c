// spread-canbus PATH: a virtual CAN bus for processes on one machine without AF_CAN/vcan (DESIGN.md §6).
// Clients connect a SOCK_SEQPACKET Unix socket to PATH and exchange 16-byte `struct can_frame` datagrams;
// every frame reaches every other client. Datagram format and adapters: docs/can-integration.md.
#include <CLI/CLI.hpp>

#include <signal.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <iostream>

#include "firmware_sim/can/can_bus_relay.hpp"

namespace {
volatile sig_atomic_t g_stop = 0;
extern "C" void on_signal(int) { g_stop = 1; }

void print_summary(const spread::firmware::can::CanBusRelay& bus) {
  const auto& c = bus.counters();
  std::fprintf(stderr,
               "spread-canbus: %llu clients joined, %llu left, %llu frames relayed, %llu deliveries, "
               "%llu dropped (receiver full), %llu wrong-size datagrams, %llu invalid frames (DLC > 8)\n",
               static_cast<unsigned long long>(c.clients_accepted), static_cast<unsigned long long>(c.clients_left),
               static_cast<unsigned long long>(c.frames_relayed), static_cast<unsigned long long>(c.deliveries),
               static_cast<unsigned long long>(c.dropped_full),
               static_cast<unsigned long long>(c.wrong_size_datagrams),
               static_cast<unsigned long long>(c.invalid_frames));
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"spread-canbus: a virtual CAN bus on a Unix SEQPACKET socket (16-byte struct can_frame datagrams)"};
  std::string path;
  double duration_s = 0.0;
  bool verbose = false;
  app.add_option("path", path, "socket path to serve the bus at (a dead server's socket file is replaced)")->required();
  app.add_option("--duration", duration_s, "stop after this many seconds (0: until SIGINT/SIGTERM)")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--verbose", verbose, "print a line when a client joins or leaves");
  CLI11_PARSE(app, argc, argv);

  // SIGINT/SIGTERM are blocked except inside ppoll(): the flag is never missed between check and wait.
  sigset_t blocked;
  sigset_t wait_mask;
  sigemptyset(&blocked);
  sigaddset(&blocked, SIGINT);
  sigaddset(&blocked, SIGTERM);
  sigprocmask(SIG_BLOCK, &blocked, &wait_mask);
  sigdelset(&wait_mask, SIGINT);
  sigdelset(&wait_mask, SIGTERM);
  struct sigaction action{};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);

  try {
    spread::firmware::can::CanBusRelay bus(path);
    std::fprintf(stderr, "spread-canbus: serving %s\n", bus.path().c_str());
    const auto start = std::chrono::steady_clock::now();
    std::size_t clients = 0;
    while (g_stop == 0) {
      if (duration_s > 0.0 && std::chrono::steady_clock::now() - start >= std::chrono::duration<double>(duration_s)) {
        break;
      }
      bus.run_once(std::chrono::milliseconds(200), &wait_mask);
      if (verbose && bus.client_count() != clients) {
        clients = bus.client_count();
        std::fprintf(stderr, "spread-canbus: %zu clients connected\n", clients);
      }
    }
    print_summary(bus);
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  return 0;
}
