// The ECU's partner task controller (ISO 11783-10 partners, known by ISO 11783-5 NAMEs): who may become it,
// and each way the partnership ends.
#include <gtest/gtest.h>

#include "isobus/address_claim.hpp"
#include "isobus/iso_name.hpp"
#include "isobus/tc_partner.hpp"

namespace spread::isobus {
namespace {

using namespace std::chrono_literals;

std::uint64_t name(std::uint8_t device_class, std::uint8_t function, std::uint32_t identity) {
  IsoName n;
  n.device_class = device_class;
  n.function = function;
  n.identity_number = identity;
  return encode_name(n);
}
const std::uint64_t kTc = name(kDeviceClassNonSpecific, kFunctionTaskController, 1);
const std::uint64_t kOtherTc = name(kDeviceClassNonSpecific, kFunctionTaskController, 2);

TEST(TcPartner, OnlyAClaimedTaskControllerBecomesThePartner) {
  TaskControllerPartner p;
  using S = TaskControllerPartner::Status;
  EXPECT_EQ(p.on_tc_status(0xF8, 0s), S::kNotATc) << "never claimed an address";
  // Function 130 of device class 5 (fertilisers) is product pressure, not a task controller.
  p.on_address_claimed(0x90, name(5, kFunctionTaskController, 3));
  EXPECT_EQ(p.on_tc_status(0x90, 0s), S::kNotATc);
  p.on_address_claimed(0x81, kTc);
  EXPECT_EQ(p.on_tc_status(0x81, 1s), S::kPartner);
  EXPECT_TRUE(p.is_partner(0x81));
  EXPECT_EQ(p.name(), kTc);
  p.on_address_claimed(0xF7, kOtherTc);
  EXPECT_EQ(p.on_tc_status(0xF7, 1s), S::kOtherTc) << "one partner at a time";
  EXPECT_FALSE(p.is_partner(0xF7));
  EXPECT_EQ(p.counters().status_not_from_a_tc, 2u);
  EXPECT_EQ(p.counters().status_from_other_tc, 1u);
}

TEST(TcPartner, EndsWhenSilentOrItsAddressChangesHands) {
  auto partnered = [] {
    TaskControllerPartner p;
    p.on_address_claimed(0x81, kTc);
    p.on_tc_status(0x81, 0s);
    return p;
  };
  {
    TaskControllerPartner p = partnered();
    EXPECT_FALSE(p.update(6s, 6s)) << "6 s is still in time";
    EXPECT_TRUE(p.update(6s + 1ms, 6s));
    EXPECT_FALSE(p.address().has_value());
    EXPECT_EQ(p.last_loss(), "its TC status stopped");
  }
  {
    TaskControllerPartner p = partnered();
    EXPECT_FALSE(p.on_address_claimed(0x81, kTc)) << "its own claim again (answer to a request)";
    EXPECT_TRUE(p.on_address_claimed(0x81, kOtherTc)) << "another NAME took its address";
    EXPECT_FALSE(p.is_partner(0x81));
    // The newcomer at 0x81 is a TC too, and may become the partner with its own status.
    EXPECT_EQ(p.on_tc_status(0x81, 1s), TaskControllerPartner::Status::kPartner);
    EXPECT_EQ(p.name(), kOtherTc);
  }
  {
    TaskControllerPartner p = partnered();
    EXPECT_TRUE(p.on_address_claimed(kNullAddress, kTc)) << "it says it cannot claim";
  }
  {
    TaskControllerPartner p = partnered();
    EXPECT_TRUE(p.on_address_claimed(0x82, kTc)) << "it moved to another address";
    EXPECT_EQ(p.counters().partners_lost, 1u);
  }
}

}  // namespace
}  // namespace spread::isobus
