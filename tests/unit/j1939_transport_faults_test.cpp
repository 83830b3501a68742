// J1939 transport sessions under timeouts, lost, repeated and malformed packets, and more sessions
// than the reassembler holds.
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

TEST_F(J1939TransportTest, BamPacketGapOver750msTimesOut) {
  const Bytes payload = pattern(20);
  bam(0x00, kEc1, payload.size());
  dt(0x00, kGlobal, payload, 1);
  wait(760ms);
  dts(0x00, kGlobal, payload, 2, 3);
  EXPECT_TRUE(got_.empty());
  EXPECT_EQ(tp_.counters().timed_out, 1u);
  EXPECT_EQ(tp_.counters().orphan_packets, 2u);
}

TEST_F(J1939TransportTest, BamPacketGapJustUnder750msStillCompletes) {
  const Bytes payload = pattern(20);
  bam(0x00, kEc1, payload.size());
  dt(0x00, kGlobal, payload, 1);
  wait(740ms - kStep);
  dts(0x00, kGlobal, payload, 2, 3);
  ASSERT_EQ(got_.size(), 1u);
  EXPECT_EQ(got_[0].data, payload);
  EXPECT_EQ(tp_.counters().timed_out, 0u);
}

TEST_F(J1939TransportTest, ConnectionTimesOutAfter1250msWithoutAFrame) {
  const Bytes payload = pattern(20);
  rts(0x00, 0x21, kDm1, payload.size());
  cts(0x21, 0x00, kDm1, 3, 1);
  dt(0x00, 0x21, payload, 1);
  wait(1s);  // longer than a BAM may pause, shorter than a connection
  dt(0x00, 0x21, payload, 2);
  EXPECT_EQ(tp_.counters().timed_out, 0u);
  wait(1300ms);
  dt(0x00, 0x21, payload, 3);
  EXPECT_TRUE(got_.empty());
  EXPECT_EQ(tp_.counters().timed_out, 1u);
  EXPECT_EQ(tp_.counters().orphan_packets, 1u);
}

TEST_F(J1939TransportTest, HoldCtsKeepsTheConnectionAlive) {
  const Bytes payload = pattern(20);
  rts(0x00, 0x21, kDm1, payload.size());
  for (int i = 0; i < 3; ++i) {
    cts(0x21, 0x00, kDm1, 0, 1);  // hold: zero packets
    wait(1s);
  }
  cts(0x21, 0x00, kDm1, 3, 1);
  dts(0x00, 0x21, payload, 1, 3);
  ASSERT_EQ(got_.size(), 1u);
  EXPECT_EQ(tp_.counters().timed_out, 0u);
}

TEST_F(J1939TransportTest, ExpireClosesSessionsOnAQuietBus) {
  bam(0x00, kEc1, 20);
  tp_.expire(last_ + 750ms);
  EXPECT_EQ(tp_.open_sessions(), 1u);
  tp_.expire(last_ + 751ms);
  EXPECT_EQ(tp_.open_sessions(), 0u);
  EXPECT_EQ(tp_.counters().timed_out, 1u);
}

TEST_F(J1939TransportTest, PushOfAnyFrameFirstExpiresStaleSessions) {
  bam(0x00, kEc1, 20);
  wait(800ms);
  send(0x0CF00400, {0x50, 0x7D, 0x84, 0x46, 0x14, 0x00, 0xF0, 0x84});  // EEC1, not TP
  EXPECT_EQ(tp_.open_sessions(), 0u);
  EXPECT_EQ(tp_.counters().timed_out, 1u);
}

TEST_F(J1939TransportTest, DuplicatePacketIsCountedAndIgnored) {
  const Bytes payload = pattern(20);
  bam(0x00, kEc1, payload.size());
  dt(0x00, kGlobal, payload, 1);
  data(j::kPgnTpDt, 0x00, kGlobal, pattern(20, 77), 1, 1);  // same sequence, other bytes
  dts(0x00, kGlobal, payload, 2, 3);
  ASSERT_EQ(got_.size(), 1u);
  EXPECT_EQ(got_[0].data, payload);
  EXPECT_EQ(tp_.counters().duplicate_packets, 1u);
}

TEST_F(J1939TransportTest, PacketsResentOnCtsAfterALossAreStoredBySequence) {
  const Bytes payload = pattern(33, 4);  // 5 packets
  rts(0x00, 0x21, kDm1, payload.size());
  cts(0x21, 0x00, kDm1, 5, 1);
  dts(0x00, 0x21, payload, 1, 2);
  dts(0x00, 0x21, payload, 4, 5);  // packet 3 lost on the bus
  cts(0x21, 0x00, kDm1, 1, 3);     // the receiver asks for it again
  EXPECT_TRUE(got_.empty());
  dt(0x00, 0x21, payload, 3);
  ASSERT_EQ(got_.size(), 1u);
  EXPECT_EQ(got_[0].data, payload);
  EXPECT_EQ(tp_.counters().out_of_order_packets, 2u);  // 4 and 5 came while 3 was missing
  EXPECT_EQ(tp_.counters().duplicate_packets, 0u);
}

TEST_F(J1939TransportTest, PacketResentForTheReceiverAfterCompletionIsADuplicate) {
  const Bytes payload = pattern(33, 4);
  rts(0x00, 0x21, kDm1, payload.size());
  cts(0x21, 0x00, kDm1, 5, 1);
  dts(0x00, 0x21, payload, 1, 5);  // the logger saw all; the receiver missed packet 5
  ASSERT_EQ(got_.size(), 1u);
  cts(0x21, 0x00, kDm1, 1, 5);
  dt(0x00, 0x21, payload, 5);
  eoma(0x21, 0x00, kDm1, payload.size());
  EXPECT_EQ(got_.size(), 1u);
  EXPECT_EQ(tp_.counters().duplicate_packets, 1u);
  EXPECT_EQ(tp_.counters().orphan_packets, 0u);
}

TEST_F(J1939TransportTest, BadSequenceNumbersAreCountedAndIgnored) {
  const Bytes payload = pattern(20);
  bam(0x00, kEc1, payload.size());
  data(j::kPgnTpDt, 0x00, kGlobal, payload, 1, 0);
  data(j::kPgnTpDt, 0x00, kGlobal, payload, 1, 4);
  data(j::kPgnTpDt, 0x00, kGlobal, payload, 1, 255);
  dts(0x00, kGlobal, payload, 1, 3);
  ASSERT_EQ(got_.size(), 1u);
  EXPECT_EQ(got_[0].data, payload);
  EXPECT_EQ(tp_.counters().bad_sequence, 3u);
}

TEST_F(J1939TransportTest, UnpaddedLastPacketIsAcceptedButATruncatedPacketIsMalformed) {
  const Bytes payload = pattern(9);
  bam(0x00, kEc1, payload.size());
  const std::uint32_t id = j::make_can_id(7, j::kPgnTpDt, kGlobal, 0x00);
  send(id, {});                           // no sequence number
  send(id, {1, payload[0], payload[1]});  // packet 1 needs 7 bytes
  EXPECT_EQ(tp_.counters().malformed, 2u);
  dt(0x00, kGlobal, payload, 1);
  send(id, {2, payload[7], payload[8]});  // packet 2 needs only 2
  ASSERT_EQ(got_.size(), 1u);
  EXPECT_EQ(got_[0].data, payload);
}

TEST_F(J1939TransportTest, InconsistentPacketCountIsMalformedAndOpensNoSession) {
  control(j::kPgnTpCm, 0x00, kGlobal, {kBam, 39, 0, 5, 0xFF}, kEc1);  // 39 bytes need 6
  control(j::kPgnTpCm, 0x00, 0x21, {kRts, 39, 0, 7, 0xFF}, kDm1);
  EXPECT_EQ(tp_.counters().malformed, 2u);
  EXPECT_EQ(tp_.open_sessions(), 0u);
  dt(0x00, kGlobal, pattern(39), 1);
  EXPECT_EQ(tp_.counters().orphan_packets, 1u);
}

TEST_F(J1939TransportTest, ImpossibleAnnouncementsAreMalformed) {
  control(j::kPgnTpCm, 0x00, kGlobal, {kBam, 8, 0, 2, 0xFF}, kEc1);        // fits one frame
  control(j::kPgnTpCm, 0x00, kGlobal, {kBam, 0xFA, 0x06, 0, 0xFF}, kEc1);  // 1786 bytes
  control(j::kPgnTpCm, 0x00, kGlobal, {kRts, 20, 0, 3, 0xFF}, kDm1);       // RTS to everyone
  control(j::kPgnTpCm, 0x00, 0x21, {kBam, 20, 0, 3, 0xFF}, kEc1);          // BAM to one node
  control(j::kPgnTpCm, 0x00, 0x21, {0x42, 20, 0, 3, 0xFF}, kDm1);          // unknown control
  etp_rts(0x00, 0x21, kDm1, 1785);                                         // TP would do
  send(j::make_can_id(7, j::kPgnTpCm, kGlobal, 0x00), {kBam, 20, 0, 3});   // short frame
  EXPECT_EQ(tp_.counters().malformed, 7u);
  EXPECT_EQ(tp_.open_sessions(), 0u);
}

TEST_F(J1939TransportTest, NewAnnouncementSupersedesAnUnfinishedSession) {
  const Bytes first = pattern(20, 1);
  const Bytes second = pattern(30, 2);
  bam(0x00, kEc1, first.size());
  dt(0x00, kGlobal, first, 1);
  broadcast(0x00, kEc1, second);
  ASSERT_EQ(got_.size(), 1u);
  EXPECT_EQ(got_[0].data, second);
  EXPECT_EQ(tp_.counters().superseded, 1u);
  EXPECT_EQ(tp_.counters().bam_started, 2u);
}

TEST_F(J1939TransportTest, DataPacketWithoutSessionIsAnOrphan) {
  dt(0x00, kGlobal, pattern(20), 1);
  dt(0x00, 0x21, pattern(20), 1);
  data(j::kPgnEtpDt, 0x00, 0x21, pattern(20), 1, 1);
  EXPECT_EQ(tp_.counters().orphan_packets, 3u);
  EXPECT_TRUE(got_.empty());
}

TEST_F(J1939TransportTest, MoreConcurrentSessionsThanMaxSessionsCountsNoFreeSession) {
  configure({.max_sessions = 2});
  const Bytes a = pattern(20, 1);
  const Bytes b = pattern(20, 2);
  const Bytes c = pattern(20, 3);
  bam(0x01, kEc1, a.size());
  bam(0x02, kEc1, b.size());
  bam(0x03, kEc1, c.size());
  EXPECT_EQ(tp_.counters().no_free_session, 1u);
  for (std::size_t p = 1; p <= 3; ++p) {
    dt(0x01, kGlobal, a, p);
    dt(0x02, kGlobal, b, p);
    dt(0x03, kGlobal, c, p);
  }
  ASSERT_EQ(got_.size(), 2u);
  EXPECT_EQ(got_[0].data, a);
  EXPECT_EQ(got_[1].data, b);
  EXPECT_EQ(tp_.counters().orphan_packets, 3u);
  broadcast(0x03, kEc1, c);  // slots are free again
  ASSERT_EQ(got_.size(), 3u);
  EXPECT_EQ(got_[2].data, c);
}

}  // namespace
