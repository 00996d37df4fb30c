// candump logs (can-utils' text format): parsing, writing with wall-clock time, and bad lines named by number.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "isobus/can/candump_log.hpp"
#include "libspread/core/clock.hpp"

namespace spread::isobus::can {
namespace {

TEST(Candump, ParsesAndFormatsLines) {
  std::string error;
  const auto record = parse_candump_line("(1700000000.123456) can0 0CCB8081#0306000064000000", error);
  ASSERT_TRUE(record.has_value()) << error;
  EXPECT_EQ(record->interface, "can0");
  EXPECT_EQ(record->frame.can_id, 0x0CCB8081u | CAN_EFF_FLAG);
  EXPECT_EQ(record->frame.len, 8);
  EXPECT_EQ(record->frame.data[4], 0x64);
  EXPECT_EQ(record->time, Nanoseconds(1700000000123456000));
  EXPECT_EQ(format_candump_line(record->time, "can0", record->frame),
            "(1700000000.123456) can0 0CCB8081#0306000064000000");
  const auto standard = parse_candump_line("(0000000001.000000) can1 123#DEAD", error);
  ASSERT_TRUE(standard.has_value()) << error;
  EXPECT_EQ(standard->frame.can_id, 0x123u);
  EXPECT_EQ(standard->frame.len, 2);
  // Remote frames as can-utils writes them: `ID#R`, or with the length `ID#R8`.
  for (const char* line : {"(1.000000) can0 123#R", "(1.000000) can0 18EA0080#R3"}) {
    const auto remote = parse_candump_line(line, error);
    ASSERT_TRUE(remote.has_value()) << line << ": " << error;
    EXPECT_NE(remote->frame.can_id & CAN_RTR_FLAG, 0u);
    EXPECT_EQ(format_candump_line(remote->time, "can0", remote->frame), std::string(line).replace(1, 0, "000000000"));
  }
  EXPECT_FALSE(parse_candump_line("(1.000000) can0 123#R9", error).has_value());
  EXPECT_NE(error.find("remote frame length"), std::string::npos) << error;
}

TEST(Candump, RecordingsCarryWallClockTime) {
  // A live recording runs on the monotonic clock; the writer adds the wall-clock offset, as candump does.
  ManualClock monotonic(std::chrono::seconds(1234));  // e.g. time since boot
  const Nanoseconds epoch_offset = std::chrono::seconds(1700000000) - std::chrono::seconds(1234);
  std::ostringstream out;
  CandumpWriter writer(out, monotonic, "can0", epoch_offset);
  const std::uint8_t data[1] = {0xAB};
  ASSERT_TRUE(writer.send(make_frame(0x18EEFF80, data, 1)));
  EXPECT_EQ(out.str(), "(1700000000.000000) can0 18EEFF80#AB\n");
}

TEST(Candump, BadLinesAreReportedWithLineNumbers) {
  std::istringstream in(
      "(1.000000) can0 0CCB8081#03\n"
      "garbage\n"
      "(1.000000) can0 0CCB8081#0G\n"
      "(1.000000) can0 0CCB8081##0011\n"
      "(1.000000) can0 3FFFFFFF1#00\n"
      "(1.5) can0 0CCB8081#00\n"
      "\n"
      "(2.000000) can0 0CCB8081#030600006400000000\n");
  const CandumpLog log = read_candump_log(in);
  EXPECT_EQ(log.records.size(), 1u);
  ASSERT_EQ(log.errors.size(), 6u);
  EXPECT_NE(log.errors[0].find("line 2"), std::string::npos) << log.errors[0];
  EXPECT_NE(log.errors[2].find("CAN FD"), std::string::npos) << log.errors[2];
}

// Fuzz finding (docs/stability.md): a huge seconds part overflowed the int64 nanosecond conversion (UB)
// and the record printed as a negative time. The largest representable second still parses and round
// trips; one more, and the fuzzer's 17100000002 s = year 2511, are bad lines naming the line.
TEST(Candump, TimestampsBeyondTheNanosecondRangeAreBadLines) {
  std::string error;
  const std::string last = "(" + std::to_string(kMaxCandumpSeconds) + ".999999) can0 0CCB8081#00";
  const auto record = parse_candump_line(last, error);
  ASSERT_TRUE(record.has_value()) << error;
  EXPECT_EQ(record->time.count(), static_cast<std::int64_t>(kMaxCandumpSeconds) * 1000000000 + 999999000);
  EXPECT_EQ(format_candump_line(record->time, "can0", record->frame), last);
  std::istringstream in("(1.000000) can0 0CCB8081#00\n"
                        "(" + std::to_string(kMaxCandumpSeconds + 1) + ".000000) can0 0CCB8081#00\n"
                        "(17100000002.010000) can0 0CCB8081#0200070000000000\n"
                        "(18446744073709551615.999999) can0 0CCB8081#00\n");
  const CandumpLog log = read_candump_log(in);
  ASSERT_EQ(log.records.size(), 1u);
  ASSERT_EQ(log.errors.size(), 3u);
  for (std::size_t i = 0; i < log.errors.size(); ++i) {
    EXPECT_EQ(log.errors[i].rfind("line " + std::to_string(i + 2) + ": timestamp (", 0), 0u) << log.errors[i];
    EXPECT_NE(log.errors[i].find("beyond the representable range"), std::string::npos) << log.errors[i];
  }
}

}  // namespace
}  // namespace spread::isobus::can
