// ISO 11783-3 TP (RTS/CTS, BAM) and ISO 11783-6 ETP between two in-process protocol instances on an
// injected clock: byte layouts, complete transfers up to the size limits, aborts with their reasons,
// every timeout, holds, lost / duplicate / out-of-order packets.
#include <gtest/gtest.h>

#include <functional>
#include <numeric>

#include "isobus/transport_protocol.hpp"
#include "libspread/core/clock.hpp"

namespace spread::isobus {
namespace {

using namespace std::chrono_literals;

constexpr std::uint8_t kA = 0x80;
constexpr std::uint8_t kB = 0x81;
constexpr std::uint32_t kPgn = 0xCB00;  // process data: the DDOP transfer the ECU will need

std::vector<std::uint8_t> pattern(std::size_t n) {
  std::vector<std::uint8_t> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<std::uint8_t>(i * 7 + i / 251);
  return v;
}

// Two nodes and the wire between them. `filter` sees every frame before delivery and may drop it.
class TwoNodes : public ::testing::Test {
 protected:
  explicit TwoNodes(TransportLimits b_limits = {}) : a_(kA), b_(kB, b_limits) {}

  // Moves frames both ways until nobody has anything to say; returns how many frames were carried.
  std::size_t exchange() {
    std::size_t carried = 0;
    for (;;) {
      auto from_a = a_.take_frames();
      auto from_b = b_.take_frames();
      if (from_a.empty() && from_b.empty()) return carried;
      for (const auto& f : from_a) {
        log_.push_back(f);
        if (!filter || filter(f)) b_.handle_frame(f, clock_.now()), ++carried;
      }
      for (const auto& f : from_b) {
        log_.push_back(f);
        if (!filter || filter(f)) a_.handle_frame(f, clock_.now()), ++carried;
      }
    }
  }
  void advance(Nanoseconds by) {
    clock_.advance(by);
    a_.update(clock_.now());
    b_.update(clock_.now());
    exchange();
  }
  std::size_t count(std::uint32_t pgn, std::uint8_t control = 0, bool any_control = true) const {
    return static_cast<std::size_t>(std::count_if(log_.begin(), log_.end(), [&](const TransportFrame& f) {
      return f.pgn == pgn && (any_control || f.data[0] == control);
    }));
  }
  std::optional<TransportSessionEnd> single_end(TransportProtocol& node) {
    auto ends = node.take_ended();
    EXPECT_EQ(ends.size(), 1u);
    if (ends.empty()) return std::nullopt;
    return ends[0];
  }

  ManualClock clock_;
  TransportProtocol a_;
  TransportProtocol b_;
  std::vector<TransportFrame> log_;
  std::function<bool(const TransportFrame&)> filter;
};

TEST_F(TwoNodes, TpRtsCtsTransfersAMessageWithTheStandardByteLayout) {
  const auto data = pattern(100);  // 15 packets, the last one with 2 data bytes
  ASSERT_TRUE(a_.send({kPgn, kA, kB, data}, clock_.now()));
  exchange();
  const auto got = b_.take_received();
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].data, data);
  EXPECT_EQ(got[0].pgn, kPgn);
  EXPECT_EQ(got[0].source, kA);
  EXPECT_EQ(got[0].destination, kB);
  const auto end = single_end(a_);
  ASSERT_TRUE(end);
  EXPECT_EQ(end->outcome, TransportOutcome::kCompleted);
  ASSERT_EQ(log_.size(), 1u + 1u + 15u + 1u);  // RTS, CTS, 15 DT, EoMA
  const std::array<std::uint8_t, 8> rts{16, 100, 0, 15, 0xFF, 0x00, 0xCB, 0x00};
  EXPECT_EQ(log_[0].data, rts);
  EXPECT_EQ(log_[0].pgn, kTpConnectionManagementPgn);
  EXPECT_EQ(log_[0].destination, kB);
  EXPECT_EQ(log_[0].priority, 7);
  const std::array<std::uint8_t, 8> cts{17, 15, 1, 0xFF, 0xFF, 0x00, 0xCB, 0x00};
  EXPECT_EQ(log_[1].data, cts);
  EXPECT_EQ(log_[1].source, kB);
  const std::array<std::uint8_t, 8> last{15, data[98], data[99], 0xFF, 0xFF, 0xFF, 0xFF, 0xFF};
  EXPECT_EQ(log_[16].data, last) << "unused bytes of the last packet are 0xFF";
  const std::array<std::uint8_t, 8> eoma{19, 100, 0, 15, 0xFF, 0x00, 0xCB, 0x00};
  EXPECT_EQ(log_[17].data, eoma);
  EXPECT_EQ(a_.session_count() + b_.session_count(), 0u);
}

TEST_F(TwoNodes, TheLargestTpMessageGoesInWindowsOfSixteen) {
  const auto data = pattern(kTpMaxBytes);
  ASSERT_TRUE(a_.send({kPgn, kA, kB, data}, clock_.now()));
  exchange();
  const auto got = b_.take_received();
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].data, data);
  EXPECT_EQ(count(kTpDataTransferPgn), 255u);
  EXPECT_EQ(count(kTpConnectionManagementPgn, 17, false), 16u);  // ceil(255 / 16)
}

TEST_F(TwoNodes, SizesDecideTheProtocolAndOutOfRangeSizesAreRefused) {
  EXPECT_FALSE(a_.send({kPgn, kA, kB, pattern(8)}, clock_.now())) << "8 bytes fit one frame";
  EXPECT_FALSE(a_.send({kPgn, kA, 0xFF, pattern(kTpMaxBytes + 1)}, clock_.now())) << "no ETP broadcast";
  EXPECT_FALSE(a_.send({kPgn, kA, kA, pattern(20)}, clock_.now())) << "not to ourselves";
  ASSERT_TRUE(a_.send({kPgn, kA, kB, pattern(kTpMaxBytes + 1)}, clock_.now()));
  EXPECT_FALSE(a_.send({kPgn, kA, kB, pattern(20)}, clock_.now())) << "one session per destination";
  const auto frames = a_.take_frames();
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].pgn, kEtpConnectionManagementPgn);
  const std::array<std::uint8_t, 8> rts{20, 0xFA, 0x06, 0, 0, 0x00, 0xCB, 0x00};  // 1786 = 0x06FA
  EXPECT_EQ(frames[0].data, rts);
}

TEST_F(TwoNodes, EtpTransfersThreeThousandBytesWithDataPacketOffsets) {
  const auto data = pattern(3000);  // 429 packets
  ASSERT_TRUE(a_.send({kPgn, kA, kB, data}, clock_.now()));
  exchange();
  const auto got = b_.take_received();
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].data, data);
  EXPECT_EQ(single_end(a_)->outcome, TransportOutcome::kCompleted);
  EXPECT_EQ(count(kEtpDataTransferPgn), 429u);
  EXPECT_EQ(count(kEtpConnectionManagementPgn, 22, false), 27u);  // DPO per window: ceil(429 / 16)
  // The second window: CTS for packet 17, DPO offset 16, sequence numbers restart at 1.
  const auto second_cts = std::find_if(log_.begin() + 2, log_.end(), [](const TransportFrame& f) {
    return f.pgn == kEtpConnectionManagementPgn && f.data[0] == 21;
  });
  ASSERT_NE(second_cts, log_.end());
  const std::array<std::uint8_t, 8> cts{21, 16, 17, 0, 0, 0x00, 0xCB, 0x00};
  EXPECT_EQ(second_cts->data, cts);
  const std::array<std::uint8_t, 8> dpo{22, 16, 16, 0, 0, 0x00, 0xCB, 0x00};
  EXPECT_EQ((second_cts + 1)->data, dpo);
  EXPECT_EQ((second_cts + 2)->data[0], 1);
  const std::array<std::uint8_t, 8> eoma{23, 0xB8, 0x0B, 0, 0, 0x00, 0xCB, 0x00};  // 3000 = 0x0BB8
  EXPECT_EQ(log_.back().data, eoma);
}

TEST_F(TwoNodes, BamIsPacedFiftyMillisecondsApartAndNeedsNoAnswers) {
  const auto data = pattern(30);  // 5 packets
  ASSERT_TRUE(a_.send({0xFEE6, kA, 0xFF, data}, clock_.now()));
  exchange();
  EXPECT_EQ(count(kTpConnectionManagementPgn, 32, false), 1u);
  for (int i = 0; i < 4; ++i) {
    advance(49ms);
    EXPECT_EQ(count(kTpDataTransferPgn), static_cast<std::size_t>(i));
    advance(1ms);
    EXPECT_EQ(count(kTpDataTransferPgn), static_cast<std::size_t>(i + 1));
  }
  EXPECT_TRUE(b_.take_received().empty());
  advance(50ms);
  const auto got = b_.take_received();
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].data, data);
  EXPECT_EQ(got[0].destination, 0xFF);
  EXPECT_EQ(single_end(a_)->outcome, TransportOutcome::kCompleted);
  for (const auto& f : log_) EXPECT_EQ(f.source, kA) << "a BAM receiver never answers";
}

TEST_F(TwoNodes, BamReceiverDropsTheMessageAfterT1OrALostPacket) {
  ASSERT_TRUE(a_.send({0xFEE6, kA, 0xFF, pattern(30)}, clock_.now()));
  exchange();
  filter = [](const TransportFrame& f) { return f.pgn != kTpDataTransferPgn || f.data[0] != 2; };
  advance(50ms);
  advance(50ms);  // packet 2 lost
  advance(50ms);  // packet 3 shows the gap
  auto ends = b_.take_ended();
  ASSERT_EQ(ends.size(), 1u);
  EXPECT_EQ(ends[0].reason, AbortReason::kBadSequenceNumber);
  filter = nullptr;
  log_.clear();
  ASSERT_TRUE(b_.send({0xFEE6, kB, 0xFF, pattern(30)}, clock_.now()));  // now B broadcasts
  exchange();
  filter = [](const TransportFrame& f) { return f.pgn != kTpDataTransferPgn; };  // every packet lost
  advance(749ms);
  EXPECT_TRUE(a_.take_ended().empty());
  advance(1ms);
  ends = a_.take_ended();
  ASSERT_EQ(ends.size(), 1u);
  EXPECT_EQ(ends[0].outcome, TransportOutcome::kTimedOut);
  EXPECT_EQ(count(kTpConnectionManagementPgn, 255, false), 0u) << "no abort for a BAM";
}

class SmallReceiver : public TwoNodes {
 protected:
  SmallReceiver() : TwoNodes(TransportLimits{1000, 8, 16}) {}
};

TEST_F(SmallReceiver, AMessageLargerThanTheReceiverTakesIsAbortedWithReason2) {
  ASSERT_TRUE(a_.send({kPgn, kA, kB, pattern(1500)}, clock_.now()));
  exchange();
  const auto end = single_end(a_);
  ASSERT_TRUE(end);
  EXPECT_EQ(end->outcome, TransportOutcome::kAbortedByPeer);
  EXPECT_EQ(end->reason, AbortReason::kResourcesNeeded);
  const std::array<std::uint8_t, 8> abort{255, 2, 0xFF, 0xFF, 0xFF, 0x00, 0xCB, 0x00};
  EXPECT_EQ(log_.back().data, abort);
  EXPECT_TRUE(b_.take_received().empty());
}

TEST_F(TwoNodes, ReceiverTimesOutAfterT1BetweenPacketsAndT2AfterItsCts) {
  ASSERT_TRUE(a_.send({kPgn, kA, kB, pattern(100)}, clock_.now()));
  filter = [](const TransportFrame& f) { return f.pgn != kTpDataTransferPgn || f.data[0] <= 3; };
  exchange();
  advance(749ms);
  EXPECT_TRUE(b_.take_ended().empty());
  advance(1ms);
  auto end = single_end(b_);
  ASSERT_TRUE(end);
  EXPECT_EQ(end->outcome, TransportOutcome::kTimedOut);
  end = single_end(a_);
  ASSERT_TRUE(end);
  EXPECT_EQ(end->outcome, TransportOutcome::kAbortedByPeer);
  EXPECT_EQ(end->reason, AbortReason::kTimeout);
  // T2: the CTS was sent, no packet ever came.
  log_.clear();
  filter = [](const TransportFrame& f) { return f.pgn != kTpDataTransferPgn; };
  ASSERT_TRUE(a_.send({kPgn, kA, kB, pattern(100)}, clock_.now()));
  exchange();
  a_.take_ended();
  advance(1249ms);
  EXPECT_TRUE(b_.take_ended().empty());
  advance(1ms);
  EXPECT_EQ(single_end(b_)->reason, AbortReason::kTimeout);
}

TEST_F(TwoNodes, SenderTimesOutAfterT3WithoutCtsAndHonoursHoldsForT4) {
  filter = [](const TransportFrame&) { return false; };  // B is deaf
  ASSERT_TRUE(a_.send({kPgn, kA, kB, pattern(100)}, clock_.now()));
  exchange();
  advance(1249ms);
  EXPECT_TRUE(a_.take_ended().empty());
  advance(1ms);
  auto end = single_end(a_);
  ASSERT_TRUE(end);
  EXPECT_EQ(end->outcome, TransportOutcome::kTimedOut);
  EXPECT_EQ(log_.back().data[0], 255);
  EXPECT_EQ(log_.back().data[1], 3);

  // Hold: a CTS(0) every Th = 500 ms keeps the session open beyond T3; without renewal T4 ends it.
  filter = nullptr;
  ASSERT_TRUE(a_.send({kPgn, kA, kB + 1, pattern(100)}, clock_.now()));  // to a node we play by hand
  exchange();
  TransportFrame hold{7, kTpConnectionManagementPgn, static_cast<std::uint8_t>(kB + 1), kA,
                      {17, 0, 0xFF, 0xFF, 0xFF, 0x00, 0xCB, 0x00}};
  for (int i = 0; i < 4; ++i) {
    a_.handle_frame(hold, clock_.now());
    advance(500ms);
  }
  EXPECT_TRUE(a_.take_ended().empty()) << "2 s of renewed holds";
  TransportFrame go = hold;
  go.data[1] = 15;
  go.data[2] = 1;
  a_.handle_frame(go, clock_.now());
  const auto frames = a_.take_frames();
  EXPECT_EQ(frames.size(), 15u);
  a_.handle_frame(hold, clock_.now());  // ... and a hold once all is sent is just another wait
  a_.take_frames();
  TransportFrame eoma = hold;
  eoma.data = {19, 100, 0, 15, 0xFF, 0x00, 0xCB, 0x00};
  a_.handle_frame(eoma, clock_.now());
  EXPECT_EQ(single_end(a_)->outcome, TransportOutcome::kCompleted);

  ASSERT_TRUE(a_.send({kPgn, kA, kB + 1, pattern(100)}, clock_.now()));
  a_.handle_frame(hold, clock_.now());
  advance(1049ms);
  EXPECT_TRUE(a_.take_ended().empty());
  advance(1ms);
  EXPECT_EQ(single_end(a_)->outcome, TransportOutcome::kTimedOut) << "T4 after a hold";
}

TEST_F(TwoNodes, ALostPacketIsAskedAgainDuplicatesAreIgnored) {
  bool dropped = false;
  filter = [&](const TransportFrame& f) {
    if (f.pgn == kTpDataTransferPgn && f.data[0] == 5 && !dropped) {
      dropped = true;
      return false;
    }
    return true;
  };
  const auto data = pattern(200);
  ASSERT_TRUE(a_.send({kPgn, kA, kB, data}, clock_.now()));
  exchange();
  auto got = b_.take_received();
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].data, data);
  EXPECT_EQ(b_.counters().retransmit_requests, 1u);
  // Every packet delivered twice: the copies are ignored.
  filter = nullptr;
  ASSERT_TRUE(a_.send({kPgn, kA, kB, data}, clock_.now()));
  for (int round = 0; round < 100; ++round) {
    auto from_a = a_.take_frames();
    auto from_b = b_.take_frames();
    if (from_a.empty() && from_b.empty()) break;
    for (const auto& f : from_a) {
      b_.handle_frame(f, clock_.now());
      if (f.pgn == kTpDataTransferPgn) b_.handle_frame(f, clock_.now());
    }
    for (const auto& f : from_b) a_.handle_frame(f, clock_.now());
  }
  got = b_.take_received();
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].data, data);
  EXPECT_GT(b_.counters().duplicates_ignored, 0u);
}

TEST_F(TwoNodes, APacketLostThreeTimesAbortsWithTheRetransmitLimit) {
  filter = [](const TransportFrame& f) { return !(f.pgn == kTpDataTransferPgn && f.data[0] == 5); };
  ASSERT_TRUE(a_.send({kPgn, kA, kB, pattern(200)}, clock_.now()));
  exchange();
  const auto end = single_end(a_);
  ASSERT_TRUE(end);
  EXPECT_EQ(end->reason, AbortReason::kRetransmitLimit);
  EXPECT_EQ(b_.counters().retransmit_requests, 2u);
}

TEST_F(TwoNodes, ProtocolViolationsAbortWithTheirReasons) {
  auto rts_to_b = [&](std::uint16_t size) {
    b_.handle_frame({7, kTpConnectionManagementPgn, kA, kB,
                     {16, static_cast<std::uint8_t>(size), static_cast<std::uint8_t>(size >> 8),
                      static_cast<std::uint8_t>((size + 6) / 7), 0xFF, 0x00, 0xCB, 0x00}},
                    clock_.now());
  };
  auto last_abort_reason = [&]() -> int {
    const auto frames = b_.take_frames();
    if (frames.empty() || frames.back().data[0] != 255) return -1;
    return frames.back().data[1];
  };
  rts_to_b(100);
  b_.handle_frame({7, kTpDataTransferPgn, kA, kB, {0, 1, 2, 3, 4, 5, 6, 7}}, clock_.now());
  EXPECT_EQ(last_abort_reason(), 7) << "sequence number 0";
  rts_to_b(5);
  EXPECT_EQ(last_abort_reason(), 250) << "an RTS for 5 bytes is not a TP message";
  // ETP: data before the DPO, a DPO offset that skips packets, a DPO for more than the CTS granted.
  auto etp_rts = [&]() {
    b_.handle_frame({7, kEtpConnectionManagementPgn, kA, kB, {20, 0xB8, 0x0B, 0, 0, 0x00, 0xCB, 0x00}}, clock_.now());
    b_.take_frames();
  };
  etp_rts();
  b_.handle_frame({7, kEtpDataTransferPgn, kA, kB, {1, 1, 2, 3, 4, 5, 6, 7}}, clock_.now());
  EXPECT_EQ(last_abort_reason(), 6);
  etp_rts();
  b_.handle_frame({7, kEtpConnectionManagementPgn, kA, kB, {22, 16, 5, 0, 0, 0x00, 0xCB, 0x00}}, clock_.now());
  EXPECT_EQ(last_abort_reason(), 12);
  etp_rts();
  b_.handle_frame({7, kEtpConnectionManagementPgn, kA, kB, {22, 17, 0, 0, 0, 0x00, 0xCB, 0x00}}, clock_.now());
  EXPECT_EQ(last_abort_reason(), 11);
  etp_rts();
  b_.handle_frame({7, kEtpConnectionManagementPgn, kA, kB, {22, 16, 0, 0, 0, 0x00, 0xCC, 0x00}}, clock_.now());
  EXPECT_EQ(last_abort_reason(), 10);
  // A CTS asking for packets the message does not have.
  ASSERT_TRUE(a_.send({kPgn, kA, kB, pattern(100)}, clock_.now()));
  a_.take_frames();
  a_.handle_frame({7, kTpConnectionManagementPgn, kB, kA, {17, 5, 14, 0xFF, 0xFF, 0x00, 0xCB, 0x00}}, clock_.now());
  auto frames = a_.take_frames();
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].data[1], 15);
  EXPECT_EQ(single_end(a_)->reason, AbortReason::kCtsPacketsBeyondMessage);
  // The peer's abort ends the matching session only.
  ASSERT_TRUE(a_.send({kPgn, kA, kB, pattern(100)}, clock_.now()));
  a_.handle_frame({7, kTpConnectionManagementPgn, kB, kA, {255, 1, 0xFF, 0xFF, 0xFF, 0x00, 0xCC, 0x00}}, clock_.now());
  EXPECT_TRUE(a_.take_ended().empty()) << "abort for another PGN";
  a_.handle_frame({7, kTpConnectionManagementPgn, kB, kA, {255, 1, 0xFF, 0xFF, 0xFF, 0x00, 0xCB, 0x00}}, clock_.now());
  const auto end = single_end(a_);
  ASSERT_TRUE(end);
  EXPECT_EQ(end->outcome, TransportOutcome::kAbortedByPeer);
  EXPECT_EQ(end->reason, AbortReason::kAlreadyInSession);
}

TEST_F(TwoNodes, FramesForOtherNodesAndTooManySessionsAreRefused) {
  b_.handle_frame({7, kTpConnectionManagementPgn, kA, 0x90, {16, 100, 0, 15, 0xFF, 0x00, 0xCB, 0x00}}, clock_.now());
  b_.handle_frame({7, 0xCB00, kA, kB, {16, 100, 0, 15, 0xFF, 0x00, 0xCB, 0x00}}, clock_.now());
  EXPECT_EQ(b_.session_count(), 0u);
  EXPECT_TRUE(b_.take_frames().empty());
  for (std::uint8_t source = 1; source <= 9; ++source) {
    b_.handle_frame({7, kTpConnectionManagementPgn, source, kB, {16, 100, 0, 15, 0xFF, 0x00, 0xCB, 0x00}},
                    clock_.now());
  }
  EXPECT_EQ(b_.session_count(), 8u);
  const auto frames = b_.take_frames();
  ASSERT_EQ(frames.size(), 9u);
  EXPECT_EQ(frames.back().destination, 9);
  EXPECT_EQ(frames.back().data[0], 255);
  EXPECT_EQ(frames.back().data[1], 1);
  // Losing our address ends every session without a word.
  b_.set_address(0x82);
  EXPECT_EQ(b_.session_count(), 0u);
  EXPECT_TRUE(b_.take_frames().empty());
  EXPECT_EQ(b_.take_ended().size(), 8u);
}

}  // namespace
}  // namespace spread::isobus
