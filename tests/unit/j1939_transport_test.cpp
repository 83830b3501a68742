// J1939 transport sessions reassembled from a passive listener: BAM and RTS/CTS messages, aborts.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <random>
#include <string_view>
#include <vector>

#include "allocation_counter.hpp"
#include "j1939_transport.hpp"

namespace {

using namespace roadload::j1939::transport_test;

TEST_F(J1939TransportTest, BamOf9BytesIsReassembledByteExact) {
  const Bytes payload = pattern(9);
  broadcast(0x00, kEc1, payload);
  ASSERT_EQ(got_.size(), 1u);
  EXPECT_EQ(got_[0].data, payload);
  EXPECT_EQ(got_[0].pgn, kEc1);
  EXPECT_EQ(got_[0].sa, 0x00);
  EXPECT_EQ(got_[0].da, kGlobal);
  EXPECT_FALSE(got_[0].extended);
  EXPECT_EQ(tp_.counters().bam_started, 1u);
  EXPECT_EQ(tp_.counters().completed, 1u);
  EXPECT_EQ(irregularities(tp_.counters()), 0u);
  EXPECT_EQ(tp_.open_sessions(), 0u);
}

TEST_F(J1939TransportTest, BamOf39BytesIsEmittedAtItsLastPacketWithThatStamp) {
  const Bytes payload = pattern(39, 5);
  bam(0x00, kEc1, payload.size());
  dts(0x00, kGlobal, payload, 1, 5);
  EXPECT_TRUE(got_.empty());
  EXPECT_EQ(tp_.open_sessions(), 1u);
  dt(0x00, kGlobal, payload, 6);
  ASSERT_EQ(got_.size(), 1u);
  EXPECT_EQ(got_[0].data, payload);
  EXPECT_EQ(got_[0].t, last_);
  EXPECT_EQ(got_[0].priority, 7);
  EXPECT_EQ(tp_.open_sessions(), 0u);
}

TEST_F(J1939TransportTest, BamOf1785BytesIsReassembledByteExact) {
  const Bytes payload = pattern(j::kTpMaxBytes, 9);
  broadcast(0x17, kProprietaryA | 0x10, payload);
  ASSERT_EQ(got_.size(), 1u);
  EXPECT_EQ(got_[0].data, payload);
  EXPECT_EQ(got_[0].sa, 0x17);
  EXPECT_EQ(irregularities(tp_.counters()), 0u);
}

TEST_F(J1939TransportTest, MessagePriorityComesFromTheControlFrame) {
  cm_priority_ = 3;
  broadcast(0x00, kEc1, pattern(20));
  ASSERT_EQ(got_.size(), 1u);
  EXPECT_EQ(got_[0].priority, 3);
}

TEST_F(J1939TransportTest, RtsCtsInBlocksIsEmittedAtLastPacketBeforeEndOfMsgAck) {
  const Bytes payload = pattern(100, 1);  // 15 packets, 5 per CTS
  rts(0x00, 0x21, kDm1, payload.size(), 5);
  cts(0x21, 0x00, kDm1, 5, 1);
  dts(0x00, 0x21, payload, 1, 5);
  cts(0x21, 0x00, kDm1, 5, 6);
  dts(0x00, 0x21, payload, 6, 10);
  cts(0x21, 0x00, kDm1, 5, 11);
  dts(0x00, 0x21, payload, 11, 15);
  ASSERT_EQ(got_.size(), 1u);
  EXPECT_EQ(got_[0].data, payload);
  EXPECT_EQ(got_[0].sa, 0x00);
  EXPECT_EQ(got_[0].da, 0x21);
  EXPECT_EQ(got_[0].t, last_);
  eoma(0x21, 0x00, kDm1, payload.size());
  EXPECT_EQ(got_.size(), 1u);
  EXPECT_EQ(tp_.open_sessions(), 0u);
  // After the EOMA the pair is free: the next RTS supersedes nothing.
  rts(0x00, 0x21, kDm1, payload.size(), 5);
  EXPECT_EQ(tp_.counters().rts_started, 2u);
  EXPECT_EQ(tp_.counters().completed, 1u);
  EXPECT_EQ(irregularities(tp_.counters()), 0u);
}

TEST_F(J1939TransportTest, RtsCtsMessageIsEmittedEvenIfEndOfMsgAckIsLost) {
  const Bytes payload = pattern(20);
  rts(0x00, 0x21, kDm1, payload.size());
  cts(0x21, 0x00, kDm1, 3, 1);
  dts(0x00, 0x21, payload, 1, 3);
  ASSERT_EQ(got_.size(), 1u);
  wait(2s);
  tp_.expire(now_);
  EXPECT_EQ(tp_.counters().timed_out, 0u);  // nothing was lost, only the ack
}

TEST_F(J1939TransportTest, PeerToPeerSessionsFromTwoSourcesToOneDestinationAreKeptApart) {
  const Bytes a = pattern(30, 1);
  const Bytes b = pattern(30, 2);
  rts(0x00, 0x21, kDm1, a.size());
  rts(0x03, 0x21, kDm1, b.size());
  cts(0x21, 0x00, kDm1, 5, 1);
  cts(0x21, 0x03, kDm1, 5, 1);
  for (std::size_t p = 1; p <= 5; ++p) {
    dt(0x03, 0x21, b, p);
    dt(0x00, 0x21, a, p);
  }
  ASSERT_EQ(got_.size(), 2u);
  EXPECT_EQ(got_[0].sa, 0x03);
  EXPECT_EQ(got_[0].data, b);
  EXPECT_EQ(got_[1].sa, 0x00);
  EXPECT_EQ(got_[1].data, a);
  EXPECT_EQ(irregularities(tp_.counters()), 0u);
}

TEST_F(J1939TransportTest, PeerToPeerSessionsFromOneSourceToTwoDestinationsAreKeptApart) {
  const Bytes a = pattern(16, 1);
  const Bytes b = pattern(40, 2);
  rts(0x00, 0x21, kDm1, a.size());
  rts(0x00, 0x22, kDm1, b.size());
  cts(0x22, 0x00, kDm1, 6, 1);
  cts(0x21, 0x00, kDm1, 3, 1);
  dt(0x00, 0x22, b, 1);
  dts(0x00, 0x21, a, 1, 3);
  dts(0x00, 0x22, b, 2, 6);
  ASSERT_EQ(got_.size(), 2u);
  EXPECT_EQ(got_[0].da, 0x21);
  EXPECT_EQ(got_[0].data, a);
  EXPECT_EQ(got_[1].da, 0x22);
  EXPECT_EQ(got_[1].data, b);
  EXPECT_EQ(irregularities(tp_.counters()), 0u);
}

TEST_F(J1939TransportTest, AbortFromReceiverEndsTheSession) {
  const Bytes payload = pattern(30);
  rts(0x00, 0x21, kDm1, payload.size());
  cts(0x21, 0x00, kDm1, 5, 1);
  dts(0x00, 0x21, payload, 1, 2);
  abort(j::kPgnTpCm, 0x21, 0x00, kDm1);
  EXPECT_EQ(tp_.counters().aborted, 1u);
  EXPECT_EQ(tp_.open_sessions(), 0u);
  dts(0x00, 0x21, payload, 3, 5);
  EXPECT_TRUE(got_.empty());
  EXPECT_EQ(tp_.counters().orphan_packets, 3u);
}

TEST_F(J1939TransportTest, AbortFromSenderEndsTheSession) {
  const Bytes payload = pattern(30);
  rts(0x00, 0x21, kDm1, payload.size());
  cts(0x21, 0x00, kDm1, 5, 1);
  dt(0x00, 0x21, payload, 1);
  abort(j::kPgnTpCm, 0x00, 0x21, kDm1);
  EXPECT_EQ(tp_.counters().aborted, 1u);
  EXPECT_EQ(tp_.open_sessions(), 0u);
  EXPECT_TRUE(got_.empty());
}

TEST_F(J1939TransportTest, AbortForAnotherPgnLeavesTheSessionOpen) {
  rts(0x00, 0x21, kDm1, 30);
  abort(j::kPgnTpCm, 0x21, 0x00, kEc1);
  EXPECT_EQ(tp_.open_sessions(), 1u);
}

}  // namespace
