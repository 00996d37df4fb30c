// spread-canbus: the relay in-process (fan-out, no echo, wrong-size and empty datagrams, DLC > 8, clients leaving, a
// client that never reads, stale and live socket files) and the real executable with three clients.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "isobus/can/can_bus_relay.hpp"
#include "isobus/can/unix_can_bus.hpp"

namespace spread::isobus::can {
namespace {

using namespace std::chrono_literals;

// A fresh directory for each test's socket (sun_path is limited to 107 bytes: keep it short, under /tmp).
class TempDir {
 public:
  TempDir() {
    char pattern[] = "/tmp/canbus-XXXXXX";
    const char* made = ::mkdtemp(pattern);
    if (made == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = made;
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  std::string file(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

can_frame frame_with(std::uint32_t id29, std::uint8_t first_byte) {
  const std::uint8_t data[8] = {first_byte, 1, 2, 3, 4, 5, 6, 7};
  return make_frame(id29, data, 8);
}

// Reads every frame the port has pending now.
std::vector<can_frame> read_all(CanFramePort& port) {
  std::vector<can_frame> out;
  can_frame f{};
  while (port.read(f) == ReadOutcome::kFrame) out.push_back(f);
  return out;
}

// Lets the relay handle everything pending (a few rounds: accept, then frames).
void settle(CanBusRelay& bus) {
  for (int i = 0; i < 4; ++i) bus.run_once(5ms);
}

TEST(CanBusRelay, EveryFrameReachesEveryOtherClientButNotTheSender) {
  TempDir dir;
  CanBusRelay bus(dir.file("bus"));
  CanFramePort a = connect_unix_can_bus(bus.path());
  CanFramePort b = connect_unix_can_bus(bus.path());
  CanFramePort c = connect_unix_can_bus(bus.path());
  settle(bus);
  ASSERT_EQ(bus.client_count(), 3u);
  ASSERT_TRUE(a.send(frame_with(0x18EEFF80, 0xA1)));
  ASSERT_TRUE(b.send(frame_with(0x0CCB8081, 0xB2)));
  settle(bus);
  const auto at_a = read_all(a);
  const auto at_b = read_all(b);
  const auto at_c = read_all(c);
  ASSERT_EQ(at_a.size(), 1u);
  EXPECT_EQ(at_a[0].data[0], 0xB2);
  ASSERT_EQ(at_b.size(), 1u);
  EXPECT_EQ(at_b[0].data[0], 0xA1);
  EXPECT_EQ(at_b[0].can_id, 0x18EEFF80u | CAN_EFF_FLAG);  // the 16 bytes pass unchanged
  ASSERT_EQ(at_c.size(), 2u);
  EXPECT_EQ(bus.counters().frames_relayed, 2u);
  EXPECT_EQ(bus.counters().deliveries, 4u);
}

TEST(CanBusRelay, WrongSizeDatagramsAndOversizedDlcAreCountedNotRelayed) {
  TempDir dir;
  CanBusRelay bus(dir.file("bus"));
  CanFramePort a = connect_unix_can_bus(bus.path());
  CanFramePort b = connect_unix_can_bus(bus.path());
  settle(bus);
  const unsigned char short_record[8] = {};
  const unsigned char canfd_record[72] = {};  // a struct canfd_frame: not this bus's format
  ASSERT_TRUE(a.send_raw(short_record, sizeof(short_record)));
  ASSERT_TRUE(a.send_raw(canfd_record, sizeof(canfd_record)));
  can_frame too_long = frame_with(0x0CCB8081, 1);
  too_long.len = 9;
  ASSERT_TRUE(a.send_raw(&too_long, sizeof(too_long)));
  ASSERT_TRUE(a.send(frame_with(0x0CCB8081, 0x42)));  // the client stays connected and is still relayed
  settle(bus);
  EXPECT_EQ(bus.counters().wrong_size_datagrams, 2u);
  EXPECT_EQ(bus.counters().invalid_frames, 1u);
  const auto at_b = read_all(b);
  ASSERT_EQ(at_b.size(), 1u);
  EXPECT_EQ(at_b[0].data[0], 0x42);
  EXPECT_EQ(bus.client_count(), 2u);
}

// On a SEQPACKET socket recv() returns 0 both for an empty datagram and for the peer's end of stream: an
// empty datagram is a malformed record like any other wrong size, and its sender stays on the bus.
TEST(CanBusRelay, ZeroLengthDatagramIsCountedAndItsSenderStaysConnected) {
  TempDir dir;
  CanBusRelay bus(dir.file("bus"));
  CanFramePort a = connect_unix_can_bus(bus.path());
  CanFramePort b = connect_unix_can_bus(bus.path());
  settle(bus);
  ASSERT_EQ(::send(a.fd(), "", 0, 0), 0);
  ASSERT_EQ(::send(a.fd(), "", 0, 0), 0);
  ASSERT_TRUE(a.send(frame_with(0x0CCB8081, 0x42)));
  settle(bus);
  EXPECT_EQ(bus.counters().wrong_size_datagrams, 2u);
  EXPECT_EQ(bus.counters().clients_left, 0u);
  EXPECT_EQ(bus.client_count(), 2u);
  const auto at_b = read_all(b);
  ASSERT_EQ(at_b.size(), 1u) << "the frame after the empty datagrams was not relayed";
  EXPECT_EQ(at_b[0].data[0], 0x42);
  ASSERT_TRUE(b.send(frame_with(0x0CCB8180, 0x43)));  // and a still hears the bus
  settle(bus);
  const auto at_a = read_all(a);
  ASSERT_EQ(at_a.size(), 1u);
  EXPECT_EQ(at_a[0].data[0], 0x43);
  // An empty datagram and a frame just before their sender closes: the departure is seen, and what it
  // left queued goes with it (a node switched off loses its transmit queue), the frame counted as lost.
  ASSERT_EQ(::send(a.fd(), "", 0, 0), 0);
  ASSERT_TRUE(a.send(frame_with(0x0CCB8081, 0x44)));
  ::shutdown(a.fd(), SHUT_RDWR);
  settle(bus);
  EXPECT_TRUE(read_all(b).empty());
  EXPECT_EQ(bus.counters().lost_with_sender, 1u);
  EXPECT_EQ(bus.counters().clients_left, 1u);
}

TEST(CanBusRelay, ClientsJoinAndLeaveWhileTheBusRuns) {
  TempDir dir;
  CanBusRelay bus(dir.file("bus"));
  CanFramePort a = connect_unix_can_bus(bus.path());
  std::optional<CanFramePort> b(connect_unix_can_bus(bus.path()));
  settle(bus);
  ASSERT_EQ(bus.client_count(), 2u);
  b.reset();  // b leaves (closes its socket)
  ASSERT_TRUE(a.send(frame_with(0x0CCB8081, 1)));
  settle(bus);
  EXPECT_EQ(bus.client_count(), 1u);
  EXPECT_EQ(bus.counters().clients_left, 1u);
  CanFramePort c = connect_unix_can_bus(bus.path());
  settle(bus);
  ASSERT_TRUE(a.send(frame_with(0x0CCB8081, 2)));
  settle(bus);
  const auto at_c = read_all(c);
  ASSERT_EQ(at_c.size(), 1u);  // only what was sent after c joined
  EXPECT_EQ(at_c[0].data[0], 2);
}

// A client that leaves (exits, is killed) takes the frames still queued in its socket with it: they never
// reached the bus, as a node switched off loses its transmit queue. Frames the bus took before go out.
TEST(CanBusRelay, AClientThatLeavesTakesItsQueuedFramesWithIt) {
  for (const bool paced : {false, true}) {
    SCOPED_TRACE(paced ? "paced" : "unpaced");
    TempDir dir;
    CanBusRelay bus(dir.file("bus"), CanBusTiming{paced, kIsobusBitRate});
    std::optional<CanFramePort> sender(connect_unix_can_bus(bus.path()));
    CanFramePort receiver = connect_unix_can_bus(bus.path());
    settle(bus);
    ASSERT_TRUE(sender->send(frame_with(0x18EEFF80, 0xA0)));
    for (int i = 0; i < 20 && receiver.wait_readable(0ms) == false; ++i) bus.run_once(5ms);
    ASSERT_EQ(read_all(receiver).size(), 1u) << "a client that stays: its frame goes out";
    for (int i = 0; i < 100; ++i) ASSERT_TRUE(sender->send(frame_with(0x18EEFF80, static_cast<std::uint8_t>(i))));
    sender.reset();  // leaves with 100 frames the bus has not taken
    for (int i = 0; i < 20; ++i) bus.run_once(5ms);
    EXPECT_EQ(read_all(receiver).size(), 0u);
    EXPECT_EQ(bus.counters().lost_with_sender, 100u);
    EXPECT_EQ(bus.counters().clients_left, 1u);
    EXPECT_EQ(bus.client_count(), 1u);
  }
}

TEST(CanBusRelay, AClientThatNeverReadsLosesFramesWithoutBlockingTheOthers) {
  TempDir dir;
  CanBusRelay bus(dir.file("bus"));
  CanFramePort sender = connect_unix_can_bus(bus.path());
  CanFramePort reader = connect_unix_can_bus(bus.path());
  CanFramePort sleeper = connect_unix_can_bus(bus.path());
  settle(bus);
  std::size_t received = 0;
  constexpr int kFrames = 20000;
  int sent = 0;
  while (sent < kFrames) {
    // Send in bursts the relay can take, and keep the reader reading, as a live process would.
    for (int i = 0; i < 32 && sent < kFrames; ++i) {
      if (!sender.send(frame_with(0x0CCB8081, static_cast<std::uint8_t>(sent)))) break;
      ++sent;
    }
    bus.run_once(0ms);
    received += read_all(reader).size();
  }
  for (int i = 0; i < 50; ++i) {
    bus.run_once(1ms);
    received += read_all(reader).size();
  }
  EXPECT_EQ(received, static_cast<std::size_t>(kFrames));
  EXPECT_GT(bus.counters().dropped_full, 0u);
  const auto drops = bus.drops_per_client();
  ASSERT_EQ(drops.size(), 3u);
  EXPECT_EQ(drops[1], 0u);
  EXPECT_EQ(drops[2], bus.counters().dropped_full);
  // What the sleeper finally reads is the frames that fitted, in order: none invented, none reordered.
  const auto kept = read_all(sleeper);
  EXPECT_EQ(kept.size() + drops[2], static_cast<std::size_t>(kFrames));
}

TEST(CanBusRelay, StaleSocketFileIsReplacedLiveServerAndOtherFilesAreRefused) {
  TempDir dir;
  const std::string path = dir.file("bus");
  {
    // A socket file nobody listens on any more: what a killed server leaves behind.
    const int fd = ::socket(AF_UNIX, SOCK_SEQPACKET, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    std::snprintf(address.sun_path, sizeof(address.sun_path), "%s", path.c_str());
    ASSERT_EQ(::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address)), 0);
    ::close(fd);
  }
  ASSERT_TRUE(std::filesystem::exists(path));
  EXPECT_THROW(connect_unix_can_bus(path), std::runtime_error);
  {
    CanBusRelay bus(path);
    CanFramePort a = connect_unix_can_bus(path);
    try {
      CanBusRelay second(path);
      FAIL() << "a second server replaced a live one";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("already served"), std::string::npos) << e.what();
    }
  }
  EXPECT_FALSE(std::filesystem::exists(path)) << "the socket file outlives its server";
  std::ofstream(dir.file("plain")) << "not a socket";
  EXPECT_THROW(CanBusRelay(dir.file("plain")), std::runtime_error);
  EXPECT_TRUE(std::filesystem::exists(dir.file("plain")));
}

TEST(UnixCanBus, ConnectErrorsNameThePath) {
  try {
    connect_unix_can_bus("/tmp/no-such-dir-for-canbus/bus");
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/tmp/no-such-dir-for-canbus/bus"), std::string::npos) << e.what();
  }
  EXPECT_THROW(connect_unix_can_bus(std::string(200, 'x')), std::runtime_error);
  EXPECT_EQ(can_bus_log_name("unix:/tmp/x"), "can0");
  EXPECT_EQ(can_bus_log_name("can1"), "can1");
}

#ifdef SPREAD_CANBUS_EXE
// The real executable: three clients, fan-out, a wrong-size and an empty datagram, a client leaving, and SIGTERM
// removing the socket file.
TEST(SpreadCanbusExecutable, RelaysBetweenThreeProcessesAndCleansUpOnSigterm) {
  TempDir dir;
  const std::string path = dir.file("bus");
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::execl(SPREAD_CANBUS_EXE, SPREAD_CANBUS_EXE, path.c_str(), "--duration", "20", static_cast<char*>(nullptr));
    std::_Exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + 5s;
  std::optional<CanFramePort> a;
  while (!a && std::chrono::steady_clock::now() < deadline) {
    try {
      a.emplace(connect_unix_can_bus(path));
    } catch (const std::runtime_error&) {
      std::this_thread::sleep_for(10ms);
    }
  }
  ASSERT_TRUE(a.has_value()) << "spread-canbus did not start serving " << path;
  std::optional<CanFramePort> b(connect_unix_can_bus(path));
  CanFramePort c = connect_unix_can_bus(path);
  // Connected is not yet accepted: wait until a frame from a reaches both others.
  auto receive_one = [](CanFramePort& port) -> std::optional<can_frame> {
    can_frame f{};
    if (!port.wait_readable(2s) || port.read(f) != ReadOutcome::kFrame) return std::nullopt;
    return f;
  };
  std::this_thread::sleep_for(100ms);
  ASSERT_TRUE(a->send(frame_with(0x18EAFF81, 0x11)));
  const auto b1 = receive_one(*b);
  const auto c1 = receive_one(c);
  ASSERT_TRUE(b1 && c1);
  EXPECT_EQ(b1->data[0], 0x11);
  EXPECT_EQ(c1->data[0], 0x11);
  EXPECT_FALSE(a->wait_readable(100ms)) << "the sender got its own frame back";
  const unsigned char junk[5] = {1, 2, 3, 4, 5};
  ASSERT_TRUE(c.send_raw(junk, sizeof(junk)));
  ASSERT_EQ(::send(c.fd(), "", 0, 0), 0);  // an empty datagram: dropped, c stays connected
  ASSERT_TRUE(c.send(frame_with(0x0CCB8081, 0x33)));
  const auto a2 = receive_one(*a);
  ASSERT_TRUE(a2);
  EXPECT_EQ(a2->data[0], 0x33) << "a wrong-size datagram was relayed or its sender dropped";
  ASSERT_TRUE(receive_one(*b));
  b.reset();  // b leaves; the bus goes on
  ASSERT_TRUE(a->send(frame_with(0x0CCB8081, 0x44)));
  const auto c3 = receive_one(c);
  ASSERT_TRUE(c3);
  EXPECT_EQ(c3->data[0], 0x44);
  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
  EXPECT_FALSE(std::filesystem::exists(path));
}
#endif

}  // namespace
}  // namespace spread::isobus::can
