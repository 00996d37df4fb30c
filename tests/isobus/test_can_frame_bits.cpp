// A classical CAN frame on the wire: bit counts with the frame's own stuff bits, their bounds, and the
// order bitwise arbitration puts frames in.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "isobus/can/can_frame_bits.hpp"
#include "isobus/can/can_frame_port.hpp"

namespace spread::isobus::can {
namespace {

can_frame extended(std::uint32_t id29, std::vector<std::uint8_t> data) {
  return make_frame(id29, data.data(), static_cast<std::uint8_t>(data.size()));
}

can_frame standard(std::uint32_t id11, std::vector<std::uint8_t> data) {
  can_frame f{};
  f.can_id = id11;
  f.len = static_cast<std::uint8_t>(data.size());
  std::copy(data.begin(), data.end(), f.data);
  return f;
}

// Expected counts from a separate computation: the CRC by polynomial long division, the stuffed stream
// built bit by bit and checked to hold no six equal bits, plus the 13 fixed-form bits.
TEST(CanFrameBits, CountsTheFramesOwnStuffBits) {
  EXPECT_EQ(can_frame_bit_count(extended(0x0CCB8081, {0x0A, 0, 6, 0, 0xA8, 0x61, 0, 0})), 142);
  EXPECT_EQ(can_frame_bit_count(extended(0x18EEFF80, {0x34, 0x12, 0, 0, 0, 0x80, 0x0A, 0x20})), 145);
  EXPECT_EQ(can_frame_bit_count(extended(0x00000000, {0, 0, 0, 0, 0, 0, 0, 0})), 150);
  EXPECT_EQ(can_frame_bit_count(extended(0x1FFFFFFF, {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF})), 149);
  EXPECT_EQ(can_frame_bit_count(extended(0x0CCB8081, {0, 1, 2, 3, 4, 5, 6, 7})), 144);
  EXPECT_EQ(can_frame_bit_count(standard(0x123, {1, 2, 3})), 75);
}

// An extended frame of 8 bytes: 131 bit times unstuffed, 160 at worst; at 250 kbit/s that is 1,908 and
// 1,562 frames/s.
TEST(CanFrameBits, ExtendedEightByteFrameLiesBetween131And160Bits) {
  const can_frame f = extended(0x18FF0080, {1, 2, 3, 4, 5, 6, 7, 8});
  EXPECT_EQ(can_frame_bit_count_unstuffed(f), 131);
  EXPECT_EQ(can_frame_bit_count_worst_case(f), 160);
  EXPECT_EQ(can_frame_bit_count_unstuffed(standard(0x100, {})), 47);  // 19 + 15 + 13
  std::mt19937 random(7);
  for (int i = 0; i < 2000; ++i) {
    std::vector<std::uint8_t> data(random() % 9);
    for (auto& b : data) b = static_cast<std::uint8_t>(random());
    const can_frame g = extended(random() & CAN_EFF_MASK, data);
    const int bits = can_frame_bit_count(g);
    ASSERT_GE(bits, can_frame_bit_count_unstuffed(g));
    ASSERT_LE(bits, can_frame_bit_count_worst_case(g));
  }
}

TEST(CanFrameBits, ArbitrationPutsTheLowerIdentifierFirst) {
  const auto key = [](const can_frame& f) { return can_arbitration_key(f); };
  // ISOBUS: priority 3 process data beats priority 6 address claims, and a lower source address wins
  // between two equal PGNs.
  EXPECT_LT(key(extended(0x0CCB8081, {})), key(extended(0x18EEFF80, {})));
  EXPECT_LT(key(extended(0x0CCB8080, {})), key(extended(0x0CCB8081, {})));
  // A standard frame beats an extended frame with the same 11 leading identifier bits (its IDE is
  // dominant), and loses to one whose leading bits are lower.
  EXPECT_LT(key(standard(0x333, {})), key(extended(0x333U << 18, {})));
  EXPECT_LT(key(extended(0x332U << 18 | 0x3FFFF, {})), key(standard(0x333, {})));
  // Data beats remote with the same identifier.
  can_frame remote = extended(0x18EAFF80, {});
  remote.can_id |= CAN_RTR_FLAG;
  EXPECT_LT(key(extended(0x18EAFF80, {})), key(remote));
}

}  // namespace
}  // namespace spread::isobus::can
