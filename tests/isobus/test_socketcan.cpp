// SocketCAN (CAN_RAW): a clear error without kernel support or interface, and real frames on vcan0 when there is one.
#include <gtest/gtest.h>

#include <chrono>
#include <stdexcept>
#include <string>

#include "isobus/can/socketcan.hpp"

namespace spread::isobus::can {
namespace {

using namespace std::chrono_literals;

TEST(SocketCan, MissingSupportOrInterfaceIsAClearError) {
  try {
    open_socketcan("nosuchcan7");
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_TRUE(what.find("AF_CAN") != std::string::npos || what.find("nosuchcan7") != std::string::npos) << what;
  }
  EXPECT_THROW(open_socketcan(""), std::runtime_error);
}

TEST(SocketCan, RealCanRawOnVcan0) {
  if (!socketcan_available()) GTEST_SKIP() << "this kernel has no AF_CAN (SocketCAN): real CAN_RAW cannot be tested";
  CanFramePort a;
  try {
    a = open_socketcan("vcan0");
  } catch (const std::exception& e) {
    GTEST_SKIP() << "no vcan0 interface (ip link add vcan0 type vcan; ip link set vcan0 up): " << e.what();
  }
  CanFramePort b = open_socketcan("vcan0");
  const std::uint8_t data[8] = {1, 2, 3, 4, 5, 6, 7, 8};
  ASSERT_TRUE(a.send(make_frame(0x0CCB8081, data, 8)));
  ASSERT_TRUE(b.wait_readable(1s));
  can_frame frame{};
  ASSERT_EQ(b.read(frame), ReadOutcome::kFrame);
  EXPECT_EQ(frame.data[7], 8);
}

}  // namespace
}  // namespace spread::isobus::can
