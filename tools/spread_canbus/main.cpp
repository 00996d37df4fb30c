// spread-canbus PATH: a virtual CAN bus for processes on one machine without AF_CAN/vcan (docs/design.md §6).
// Clients connect a SOCK_SEQPACKET Unix socket to PATH and exchange 16-byte `struct can_frame` datagrams;
// every frame reaches every other client. Datagram format and adapters: docs/can-integration.md.
// --paced runs the bus at a bit rate with arbitration by identifier (can_bus_pacer.hpp); --status-interval
// prints the bus load and the drop and malformed counters as it runs.
#include <CLI/CLI.hpp>

#include <signal.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <iostream>

#include "isobus/can/can_bus_relay.hpp"

namespace {
volatile sig_atomic_t g_stop = 0;
extern "C" void on_signal(int) { g_stop = 1; }

using spread::isobus::can::CanBusRelay;
using spread::isobus::can::CanBusRelayCounters;

// Malformed input: datagrams of another size than a can_frame (empty ones included) and DLC > 8.
unsigned long long malformed(const CanBusRelayCounters& c) {
  return static_cast<unsigned long long>(c.wrong_size_datagrams + c.invalid_frames);
}

void print_summary(const CanBusRelay& bus, std::chrono::nanoseconds elapsed) {
  const auto& c = bus.counters();
  std::fprintf(stderr,
               "spread-canbus: %llu clients joined, %llu left, %llu frames relayed, %llu deliveries, "
               "%llu dropped (receiver full), %llu wrong-size datagrams, %llu invalid frames (DLC > 8), "
               "%llu withdrawn (sender left), %llu lost with their sender (queued when it left), bus load %.1f %% "
               "at %u kbit/s over %.1f s (%s)\n",
               static_cast<unsigned long long>(c.clients_accepted), static_cast<unsigned long long>(c.clients_left),
               static_cast<unsigned long long>(c.frames_relayed), static_cast<unsigned long long>(c.deliveries),
               static_cast<unsigned long long>(c.dropped_full),
               static_cast<unsigned long long>(c.wrong_size_datagrams),
               static_cast<unsigned long long>(c.invalid_frames), static_cast<unsigned long long>(c.withdrawn),
               static_cast<unsigned long long>(c.lost_with_sender),
               100.0 * bus.bus_load(c.bits, elapsed), bus.timing().bit_rate / 1000,
               std::chrono::duration<double>(elapsed).count(), bus.timing().paced ? "paced" : "unpaced");
}

// One line per interval: what the bus carried in it, and the error and drop counters so far.
void print_status(const CanBusRelay& bus, const CanBusRelayCounters& before, std::chrono::nanoseconds interval,
                  std::chrono::nanoseconds since_start) {
  const auto& c = bus.counters();
  const double seconds = std::chrono::duration<double>(interval).count();
  std::fprintf(stderr,
               "spread-canbus: %8.1f s  %zu clients, %.0f frames/s, bus load %.1f %%, %zu waiting, "
               "dropped %llu, malformed %llu\n",
               std::chrono::duration<double>(since_start).count(), bus.client_count(),
               static_cast<double>(c.frames_relayed - before.frames_relayed) / seconds,
               100.0 * bus.bus_load(c.bits - before.bits, interval), bus.frames_waiting(),
               static_cast<unsigned long long>(c.dropped_full), malformed(c));
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"spread-canbus: a virtual CAN bus on a Unix SEQPACKET socket (16-byte struct can_frame datagrams)"};
  std::string path;
  double duration_s = 0.0;
  bool verbose = false;
  bool paced = false;
  std::uint32_t bit_rate = spread::isobus::can::kIsobusBitRate;
  double status_interval_s = 0.0;
  app.add_option("path", path, "socket path to serve the bus at (a dead server's socket file is replaced)")->required();
  app.add_flag("--paced", paced,
               "run the bus at --bitrate: one frame at a time for its bit count, lowest identifier first "
               "(default: pass frames on as soon as they are read)");
  auto* bitrate_option =
      app.add_option("--bitrate", bit_rate, "bit rate in bit/s for --paced and the bus load (implies --paced)")
          ->check(CLI::Range(1000U, 1000000U))
          ->capture_default_str();
  app.add_option("--status-interval", status_interval_s,
                 "print a status line (frames/s, bus load, waiting frames, drops) every this many seconds")
      ->check(CLI::NonNegativeNumber);
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
    spread::isobus::can::CanBusTiming timing;
    timing.paced = paced || bitrate_option->count() > 0;
    timing.bit_rate = bit_rate;
    CanBusRelay bus(path, timing);
    if (timing.paced) {
      std::fprintf(stderr, "spread-canbus: serving %s, paced at %u bit/s\n", bus.path().c_str(), timing.bit_rate);
    } else {
      std::fprintf(stderr, "spread-canbus: serving %s\n", bus.path().c_str());
    }
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    const auto status_interval = std::chrono::duration_cast<std::chrono::nanoseconds>(
        std::chrono::duration<double>(status_interval_s));
    auto next_status = start + status_interval;
    auto last_status = start;
    CanBusRelayCounters at_last_status;
    std::size_t clients = 0;
    while (g_stop == 0) {
      const auto now = Clock::now();
      if (duration_s > 0.0 && now - start >= std::chrono::duration<double>(duration_s)) break;
      if (status_interval_s > 0.0 && now >= next_status) {
        print_status(bus, at_last_status, now - last_status, now - start);
        at_last_status = bus.counters();
        last_status = now;
        next_status += status_interval;
        if (next_status <= now) next_status = now + status_interval;
      }
      // Wake in time for the next status line (paced, run_once also wakes for every frame's end).
      auto wait = std::chrono::milliseconds(200);
      if (status_interval_s > 0.0) {
        wait = std::clamp(std::chrono::duration_cast<std::chrono::milliseconds>(next_status - now) +
                              std::chrono::milliseconds(1),
                          std::chrono::milliseconds(1), wait);
      }
      bus.run_once(wait, &wait_mask);
      if (verbose && bus.client_count() != clients) {
        clients = bus.client_count();
        std::fprintf(stderr, "spread-canbus: %zu clients connected\n", clients);
      }
    }
    print_summary(bus, Clock::now() - start);
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  return 0;
}
