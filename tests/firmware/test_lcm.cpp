// LCM end to end: in-process over memq://, and over udpm:// inside a private network namespace the test
// creates itself (re-executing this binary under `unshare -n`), never on the machine's interfaces.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include "libspread/control/ecu.hpp"
#include "firmware_sim/ecu/fixed_rate_loop.hpp"
#include "firmware_sim/lcm/lcm_ecu_link.hpp"
#include "lcm_link/lcm_payload.hpp"
#include "lcm_link/lcm_tractor_link.hpp"

namespace spread::firmware {
namespace {

using namespace lcm_link;

using namespace std::chrono_literals;

spread::command_t manual_command(std::int64_t sequence) {
  spread::command_t c{};
  c.sequence = sequence;
  c.mode = spread::command_t::MODE_MANUAL;
  c.rate_setpoint_kg_ha = 200.0;
  c.width_setpoint_m = 24.0;
  c.ground_speed_m_s = 12.0 / 3.6;
  c.material = "urea";
  c.rpm_setpoint = 750.0;
  c.work_state = true;
  c.num_sections = 8;
  c.section_on.assign(8, true);
  return c;
}

std::vector<std::uint8_t> encode(const spread::command_t& c) {
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(c.getEncodedSize()));
  c.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

// One LCM instance (memq is per instance) shared by the ECU link and the tractor link.
class Memq : public ::testing::Test {
 protected:
  Memq()
      : lcm_("memq://"),
        ecu_(clock_, parameters()),
        ecu_link_(lcm_, ecu_, channels_with_prefix("TEST_")),
        tractor_(lcm_, channels_with_prefix("TEST_")),
        loop_(clock_, 20.0) {
    ecu_link_.attach_loop(&loop_);
  }
  static EcuParameters parameters() {
    EcuParameters p;
    p.command_timeout = 0s;
    return p;
  }
  void ticks(int n) {
    for (int i = 0; i < n; ++i) loop_.tick(ecu_, ecu_link_);
    tractor_.handle(0ns);  // deliver the last status
  }
  const spread::status_t& status() {
    EXPECT_TRUE(tractor_.latest_status().has_value());
    return *tractor_.latest_status();
  }

  ManualClock clock_;
  lcm::LCM lcm_;
  Ecu ecu_;
  LcmEcuLink ecu_link_;
  LcmTractorLink tractor_;
  FixedRateLoop loop_;
};

TEST_F(Memq, CommandInStatusOutHeartbeat) {
  ASSERT_TRUE(tractor_.send(manual_command(1)));
  ticks(100);  // 5 s
  const spread::status_t& s = status();
  EXPECT_EQ(s.last_command_sequence, 1);
  EXPECT_EQ(s.material, "urea");
  EXPECT_NEAR(s.rpm_actual, 750.0 * (1.0 - std::exp(-5.0 / 0.8)), 1e-6);
  EXPECT_NEAR(s.mass_flow_kg_s, 1.6, 1e-9);
  EXPECT_EQ(s.num_sections, 8);
  EXPECT_TRUE(s.work_state_actual);
  EXPECT_TRUE(std::isnan(s.throw_width_m)) << "no tables loaded";
  EXPECT_EQ(s.fault_codes, 0);
  EXPECT_EQ(s.num_fault_counts, static_cast<int>(kFaultCount));
  EXPECT_EQ(tractor_.statuses_received(), 100u);
  EXPECT_EQ(tractor_.heartbeats_received(), 5u) << "1 Hz over 5 s";
  ASSERT_TRUE(tractor_.latest_heartbeat().has_value());
  EXPECT_EQ(tractor_.latest_heartbeat()->loop_rate_mhz, 20000);
  EXPECT_EQ(ecu_link_.counters().commands_accepted, 1u);
}

TEST_F(Memq, SectionsFromTheCommand) {
  spread::command_t c = manual_command(1);
  c.section_on[6] = false;
  c.section_on[7] = false;
  ASSERT_TRUE(tractor_.send(c));
  ticks(100);  // the disc reaches its speed: metering opens
  // No tables: the right disc cannot be narrowed to section 6, so sections 7 and 8 are still spread.
  EXPECT_NEAR(status().width_actual_m, 24.0, 1e-12);
  EXPECT_FALSE(status().section_on[7]);
  EXPECT_TRUE(status().section_actual_on[7]);
  // The right side off entirely: its disc's flow closes.
  c = manual_command(2);
  for (int i = 4; i < 8; ++i) c.section_on[static_cast<std::size_t>(i)] = false;
  ASSERT_TRUE(tractor_.send(c));
  ticks(2);
  EXPECT_NEAR(status().width_actual_m, 12.0, 1e-12);
  EXPECT_FALSE(status().section_actual_on[4]);
  EXPECT_EQ(status().disc_flow_fraction[0], 1.0);
  EXPECT_EQ(status().disc_flow_fraction[1], 0.0);
  EXPECT_NEAR(status().mass_flow_kg_s, 0.8, 1e-9);
}

// The border and wind fields reach the ECU and come back in the status; wind compensation without tables
// is refused as a whole command.
TEST_F(Memq, BorderAndWindFromTheCommand) {
  spread::command_t c = manual_command(1);
  c.border_mode = spread::command_t::FIELD_EDGE_LEFT;
  c.border_gap_m = 1.0;
  c.wind_m_s[0] = 2.0;
  c.wind_m_s[1] = -1.0;
  ASSERT_TRUE(tractor_.send(c));
  ticks(2);
  EXPECT_EQ(status().border_mode, +spread::command_t::FIELD_EDGE_LEFT);
  EXPECT_FALSE(status().border_applied) << "no tables: nothing to plan the border with";
  EXPECT_EQ(ecu_.status().border_gap_m, 1.0);
  EXPECT_EQ(ecu_.status().wind_x_m_s, 2.0);
  EXPECT_EQ(ecu_.status().wind_y_m_s, -1.0);
  c = manual_command(2);
  c.wind_compensation = true;
  ASSERT_TRUE(tractor_.send(c));
  ticks(2);
  EXPECT_EQ(status().last_command_sequence, 1) << "refused whole";
  EXPECT_FALSE(status().wind_compensated);
  c = manual_command(3);
  c.border_mode = 9;
  ASSERT_TRUE(tractor_.send(c));
  ticks(2);
  EXPECT_EQ(status().last_command_sequence, 1);
  EXPECT_EQ(status().border_mode, +spread::command_t::FIELD_EDGE_LEFT);
}

TEST_F(Memq, WrongFingerprintIsCounted) {
  spread::heartbeat_t other{};
  other.node = "impostor";
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(other.getEncodedSize()));
  other.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  ASSERT_TRUE(tractor_.send_raw(bytes.data(), static_cast<unsigned>(bytes.size())));
  ticks(2);
  EXPECT_EQ(status().rejected_wrong_fingerprint, 1);
  EXPECT_NE(status().fault_codes & static_cast<std::int32_t>(fault_bit(Fault::kLcmWrongFingerprint)), 0);
  EXPECT_EQ(status().last_command_sequence, -1);
}

TEST_F(Memq, UndecodablePayloadsAreCountedNotFatal) {
  std::vector<std::uint8_t> good = encode(manual_command(1));
  // 1: shorter than a fingerprint. 2: truncated body. 3: trailing garbage.
  const std::uint8_t tiny[3] = {1, 2, 3};
  ASSERT_TRUE(tractor_.send_raw(tiny, sizeof(tiny)));
  ASSERT_TRUE(tractor_.send_raw(good.data(), static_cast<unsigned>(good.size() - 5)));
  std::vector<std::uint8_t> longer = good;
  longer.push_back(0);
  ASSERT_TRUE(tractor_.send_raw(longer.data(), static_cast<unsigned>(longer.size())));
  // 4: hostile string length (-1), 5: hostile array count (-1): lcm-gen's decoder would throw.
  std::vector<std::uint8_t> bad_string = good;
  const std::size_t string_length_at = 8 + 8 + 8 + 1 + 8 + 8 + 8;
  for (int i = 0; i < 4; ++i) bad_string[string_length_at + static_cast<std::size_t>(i)] = 0xFF;
  ASSERT_TRUE(tractor_.send_raw(bad_string.data(), static_cast<unsigned>(bad_string.size())));
  std::vector<std::uint8_t> bad_count = good;
  const std::size_t count_at = string_length_at + 4 + 5 /* "urea\0" */ + 8 + 1 /* rpm, work_state */;
  ASSERT_EQ(bad_count[count_at], 8);
  bad_count[count_at] = 0xFF;
  ASSERT_TRUE(tractor_.send_raw(bad_count.data(), static_cast<unsigned>(bad_count.size())));
  ticks(2);
  EXPECT_EQ(status().rejected_undecodable, 5);
  EXPECT_EQ(status().last_command_sequence, -1);
  // The link still works.
  ASSERT_TRUE(tractor_.send(manual_command(2)));
  ticks(1);
  EXPECT_EQ(status().last_command_sequence, 2);
}

TEST_F(Memq, InvalidCommandsAreRejectedAndCounted) {
  ASSERT_TRUE(tractor_.send(manual_command(5)));
  spread::command_t nan_rate = manual_command(6);
  nan_rate.rate_setpoint_kg_ha = std::numeric_limits<double>::quiet_NaN();
  ASSERT_TRUE(tractor_.send(nan_rate));
  spread::command_t too_wide = manual_command(7);
  too_wide.width_setpoint_m = 80.0;
  ASSERT_TRUE(tractor_.send(too_wide));
  spread::command_t bad_mode = manual_command(8);
  bad_mode.mode = 9;
  ASSERT_TRUE(tractor_.send(bad_mode));
  spread::command_t automatic = manual_command(9);  // no tables loaded
  automatic.mode = spread::command_t::MODE_AUTOMATIC;
  ASSERT_TRUE(tractor_.send(automatic));
  ASSERT_TRUE(tractor_.send(manual_command(5)));  // replay of an old command
  spread::command_t too_many = manual_command(10);
  too_many.num_sections = 20;
  too_many.section_on.assign(20, true);
  ASSERT_TRUE(tractor_.send(too_many));
  ticks(2);
  const spread::status_t& s = status();
  EXPECT_EQ(s.last_command_sequence, 5);
  EXPECT_EQ(s.rate_setpoint_kg_ha, 200.0);
  EXPECT_EQ(s.rejected_invalid, 5);
  EXPECT_EQ(s.rejected_stale, 1);
  EXPECT_EQ(s.fault_counts[static_cast<std::size_t>(Fault::kNotANumber)], 1);
  EXPECT_EQ(s.fault_counts[static_cast<std::size_t>(Fault::kUnknownMode)], 1);
  EXPECT_EQ(s.fault_counts[static_cast<std::size_t>(Fault::kAutomaticUnavailable)], 1);
  EXPECT_EQ(s.fault_counts[static_cast<std::size_t>(Fault::kSetpointOutOfRange)], 2);
}

// ---- length fields checked before lcm-gen's decoder (fuzz finding, docs/stability.md) --------------

template <typename Message>
std::vector<std::uint8_t> encode_any(const Message& m) {
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(m.getEncodedSize()));
  EXPECT_EQ(m.encode(bytes.data(), 0, static_cast<int>(bytes.size())), static_cast<int>(bytes.size()));
  return bytes;
}

spread::status_t sample_status(const std::string& material, int sections, int fault_counts) {
  spread::status_t s{};
  s.material = material;
  s.num_sections = static_cast<std::int8_t>(sections);
  s.section_on.assign(static_cast<std::size_t>(sections), true);
  s.section_actual_on.assign(static_cast<std::size_t>(sections), true);
  s.num_fault_counts = static_cast<std::int8_t>(fault_counts);
  s.fault_counts.assign(static_cast<std::size_t>(fault_counts), 7);
  return s;
}

// The hand-written layouts in lcm_payload.hpp follow the .lcm files: every encoding lcm-gen produces,
// with empty and long strings and empty and full arrays, is valid; one byte less or more is not.
template <typename Message>
void expect_layout_exact(const Message& m) {
  std::vector<std::uint8_t> bytes = encode_any(m);
  EXPECT_TRUE(payload_layout_valid<Message>(bytes.data(), static_cast<std::uint32_t>(bytes.size())));
  EXPECT_FALSE(payload_layout_valid<Message>(bytes.data(), static_cast<std::uint32_t>(bytes.size() - 1)));
  bytes.push_back(0);
  EXPECT_FALSE(payload_layout_valid<Message>(bytes.data(), static_cast<std::uint32_t>(bytes.size())));
}

TEST(LcmPayload, LayoutMatchesTheGeneratedEncoder) {
  for (const std::string& text : {std::string(), std::string("u"), std::string(63, 'x')}) {
    for (int n : {0, 1, 16}) {
      spread::command_t c = manual_command(1);
      c.material = text;
      c.num_sections = static_cast<std::int8_t>(n);
      c.section_on.assign(static_cast<std::size_t>(n), true);
      expect_layout_exact(c);
      expect_layout_exact(sample_status(text, n, 16 - n));
    }
    spread::heartbeat_t h{};
    h.node = text;
    expect_layout_exact(h);
  }
}

// Writes a big-endian int32 at `at`.
void put_int32(std::vector<std::uint8_t>& bytes, std::size_t at, std::int32_t value) {
  const auto u = static_cast<std::uint32_t>(value);
  for (int i = 0; i < 4; ++i) bytes[at + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(u >> (24 - 8 * i));
}

constexpr std::int32_t kHostileLengths[] = {std::numeric_limits<std::int32_t>::min(), -2, -1, 0,
                                            std::numeric_limits<std::int32_t>::max(), 1000};

// The fuzzer's finding: status_t with material length INT32_MIN made lcm-gen's decoder overflow and
// then assign ~2^64 bytes (SIGSEGV). Every such length is now undecodable before the decoder runs.
TEST(LcmPayload, HostileStringLengthsAreUndecodableNotACrash) {
  const std::size_t status_material_at = 8 + 8 + 8 + 8 + 1;
  const std::vector<std::uint8_t> status_bytes = encode_any(sample_status("urea", 8, 4));
  const std::size_t command_material_at = 8 + 8 + 8 + 1 + 8 + 8 + 8;
  const std::vector<std::uint8_t> command_bytes = encode(manual_command(1));
  spread::heartbeat_t h{};
  h.node = "firmware_sim";
  const std::vector<std::uint8_t> heartbeat_bytes = encode_any(h);
  for (const std::int32_t length : kHostileLengths) {
    SCOPED_TRACE(length);
    std::vector<std::uint8_t> s = status_bytes;
    put_int32(s, status_material_at, length);
    spread::status_t status_out{};
    EXPECT_EQ(decode_checked(s.data(), static_cast<std::uint32_t>(s.size()), status_out), DecodeOutcome::kUndecodable);
    std::vector<std::uint8_t> c = command_bytes;
    put_int32(c, command_material_at, length);
    spread::command_t command_out{};
    EXPECT_EQ(decode_checked(c.data(), static_cast<std::uint32_t>(c.size()), command_out), DecodeOutcome::kUndecodable);
    std::vector<std::uint8_t> b = heartbeat_bytes;
    put_int32(b, 8 + 8 + 8, length);
    spread::heartbeat_t heartbeat_out{};
    EXPECT_EQ(decode_checked(b.data(), static_cast<std::uint32_t>(b.size()), heartbeat_out), DecodeOutcome::kUndecodable);
  }
  // Negative array counts (num_sections, num_fault_counts) likewise.
  std::vector<std::uint8_t> s = status_bytes;
  const std::size_t sections_at = status_material_at + 4 + 5 + 14 * 8 + 3;  // 14 doubles before the flags
  ASSERT_EQ(s[sections_at], 8);
  s[sections_at] = 0x80;
  spread::status_t status_out{};
  EXPECT_EQ(decode_checked(s.data(), static_cast<std::uint32_t>(s.size()), status_out), DecodeOutcome::kUndecodable);
  s = status_bytes;
  ASSERT_EQ(s[s.size() - 4 * 8 - 1], 4);
  s[s.size() - 4 * 8 - 1] = 0xFF;
  EXPECT_EQ(decode_checked(s.data(), static_cast<std::uint32_t>(s.size()), status_out), DecodeOutcome::kUndecodable);
}

// On the ECU side: command_t with a hostile material length is counted as undecodable (the existing
// fault counter) and the link keeps working.
TEST_F(Memq, HostileCommandStringLengthIsCountedAsUndecodable) {
  const std::size_t material_at = 8 + 8 + 8 + 1 + 8 + 8 + 8;
  for (const std::int32_t length : kHostileLengths) {
    std::vector<std::uint8_t> bytes = encode(manual_command(1));
    put_int32(bytes, material_at, length);
    ASSERT_TRUE(tractor_.send_raw(bytes.data(), static_cast<unsigned>(bytes.size())));
  }
  ticks(2);
  EXPECT_EQ(status().rejected_undecodable, static_cast<std::int64_t>(std::size(kHostileLengths)));
  EXPECT_NE(status().fault_codes & static_cast<std::int32_t>(fault_bit(Fault::kLcmUndecodable)), 0);
  EXPECT_EQ(status().last_command_sequence, -1);
  ASSERT_TRUE(tractor_.send(manual_command(2)));
  ticks(1);
  EXPECT_EQ(status().last_command_sequence, 2);
}

// ---- udpm:// in a private network namespace -------------------------------------------------------

constexpr const char* kInNamespaceVariable = "SPREAD_FIRMWARE_IN_NETNS";

// Re-runs this binary for `test_name` inside `unshare -n` with multicast routed over lo. Returns
// false with `why` when namespaces are not permitted here and we are not root (as root, `unshare -n`
// must work: its failure is a test failure, not a skip). The inner run must report its one test
// PASSED: an exit status 0 alone would also come from a filter that matched nothing.
bool run_in_private_network(const std::string& test_name, std::string& why) {
  if (std::system("unshare -n true >/dev/null 2>&1") != 0) {
    why = "unshare -n is not permitted here (needs CAP_SYS_ADMIN or user namespaces)";
    EXPECT_NE(::geteuid(), 0u) << "running as root, yet " << why;
    return false;
  }
  char self[4096];
  const ssize_t n = ::readlink("/proc/self/exe", self, sizeof(self) - 1);
  if (n <= 0) {
    why = "cannot resolve /proc/self/exe";
    ADD_FAILURE() << why;
    return false;
  }
  self[n] = '\0';
  const std::string command = std::string("unshare -n sh -c 'ip link set lo up && ip link set lo multicast on && "
                                          "ip route add 224.0.0.0/4 dev lo && ") +
                              kInNamespaceVariable + "=1 exec \"$0\" --gtest_filter=" + test_name + "' '" + self +
                              "' 2>&1";
  std::string output;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) {
    ADD_FAILURE() << "popen failed: " << command;
    return true;
  }
  char buffer[4096];
  std::size_t got = 0;
  while ((got = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) output.append(buffer, got);
  const int rc = ::pclose(pipe);
  EXPECT_EQ(rc, 0) << "inside the namespace: " << command << "\n" << output;
  EXPECT_NE(output.find("[  PASSED  ] 1 test."), std::string::npos)
      << "the inner run did not pass exactly one test:\n" << output;
  EXPECT_EQ(output.find("[  SKIPPED ]"), std::string::npos) << output;
  return true;
}

TEST(Udpm, EndToEndInPrivateNetworkNamespace) {
  if (std::getenv(kInNamespaceVariable) == nullptr) {
    std::string why;
    if (!run_in_private_network("Udpm.EndToEndInPrivateNetworkNamespace", why)) GTEST_SKIP() << why;
    return;
  }
  // Inside the namespace: a real ECU loop on the steady clock, and a separate LCM instance as tractor.
  const std::string url = "udpm://239.255.76.67:7711?ttl=0";  // port reserved for this test
  lcm::LCM ecu_lcm(url);
  lcm::LCM tractor_lcm(url);
  ASSERT_TRUE(ecu_lcm.good() && tractor_lcm.good()) << "udpm provider failed to start in the namespace";
  SteadyClock clock;
  EcuParameters p;
  p.command_timeout = 0s;
  Ecu ecu(clock, p);
  LcmEcuLink ecu_link(ecu_lcm, ecu, channels_with_prefix("NETNS_"));
  FixedRateLoop loop(clock, 20.0);
  std::atomic<bool> stop{false};
  std::thread ecu_thread([&] { loop.run(ecu, ecu_link, 10s, &stop); });

  LcmTractorLink tractor(tractor_lcm, channels_with_prefix("NETNS_"));
  const spread::command_t command = manual_command(42);
  const bool accepted = tractor.wait_for(
      [&] {
        tractor.send(command);
        return tractor.latest_status() && tractor.latest_status()->last_command_sequence == 42;
      },
      5s);
  // Metering opens once the disc has spun up to within 5 % of 750 r/min (3 time constants, 2.4 s).
  const bool metering = tractor.wait_for(
      [&] { return tractor.latest_status() && tractor.latest_status()->work_state_actual; }, 6s);
  const bool heartbeat = tractor.wait_for([&] { return tractor.heartbeats_received() > 0; }, 3s);
  stop = true;
  ecu_thread.join();
  ASSERT_TRUE(accepted) << "no status acknowledging the command over udpm";
  EXPECT_TRUE(metering);
  EXPECT_TRUE(heartbeat);
  EXPECT_EQ(tractor.latest_status()->material, "urea");
  EXPECT_NEAR(tractor.latest_status()->mass_flow_kg_s, 1.6, 1e-9);
  EXPECT_EQ(tractor.undecodable_received(), 0u);
}

}  // namespace
}  // namespace spread::firmware
