// The ISO 11783 message codecs: the 29-bit identifier (ISO 11783-3), process data (ISO 11783-10) and the
// speed messages (ISO 11783-7), byte for byte.
#include <gtest/gtest.h>

#include <array>

#include "isobus/isobus_id.hpp"
#include "isobus/process_data.hpp"
#include "isobus/speed_messages.hpp"

namespace spread::isobus {
namespace {

TEST(IsobusId, DecodesTheDesignExample) {
  const IsobusId id = decode_id(0x0CCB8081);
  EXPECT_EQ(id.priority, 3);
  EXPECT_EQ(id.pgn, 0xCB00u);
  EXPECT_EQ(id.destination, 0x80);
  EXPECT_EQ(id.source, 0x81);
  EXPECT_EQ(encode_id(id), 0x0CCB8081u);
}

TEST(IsobusId, Pdu2KeepsGroupExtensionInPgn) {
  const IsobusId id{3, kGroundBasedSpeedPgn, 0x12 /* ignored for PDU2 */, 0xF0};
  const std::uint32_t raw = encode_id(id);
  EXPECT_EQ(raw, 0x0CFE49F0u);
  const IsobusId back = decode_id(raw);
  EXPECT_EQ(back.pgn, kGroundBasedSpeedPgn);
  EXPECT_EQ(back.destination, kGlobalAddress);
}

TEST(ProcessData, ByteLayoutMatchesIso11783_10) {
  // command 3, element 0x123, DDI 390, value 7 500 000 (= 750 r/min).
  const ProcessDataBytes b = encode_process_data({3, 0x123, 390, 7500000});
  const ProcessDataBytes expected{0x33, 0x12, 0x86, 0x01, 0xE0, 0x70, 0x72, 0x00};
  EXPECT_EQ(b, expected);
  const ProcessData back = decode_process_data(b);
  EXPECT_EQ(back.command, 3);
  EXPECT_EQ(back.element, 0x123);
  EXPECT_EQ(back.ddi, 390);
  EXPECT_EQ(back.value, 7500000);
  EXPECT_EQ(decode_process_data(encode_process_data({2, 0, 6, -5})).value, -5);
}

TEST(SpeedMessages, RoundTripAndNotAvailable) {
  const auto bytes = encode_speed(3.456, 1000, Direction::kForward);
  const auto speed = decode_speed(bytes);
  ASSERT_TRUE(speed.has_value());
  EXPECT_NEAR(speed->speed_m_s, 3.456, 1e-9);
  EXPECT_EQ(speed->direction, Direction::kForward);
  std::array<std::uint8_t, 8> unavailable{0xFF, 0xFF, 0, 0, 0, 0, 0xFF, 0xFF};
  EXPECT_FALSE(decode_speed(unavailable).has_value());
}

}  // namespace
}  // namespace spread::isobus
