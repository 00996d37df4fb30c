// ISO 11783-5 network management: the NAME layout and the address-claim state machine (start, 250 ms settle,
// contention won and lost, self-configurable re-claim, cannot-claim, requests). The ECU on top of it is
// tests/firmware/test_networked_ecu.cpp.
#include <gtest/gtest.h>

#include <vector>

#include "isobus/address_claim.hpp"
#include "isobus/iso_name.hpp"

namespace spread::isobus {
namespace {

using namespace std::chrono_literals;

TEST(IsoName, FieldsSitWhereIso11783_5PutsThem) {
  const IsoName spreader;  // the ECU's default: agriculture, fertilisers, rate control
  EXPECT_EQ(encode_name(spreader), 0x200A800000001234ull);
  IsoName all;
  all.self_configurable = true;
  all.industry_group = 7;
  all.device_class_instance = 0xF;
  all.device_class = 0x7F;
  all.function = 0xFF;
  all.function_instance = 0x1F;
  all.ecu_instance = 7;
  all.manufacturer_code = 0x7FF;
  all.identity_number = 0x1FFFFF;
  EXPECT_EQ(encode_name(all), 0xFFFEFFFFFFFFFFFFull) << "only the reserved bit 48 stays 0";
  IsoName one;
  one = IsoName{false, 0, 0, 0, 0, 0, 0, 0, 0};
  one.manufacturer_code = 1;
  EXPECT_EQ(encode_name(one), 1ull << 21);
  one = IsoName{false, 0, 0, 0, 0, 0, 0, 0, 0};
  one.ecu_instance = 1;
  EXPECT_EQ(encode_name(one), 1ull << 32);
  one = IsoName{false, 0, 0, 0, 0, 0, 0, 0, 0};
  one.function_instance = 1;
  EXPECT_EQ(encode_name(one), 1ull << 35);
  one = IsoName{false, 0, 0, 0, 0, 0, 0, 0, 0};
  one.device_class_instance = 1;
  EXPECT_EQ(encode_name(one), 1ull << 56);
  const IsoName back = decode_name(encode_name(all));
  EXPECT_EQ(encode_name(back), encode_name(all));
  EXPECT_EQ(check_name(all), "");
}

TEST(IsoName, OutOfWidthFieldsBytesAndHex) {
  IsoName n;
  n.identity_number = 1u << 21;
  EXPECT_EQ(check_name(n), "identity number above 2097151");
  n = IsoName{};
  n.manufacturer_code = 2048;
  EXPECT_EQ(check_name(n), "manufacturer code above 2047");
  n = IsoName{};
  n.device_class = 128;
  EXPECT_NE(check_name(n), "");
  const auto bytes = name_to_bytes(0x200A800000001234ull);
  const std::array<std::uint8_t, 8> expected{0x34, 0x12, 0x00, 0x00, 0x00, 0x80, 0x0A, 0x20};
  EXPECT_EQ(bytes, expected);  // little-endian on the bus, as in the recorded replay answers
  EXPECT_EQ(name_from_bytes(bytes.data()), 0x200A800000001234ull);
  EXPECT_EQ(parse_name_hex("0x200A800000001234"), 0x200A800000001234ull);
  EXPECT_EQ(parse_name_hex("a00a800000001234"), 0xA00A800000001234ull);
  EXPECT_FALSE(parse_name_hex("0x"));
  EXPECT_FALSE(parse_name_hex("12345678901234567"));
  EXPECT_FALSE(parse_name_hex("12G4"));
  EXPECT_NE(describe_name(0x200A800000001234ull).find("function 128"), std::string::npos);
}

std::uint64_t name_with(bool self_configurable, std::uint32_t identity) {
  IsoName n;
  n.self_configurable = self_configurable;
  n.identity_number = identity;
  return encode_name(n);
}

TEST(AddressClaim, ClaimsAtStartAndMaySendAfter250Ms) {
  AddressClaim claim(name_with(false, 10), 0x80);
  EXPECT_EQ(claim.state(), ClaimState::kNotStarted);
  EXPECT_TRUE(claim.poll(0ms).empty());
  claim.start(0ms);
  const auto sent = claim.poll(0ms);
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].source, 0x80);
  EXPECT_EQ(sent[0].name, name_with(false, 10));
  EXPECT_FALSE(claim.has_address());
  EXPECT_TRUE(claim.poll(249ms).empty());
  EXPECT_FALSE(claim.has_address()) << "§4.4.2: no other message for 250 ms after the claim";
  claim.poll(250ms);
  EXPECT_TRUE(claim.has_address());
  EXPECT_EQ(claim.address(), 0x80);
}

TEST(AddressClaim, LowerNameWinsTheWinnerRepeatsItsClaim) {
  AddressClaim claim(name_with(false, 10), 0x80);
  claim.start(0ms);
  claim.poll(300ms);
  ASSERT_TRUE(claim.has_address());
  claim.on_address_claimed(0x80, name_with(false, 11), 400ms);  // higher NAME: it loses
  const auto sent = claim.poll(400ms);
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].source, 0x80);
  EXPECT_TRUE(claim.has_address());
  EXPECT_EQ(claim.counters().contentions_won, 1u);
}

// Our NAME from another node once (a stray or spoofed frame): we contend with our claim and keep the
// address. Twice within 2 s (a second unit with our NAME): neither can be told apart, so we give up for a
// hold-off and then claim again by ourselves, never going silent for good.
TEST(AddressClaim, OurNameFromAnotherNodeOnceIsContendedTwiceMakesUsHoldOff) {
  for (const std::uint8_t other_address : {std::uint8_t{0x80}, std::uint8_t{0x81}, kNullAddress}) {
    AddressClaim claim(name_with(true, 10), 0x80);  // even a self-configurable one: moving would not help
    claim.start(0ms);
    claim.poll(300ms);
    ASSERT_TRUE(claim.has_address());
    claim.on_address_claimed(other_address, name_with(true, 10), 400ms);
    auto sent = claim.poll(400ms);
    ASSERT_EQ(sent.size(), 1u) << int{other_address};
    EXPECT_EQ(sent[0].source, 0x80) << "one sighting: our claim again, the address stays ours";
    EXPECT_TRUE(claim.has_address());
    claim.on_address_claimed(other_address, name_with(true, 10), 500ms);
    EXPECT_EQ(claim.state(), ClaimState::kCannotClaim) << "a second sighting within 2 s: a second unit";
    EXPECT_FALSE(claim.has_address());
    sent = claim.poll(700ms);
    ASSERT_EQ(sent.size(), 1u);
    EXPECT_EQ(sent[0].source, kNullAddress) << "cannot-claim, which the other unit sees in turn";
    // The other unit's cannot-claim (our NAME again) starts the 3 s hold-off over, and sends nothing.
    claim.on_address_claimed(kNullAddress, name_with(true, 10), 800ms);
    EXPECT_TRUE(claim.poll(3799ms).empty());
    EXPECT_FALSE(claim.has_address());
    sent = claim.poll(3800ms);
    ASSERT_EQ(sent.size(), 1u) << "the hold-off is over: claim the preferred address again";
    EXPECT_EQ(sent[0].source, 0x80);
    claim.poll(4050ms);
    EXPECT_TRUE(claim.has_address());
    EXPECT_EQ(claim.counters().duplicate_names, 3u);
    EXPECT_EQ(claim.counters().duplicate_name_holds, 1u);
    // A second episode holds off twice as long (6 s).
    claim.on_address_claimed(other_address, name_with(true, 10), 10000ms);
    claim.on_address_claimed(other_address, name_with(true, 10), 10100ms);
    EXPECT_FALSE(claim.has_address());
    claim.poll(16099ms);
    EXPECT_EQ(claim.state(), ClaimState::kCannotClaim);
    EXPECT_EQ(claim.poll(16100ms).size(), 1u);
    EXPECT_EQ(claim.state(), ClaimState::kClaiming);
  }
}

TEST(AddressClaim, AddressViolationIsAnsweredWithOurClaimAtMostEvery250Ms) {
  AddressClaim claim(name_with(false, 10), 0x80);
  claim.on_address_violation(0ms);
  EXPECT_TRUE(claim.poll(0ms).empty()) << "nothing to defend before start";
  claim.start(0ms);
  claim.poll(300ms);
  claim.on_address_violation(400ms);
  auto sent = claim.poll(400ms);
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].source, 0x80);
  for (auto t = 401ms; t < 650ms; t += 10ms) claim.on_address_violation(t);  // a flood of spoofed frames
  EXPECT_TRUE(claim.poll(649ms).empty());
  claim.on_address_violation(650ms);
  EXPECT_EQ(claim.poll(650ms).size(), 1u);
  EXPECT_EQ(claim.counters().address_violations, 27u);
  EXPECT_EQ(claim.counters().violation_claims, 2u);
  EXPECT_TRUE(claim.has_address()) << "a violation is no contention: the address stays ours";
}

TEST(AddressClaim, NotSelfConfigurableLoserSendsCannotClaimAfterItsDelayAndFallsSilent) {
  AddressClaim claim(name_with(false, 10), 0x80);
  claim.start(0ms);
  claim.poll(300ms);
  claim.on_address_claimed(0x80, name_with(false, 9), 1000ms);  // lower NAME takes 0x80
  EXPECT_FALSE(claim.has_address());
  EXPECT_EQ(claim.state(), ClaimState::kCannotClaim);
  EXPECT_EQ(claim.address(), kNullAddress);
  std::vector<ClaimMessage> sent;
  for (auto t = 1000ms; t <= 1160ms && sent.empty(); t += 1ms) sent = claim.poll(t);
  ASSERT_EQ(sent.size(), 1u) << "cannot-claim within 0.6 ms × 255 = 153 ms";
  EXPECT_EQ(sent[0].source, kNullAddress);
  EXPECT_EQ(sent[0].name, name_with(false, 10));
  // A request for the claim is answered with cannot-claim again, after the same bounded delay.
  claim.on_request_for_claim(2000ms);
  EXPECT_EQ(claim.poll(2153ms).size(), 1u);
  EXPECT_EQ(claim.counters().cannot_claim_sent, 2u);
  EXPECT_FALSE(claim.has_address());
}

TEST(AddressClaim, SelfConfigurableLoserMovesToAFreeAddressAndWaitsAgain) {
  AddressClaim claim(name_with(true, 10), 128);
  claim.on_address_claimed(129, name_with(false, 1), 0ms);  // 129 is held by a stronger NAME
  claim.start(0ms);
  claim.poll(300ms);
  claim.on_address_claimed(128, name_with(false, 2), 400ms);
  const auto sent = claim.poll(400ms);
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].source, 130) << "129 is held by a lower NAME, 130 is free";
  EXPECT_FALSE(claim.has_address());
  claim.poll(649ms);
  EXPECT_FALSE(claim.has_address());
  claim.poll(650ms);
  EXPECT_TRUE(claim.has_address());
  EXPECT_EQ(claim.address(), 130);
}

TEST(AddressClaim, SelfConfigurableGivesUpWhenEveryAddressIsHeldByLowerNames) {
  const std::uint64_t ours = name_with(true, 1000);
  AddressClaim claim(ours, 128);
  for (int a = kSelfConfigurableFirst; a <= kSelfConfigurableLast; ++a) {
    claim.on_address_claimed(static_cast<std::uint8_t>(a), name_with(false, static_cast<std::uint32_t>(a)), 0ms);
  }
  claim.start(0ms);
  claim.poll(0ms);
  claim.on_address_claimed(128, name_with(false, 5), 10ms);
  EXPECT_EQ(claim.state(), ClaimState::kCannotClaim);
  const auto sent = claim.poll(200ms);
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].source, kNullAddress);
}

TEST(AddressClaim, RequestIsAnsweredWithTheClaimAndStaleQueuedClaimsAreDropped) {
  AddressClaim claim(name_with(true, 10), 128);
  EXPECT_TRUE((claim.on_request_for_claim(0ms), claim.poll(0ms).empty())) << "nothing before start";
  claim.start(0ms);
  claim.poll(0ms);
  claim.on_request_for_claim(100ms);
  auto sent = claim.poll(100ms);
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].source, 128);
  // A request and then a lost contention before the next poll: the claim queued for 128 is stale.
  claim.on_request_for_claim(200ms);
  claim.on_address_claimed(128, name_with(false, 1), 200ms);
  sent = claim.poll(200ms);
  ASSERT_EQ(sent.size(), 1u);
  EXPECT_EQ(sent[0].source, 129);
}

}  // namespace
}  // namespace spread::isobus
