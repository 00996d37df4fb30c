// spread-canbus paced at 250 kbit/s, over real sockets: a flooding sender gets no more than the bus
// carries, and frames waiting together go out lowest identifier first. Unpaced runs of the same traffic
// show what the pacing changes.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "isobus/can/can_bus_relay.hpp"
#include "isobus/can/can_frame_bits.hpp"
#include "isobus/can/unix_can_bus.hpp"

namespace spread::isobus::can {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

class SocketDir {
 public:
  SocketDir() {
    char pattern[] = "/tmp/canpace-XXXXXX";
    if (::mkdtemp(pattern) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~SocketDir() { std::filesystem::remove_all(path_); }
  std::string bus() const { return path_ + "/bus"; }

 private:
  std::string path_;
};

can_frame numbered(std::uint32_t id29, int n) {
  const std::uint8_t data[8] = {static_cast<std::uint8_t>(n), static_cast<std::uint8_t>(n >> 8), 0x55, 0x55,
                                0x55, 0x55, 0x55, 0x55};
  return make_frame(id29, data, 8);
}

void settle(CanBusRelay& bus) {
  for (int i = 0; i < 4; ++i) bus.run_once(2ms);
}

struct FloodResult {
  int received = 0;
  double seconds = 0.0;  // from the first frame sent to the last frame received
  double frames_per_second() const { return seconds > 0.0 ? received / seconds : 0.0; }
};

// One sender writes as fast as its socket takes frames for `duration`; a reader counts what arrives.
FloodResult flood(CanBusTiming timing, std::chrono::milliseconds duration, const can_frame& frame,
                  std::uint64_t* bits = nullptr) {
  SocketDir dir;
  CanBusRelay bus(dir.bus(), timing);
  CanFramePort sender = connect_unix_can_bus(bus.path());
  CanFramePort reader = connect_unix_can_bus(bus.path());
  settle(bus);
  FloodResult r;
  const Clock::time_point first_sent = Clock::now();
  Clock::time_point last_received = first_sent;
  const auto end = first_sent + duration;
  while (Clock::now() < end) {
    for (int i = 0; i < 256 && sender.send(frame); ++i) {
    }
    bus.run_once(1ms);
    can_frame f{};
    while (reader.read(f) == ReadOutcome::kFrame) {
      last_received = Clock::now();
      ++r.received;
    }
  }
  r.seconds = std::chrono::duration<double>(last_received - first_sent).count();
  if (bits != nullptr) *bits = bus.counters().bits;
  return r;
}

TEST(CanBusPacing, AFloodIsHeldToTheBusCapacity) {
  const can_frame frame = numbered(0x18FF0080, 0);
  // 250,000 bit/s over this frame's bits (131 unstuffed + its stuff bits): ~1,760 frames/s; no 8-byte
  // extended frame goes faster than 250,000 / 131 = 1,908 frames/s.
  const int bits = can_frame_bit_count(frame);
  const double capacity = 250000.0 / bits;
  ASSERT_LE(capacity, 250000.0 / 131);
  std::uint64_t bits_carried = 0;
  const FloodResult paced = flood(CanBusTiming{true, 250000}, 600ms, frame, &bits_carried);
  std::printf("paced: %d frames in %.3f s = %.0f frames/s (capacity %.0f)\n", paced.received, paced.seconds,
              paced.frames_per_second(), capacity);
  // The bus cannot have ended more frames than fit back to back since the first one was sent.
  EXPECT_LE(paced.received, static_cast<int>(paced.seconds * capacity) + 1);
  EXPECT_GE(paced.frames_per_second(), capacity * 0.7) << "paced well below the bus capacity: frames lost or late";
  EXPECT_EQ(bits_carried, static_cast<std::uint64_t>(paced.received) * static_cast<std::uint64_t>(bits));
  // The same flood unpaced: many times what a 250 kbit/s bus carries.
  const FloodResult unpaced = flood(CanBusTiming{}, 200ms, frame);
  std::printf("unpaced: %d frames in %.3f s = %.0f frames/s\n", unpaced.received, unpaced.seconds,
              unpaced.frames_per_second());
  EXPECT_GT(unpaced.frames_per_second(), capacity * 3);
}

// Runs the bus until `reader` holds `count` frames (or 1 s passed).
std::vector<can_frame> collect(CanBusRelay& bus, CanFramePort& reader, std::size_t count) {
  std::vector<can_frame> got;
  const auto end = Clock::now() + 1s;
  while (got.size() < count && Clock::now() < end) {
    bus.run_once(1ms);
    can_frame f{};
    while (reader.read(f) == ReadOutcome::kFrame) got.push_back(f);
  }
  return got;
}

constexpr std::uint32_t kHigh = 0x18FF00A0;  // priority 6
constexpr std::uint32_t kLow = 0x0CFF00B0;   // priority 3

// Two senders with frames queued before the bus runs: the lower identifier wins every arbitration, so
// all of its frames go first; each sender's own frames keep their order.
std::vector<can_frame> two_queued_senders(CanBusTiming timing) {
  SocketDir dir;
  CanBusRelay bus(dir.bus(), timing);
  CanFramePort high = connect_unix_can_bus(bus.path());
  CanFramePort low = connect_unix_can_bus(bus.path());
  CanFramePort reader = connect_unix_can_bus(bus.path());
  settle(bus);
  for (int n = 0; n < 10; ++n) EXPECT_TRUE(high.send(numbered(kHigh, n)));
  for (int n = 0; n < 10; ++n) EXPECT_TRUE(low.send(numbered(kLow, n)));
  return collect(bus, reader, 20);
}

TEST(CanBusPacing, QueuedFramesGoLowestIdentifierFirst) {
  const auto paced = two_queued_senders(CanBusTiming{true, 250000});
  ASSERT_EQ(paced.size(), 20u);
  for (int n = 0; n < 10; ++n) {
    EXPECT_EQ(paced[static_cast<std::size_t>(n)].can_id & CAN_EFF_MASK, kLow) << "frame " << n;
    EXPECT_EQ(paced[static_cast<std::size_t>(n)].data[0], n);
    EXPECT_EQ(paced[static_cast<std::size_t>(10 + n)].can_id & CAN_EFF_MASK, kHigh) << "frame " << 10 + n;
    EXPECT_EQ(paced[static_cast<std::size_t>(10 + n)].data[0], n);
  }
  // Unpaced, the bus passes frames on as it reads them: the higher identifier's first frame goes first.
  const auto unpaced = two_queued_senders(CanBusTiming{});
  ASSERT_EQ(unpaced.size(), 20u);
  EXPECT_EQ(unpaced.front().can_id & CAN_EFF_MASK, kHigh);
}

// A frame that becomes ready while another is on the bus waits for its end, then wins against a
// higher identifier that was waiting longer. (10 kbit/s: the first frame holds the bus 14 ms, so the
// test does not depend on this process being scheduled within the 0.6 ms of a 250 kbit/s frame.)
TEST(CanBusPacing, AFrameOnTheBusIsNeverPreemptedAndTheWaitingLowerIdentifierGoesNext) {
  SocketDir dir;
  CanBusRelay bus(dir.bus(), CanBusTiming{true, 10000});
  CanFramePort first = connect_unix_can_bus(bus.path());
  CanFramePort high = connect_unix_can_bus(bus.path());
  CanFramePort low = connect_unix_can_bus(bus.path());
  CanFramePort reader = connect_unix_can_bus(bus.path());
  settle(bus);
  ASSERT_TRUE(first.send(numbered(0x1CFF00C0, 1)));  // priority 7: the lowest, but alone, so it starts
  bus.run_once(0ms);
  ASSERT_EQ(bus.frames_waiting(), 0u) << "the first frame is not on the bus";
  ASSERT_TRUE(high.send(numbered(kHigh, 2)));
  bus.run_once(0ms);
  ASSERT_TRUE(low.send(numbered(kLow, 3)));
  const auto got = collect(bus, reader, 3);
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got[0].data[0], 1);
  EXPECT_EQ(got[1].data[0], 3);
  EXPECT_EQ(got[2].data[0], 2);
}

#ifdef SPREAD_CANBUS_EXE
// The executable with --paced and --status-interval: a flood for 0.4 s is carried at the bus's capacity,
// and the status lines and the exit summary report the load.
TEST(SpreadCanbusExecutable, PacedBusReportsItsLoad) {
  SocketDir dir;
  const std::string path = dir.bus();
  const std::string err_path = path + ".err";
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const int err = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    ::dup2(err, 2);
    ::execl(SPREAD_CANBUS_EXE, SPREAD_CANBUS_EXE, path.c_str(), "--paced", "--status-interval", "0.1",
            "--duration", "20", static_cast<char*>(nullptr));
    std::_Exit(127);
  }
  std::optional<CanFramePort> sender;
  const auto deadline = Clock::now() + 5s;
  while (!sender && Clock::now() < deadline) {
    try {
      sender.emplace(connect_unix_can_bus(path));
    } catch (const std::runtime_error&) {
      std::this_thread::sleep_for(10ms);
    }
  }
  ASSERT_TRUE(sender.has_value()) << "spread-canbus did not start serving " << path;
  CanFramePort reader = connect_unix_can_bus(path);
  std::this_thread::sleep_for(50ms);
  const can_frame frame = numbered(0x18FF0080, 0);
  int received = 0;
  const auto end = Clock::now() + 400ms;
  while (Clock::now() < end) {
    while (sender->send(frame)) {
    }
    can_frame f{};
    if (reader.wait_readable(1ms)) {
      while (reader.read(f) == ReadOutcome::kFrame) ++received;
    }
  }
  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
  std::ifstream err_file(err_path);
  std::stringstream text;
  text << err_file.rdbuf();
  const std::string err = text.str();
  EXPECT_NE(err.find("paced at 250000 bit/s"), std::string::npos) << err;
  // 0.4 s at ~1,786 frames/s: about 714 frames, never more than the bus carries.
  EXPECT_LE(received, static_cast<int>(0.45 * 250000.0 / can_frame_bit_count(frame)) + 1);
  EXPECT_GE(received, 300);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(err, m, std::regex(R"(s  2 clients, ([0-9]+) frames/s, bus load ([0-9.]+) %)")))
      << err;
  EXPECT_LE(std::stod(m[2]), 100.5) << "a paced bus busier than its bit rate allows";
  ASSERT_TRUE(std::regex_search(err, m, std::regex(R"(bus load ([0-9.]+) % at 250 kbit/s over [0-9.]+ s \(paced\))")))
      << err;
  EXPECT_GT(std::stod(m[1]), 0.0);
  EXPECT_LE(std::stod(m[1]), 100.0);
}
#endif

}  // namespace
}  // namespace spread::isobus::can
