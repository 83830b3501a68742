#include "roadload/j1939/transport.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <random>
#include <string_view>
#include <vector>

#include "allocation_counter.hpp"

namespace {

namespace j = roadload::j1939;
using roadload::CanFrame;
using roadload::CanFrameKind;
using roadload::CaptureTime;
using roadload::Nanoseconds;
using namespace std::chrono_literals;

using namespace roadload::j1939::tp_control;
constexpr std::uint8_t kGlobal = 0xFF;
constexpr j::Pgn kEc1 = 0xFEE3;
constexpr j::Pgn kDm1 = 0xFECA;
constexpr j::Pgn kProprietaryA = 0xEF00;
constexpr Nanoseconds kStep = 10ms;  // spacing between consecutive frames in these tests

using Bytes = std::vector<std::uint8_t>;

std::uint8_t byte(std::size_t v) { return static_cast<std::uint8_t>(v & 0xFFu); }

// Distinct bytes across a long message, so a misplaced packet shows up.
Bytes pattern(std::size_t n, std::size_t seed = 0) {
  Bytes v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = byte(seed + i * 31 + i / 251);
  return v;
}

std::uint8_t packets(std::size_t size) { return byte((size + 6) / 7); }

struct Received {
  CaptureTime t;
  j::Pgn pgn = 0;
  std::uint8_t sa = 0;
  std::uint8_t da = 0;
  std::uint8_t priority = 0;
  std::uint8_t iface = 0;
  bool extended = false;
  Bytes data;
};

// Every counter that records something lost or irregular.
std::uint64_t irregularities(const j::TpCounters& c) {
  return c.aborted + c.timed_out + c.superseded + c.duplicate_packets + c.out_of_order_packets +
         c.orphan_packets + c.bad_sequence + c.malformed + c.too_large + c.no_free_session;
}

class J1939TransportTest : public ::testing::Test {
 protected:
  void configure(const j::TpConfig& config) { tp_ = j::TpReassembler(config); }

  // Pushes one frame stamped with the test clock, then advances the clock by kStep.
  void send(std::uint32_t id, const Bytes& bytes) {
    CanFrame f;
    f.t = now_;
    f.id = id;
    f.iface = iface_;
    f.len = byte(bytes.size());
    std::copy(bytes.begin(), bytes.end(), f.data.begin());
    push(f);
  }
  void push(const CanFrame& f) {
    if (auto m = tp_.push(f)) {
      got_.push_back(Received{m->t, m->pgn, m->sa, m->da, m->priority, m->iface, m->extended,
                              Bytes(m->data.begin(), m->data.end())});
    }
    last_ = f.t;
    now_ = f.t + kStep;
  }
  void wait(Nanoseconds d) { now_ += d; }

  // Control frame: five control bytes, then the PGN of the packeted message in bytes 6-8.
  void control(j::Pgn cm, std::uint8_t sa, std::uint8_t da, Bytes head, j::Pgn pgn) {
    head.push_back(byte(pgn));
    head.push_back(byte(pgn >> 8));
    head.push_back(byte(pgn >> 16));
    send(j::make_can_id(cm_priority_, cm, da, sa), head);
  }
  void bam(std::uint8_t sa, j::Pgn pgn, std::size_t size) {
    control(j::kPgnTpCm, sa, kGlobal, {kBam, byte(size), byte(size >> 8), packets(size), 0xFF}, pgn);
  }
  void rts(std::uint8_t sa, std::uint8_t da, j::Pgn pgn, std::size_t size, std::uint8_t per_cts = 0xFF) {
    control(j::kPgnTpCm, sa, da, {kRts, byte(size), byte(size >> 8), packets(size), per_cts}, pgn);
  }
  void cts(std::uint8_t receiver, std::uint8_t sender, j::Pgn pgn, std::uint8_t count, std::uint8_t next) {
    control(j::kPgnTpCm, receiver, sender, {kCts, count, next, 0xFF, 0xFF}, pgn);
  }
  void eoma(std::uint8_t receiver, std::uint8_t sender, j::Pgn pgn, std::size_t size) {
    control(j::kPgnTpCm, receiver, sender, {kEoma, byte(size), byte(size >> 8), packets(size), 0xFF}, pgn);
  }
  void abort(j::Pgn cm, std::uint8_t from, std::uint8_t to, j::Pgn pgn) {
    control(cm, from, to, {kAbort, 0x03, 0xFF, 0xFF, 0xFF}, pgn);
  }
  void etp_rts(std::uint8_t sa, std::uint8_t da, j::Pgn pgn, std::size_t size) {
    control(j::kPgnEtpCm, sa, da, {kEtpRts, byte(size), byte(size >> 8), byte(size >> 16), byte(size >> 24)}, pgn);
  }
  void etp_cts(std::uint8_t receiver, std::uint8_t sender, j::Pgn pgn, std::uint8_t count, std::size_t next) {
    control(j::kPgnEtpCm, receiver, sender, {kEtpCts, count, byte(next), byte(next >> 8), byte(next >> 16)}, pgn);
  }
  void dpo(std::uint8_t sa, std::uint8_t da, j::Pgn pgn, std::uint8_t count, std::size_t offset) {
    control(j::kPgnEtpCm, sa, da, {kEtpDpo, count, byte(offset), byte(offset >> 8), byte(offset >> 16)}, pgn);
  }
  void etp_eoma(std::uint8_t receiver, std::uint8_t sender, j::Pgn pgn, std::size_t size) {
    control(j::kPgnEtpCm, receiver, sender, {kEtpEoma, byte(size), byte(size >> 8), byte(size >> 16), byte(size >> 24)},
            pgn);
  }

  // Data packet `packet` (1-based) of `payload`, padded with 0xFF, under sequence number `seq`.
  void data(j::Pgn dt, std::uint8_t sa, std::uint8_t da, const Bytes& payload, std::size_t packet, std::size_t seq) {
    Bytes bytes{byte(seq)};
    for (std::size_t i = (packet - 1) * 7; i < packet * 7; ++i) bytes.push_back(i < payload.size() ? payload[i] : 0xFF);
    send(j::make_can_id(7, dt, da, sa), bytes);
  }
  void dt(std::uint8_t sa, std::uint8_t da, const Bytes& payload, std::size_t packet) {
    data(j::kPgnTpDt, sa, da, payload, packet, packet);
  }
  void dts(std::uint8_t sa, std::uint8_t da, const Bytes& payload, std::size_t first, std::size_t last) {
    for (std::size_t p = first; p <= last; ++p) dt(sa, da, payload, p);
  }
  void broadcast(std::uint8_t sa, j::Pgn pgn, const Bytes& payload) {
    bam(sa, pgn, payload.size());
    dts(sa, kGlobal, payload, 1, packets(payload.size()));
  }

  j::TpReassembler tp_{};
  std::vector<Received> got_;
  CaptureTime now_ = roadload::capture_time_from_ns(1'000'000'000);
  CaptureTime last_{};  // stamp of the latest frame pushed
  std::uint8_t iface_ = 0;
  std::uint8_t cm_priority_ = 7;
};

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
  cts(0x21, 0x00, kDm1, 1, 3);    // the receiver asks for it again
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
  send(id, {});                                 // no sequence number
  send(id, {1, payload[0], payload[1]});        // packet 1 needs 7 bytes
  EXPECT_EQ(tp_.counters().malformed, 2u);
  dt(0x00, kGlobal, payload, 1);
  send(id, {2, payload[7], payload[8]});        // packet 2 needs only 2
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
  etp_rts(0x00, 0x21, kDm1, 1785);                                       // TP would do
  send(j::make_can_id(7, j::kPgnTpCm, kGlobal, 0x00), {kBam, 20, 0, 3});  // short frame
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

TEST_F(J1939TransportTest, EtpMessageOf3000BytesWithTwoDposIsReassembled) {
  const Bytes payload = pattern(3000, 3);  // 429 packets: 255 + 174
  etp_rts(0x00, 0x21, kProprietaryA, payload.size());
  etp_cts(0x21, 0x00, kProprietaryA, 255, 1);
  dpo(0x00, 0x21, kProprietaryA, 255, 0);
  for (std::size_t seq = 1; seq <= 255; ++seq) data(j::kPgnEtpDt, 0x00, 0x21, payload, seq, seq);
  etp_cts(0x21, 0x00, kProprietaryA, 174, 256);
  dpo(0x00, 0x21, kProprietaryA, 174, 255);
  for (std::size_t seq = 1; seq <= 174; ++seq) data(j::kPgnEtpDt, 0x00, 0x21, payload, 255 + seq, seq);
  ASSERT_EQ(got_.size(), 1u);
  EXPECT_EQ(got_[0].data, payload);
  EXPECT_TRUE(got_[0].extended);
  EXPECT_EQ(got_[0].pgn, kProprietaryA);
  EXPECT_EQ(got_[0].da, 0x21);
  etp_eoma(0x21, 0x00, kProprietaryA, payload.size());
  EXPECT_EQ(tp_.counters().etp_started, 1u);
  EXPECT_EQ(irregularities(tp_.counters()), 0u);
}

TEST_F(J1939TransportTest, EtpDataBeyondItsDpoWindowIsABadSequence) {
  const Bytes payload = pattern(2000);
  etp_rts(0x00, 0x21, kProprietaryA, payload.size());
  data(j::kPgnEtpDt, 0x00, 0x21, payload, 1, 1);  // before any DPO
  dpo(0x00, 0x21, kProprietaryA, 10, 0);
  data(j::kPgnEtpDt, 0x00, 0x21, payload, 11, 11);
  EXPECT_EQ(tp_.counters().bad_sequence, 2u);
  dpo(0x00, 0x21, kProprietaryA, 10, 280);  // beyond the 286 packets
  EXPECT_EQ(tp_.counters().malformed, 1u);
}

TEST_F(J1939TransportTest, EtpAbortFromReceiverEndsTheEtpSessionOnly) {
  etp_rts(0x00, 0x21, kProprietaryA, 2000);
  rts(0x00, 0x21, kProprietaryA, 20);
  abort(j::kPgnEtpCm, 0x21, 0x00, kProprietaryA);
  EXPECT_EQ(tp_.counters().aborted, 1u);
  EXPECT_EQ(tp_.open_sessions(), 1u);  // the TP session between the same pair lives on
  data(j::kPgnEtpDt, 0x00, 0x21, pattern(2000), 1, 1);
  EXPECT_EQ(tp_.counters().orphan_packets, 1u);
}

TEST_F(J1939TransportTest, EtpLargerThanMaxEtpBytesIsCountedTooLargeAndIgnored) {
  configure({.max_etp_bytes = 2000});
  const Bytes payload = pattern(3000);
  etp_rts(0x00, 0x21, kProprietaryA, payload.size());
  dpo(0x00, 0x21, kProprietaryA, 2, 0);
  data(j::kPgnEtpDt, 0x00, 0x21, payload, 1, 1);
  EXPECT_EQ(tp_.counters().too_large, 1u);
  EXPECT_EQ(tp_.counters().etp_started, 0u);
  EXPECT_EQ(tp_.counters().orphan_packets, 1u);
  EXPECT_TRUE(got_.empty());
}

TEST_F(J1939TransportTest, EtpSessionsBeyondMaxEtpSessionsCountNoFreeSession) {
  configure({.max_etp_sessions = 1});
  etp_rts(0x00, 0x21, kProprietaryA, 2000);
  etp_rts(0x03, 0x21, kProprietaryA, 2000);
  EXPECT_EQ(tp_.counters().etp_started, 1u);
  EXPECT_EQ(tp_.counters().no_free_session, 1u);
  rts(0x03, 0x21, kDm1, 20);  // TP slots are separate
  EXPECT_EQ(tp_.counters().rts_started, 1u);
}

TEST_F(J1939TransportTest, TwoInterfacesWithTheSameAddressesAreNotMixed) {
  const Bytes a = pattern(39, 1);
  const Bytes b = pattern(39, 2);
  for (const int i : {0, 1}) {
    iface_ = byte(i);
    bam(0x00, kEc1, 39);
  }
  for (std::size_t p = 1; p <= 6; ++p) {
    iface_ = 1;
    dt(0x00, kGlobal, b, p);
    iface_ = 0;
    dt(0x00, kGlobal, a, p);
  }
  ASSERT_EQ(got_.size(), 2u);
  EXPECT_EQ(got_[0].iface, 1);
  EXPECT_EQ(got_[0].data, b);
  EXPECT_EQ(got_[1].iface, 0);
  EXPECT_EQ(got_[1].data, a);
  EXPECT_EQ(irregularities(tp_.counters()), 0u);
}

// candump -L line "(sec.usec) iface ID#HEX" of a classic frame; enough for the embedded trace.
CanFrame parse_candump(std::string_view line) {
  const auto hex = [](char c) { return static_cast<std::uint32_t>(c <= '9' ? c - '0' : c - 'A' + 10); };
  CanFrame f;
  const std::size_t dot = line.find('.');
  const std::size_t close = line.find(')');
  std::int64_t sec = 0;
  std::int64_t usec = 0;
  for (std::size_t i = 1; i < dot; ++i) sec = sec * 10 + (line[i] - '0');
  for (std::size_t i = dot + 1; i < close; ++i) usec = usec * 10 + (line[i] - '0');
  f.t = roadload::capture_time_from_ns(sec * 1'000'000'000 + usec * 1'000);
  const std::size_t hash = line.find('#');
  for (std::size_t i = hash - 8; i < hash; ++i) f.id = (f.id << 4) | hex(line[i]);
  for (std::size_t i = hash + 1; i + 1 < line.size(); i += 2) {
    f.data[f.len++] = static_cast<std::uint8_t>((hex(line[i]) << 4) | hex(line[i + 1]));
  }
  return f;
}

TEST_F(J1939TransportTest, RealTruckEc1BamGivesReferenceTorque2386Nm) {
  // tests/data/traces/css-truck-idle.log lines 850-989: the EC1 BAM and one frame between.
  constexpr std::string_view kTrace[] = {
      "(1635188457.419000) can0 1CECFF00#20270006FFE3FE00",
      "(1635188457.420000) can0 0CF00400#507D84461400F084",
      "(1635188457.478950) can0 1CEBFF00#015014BD32418C20",
      "(1635188457.538950) can0 1CEBFF00#021CDFC02BE15834",
      "(1635188457.598950) can0 1CEBFF00#03D3A041FFFF5209",
      "(1635188457.658950) can0 1CEBFF00#04E0470341D07DE1",
      "(1635188457.718950) can0 1CEBFF00#053041BC03FFFF80",
      "(1635188457.778950) can0 1CEBFF00#06E0FFFFFFFFFFFF",
  };
  for (std::string_view line : kTrace) push(parse_candump(line));
  ASSERT_EQ(got_.size(), 1u);
  const Received& ec1 = got_[0];
  EXPECT_EQ(ec1.pgn, 65251u);
  EXPECT_EQ(ec1.sa, 0x00);
  EXPECT_EQ(ec1.t, roadload::capture_time_from_ns(1635188457'778950'000));
  ASSERT_EQ(ec1.data.size(), 39u);
  const int reference_torque_nm = ec1.data[19] | (ec1.data[20] << 8);  // SPN 544, bytes 20-21
  EXPECT_EQ(reference_torque_nm, 2386);
  EXPECT_EQ(irregularities(tp_.counters()), 0u);
}

TEST_F(J1939TransportTest, PushOf1785ByteBamDoesNotAllocate) {
  const Bytes payload = pattern(j::kTpMaxBytes);
  std::vector<CanFrame> frames;
  frames.reserve(256);
  CanFrame f;
  f.len = 8;
  f.id = j::make_can_id(7, j::kPgnTpCm, kGlobal, 0x00);
  f.data = {kBam, byte(payload.size()), byte(payload.size() >> 8), 255, 0xFF, 0xCA, 0xFE, 0x00};
  frames.push_back(f);
  f.id = j::make_can_id(7, j::kPgnTpDt, kGlobal, 0x00);
  for (std::size_t p = 1; p <= 255; ++p) {
    f.t += 50ms;
    f.data[0] = byte(p);
    std::copy_n(payload.begin() + static_cast<std::ptrdiff_t>((p - 1) * 7), 7, f.data.begin() + 1);
    frames.push_back(f);
  }

  // Sanity: the counter sees an allocation made while counting.
  {
    const roadload::test::CountAllocations count;
    auto probe = std::make_unique<int>(1);
    ASSERT_EQ(count.count(), 1u);
    ASSERT_EQ(*probe, 1);
  }

  std::size_t completed = 0;
  bool exact = false;
  std::size_t allocations = 0;
  {
    const roadload::test::CountAllocations count;
    for (const CanFrame& frame : frames) {
      if (auto m = tp_.push(frame)) {
        ++completed;
        exact = std::equal(m->data.begin(), m->data.end(), payload.begin(), payload.end());
      }
    }
    tp_.expire(f.t + 1h);
    allocations = count.count();
  }
  EXPECT_EQ(allocations, 0u);
  EXPECT_EQ(completed, 1u);
  EXPECT_TRUE(exact);
}

TEST_F(J1939TransportTest, NonTpFramesAreIgnored) {
  CanFrame f;
  f.len = 8;
  f.data.fill(0);
  for (const CanFrameKind kind : {CanFrameKind::standard, CanFrameKind::remote, CanFrameKind::error, CanFrameKind::fd}) {
    f.kind = kind;
    f.id = j::make_can_id(7, j::kPgnTpDt, kGlobal, 0x00);  // TP-looking id in a foreign frame
    push(f);
  }
  f.kind = CanFrameKind::extended;
  f.id = 0x0CF00400;  // EEC1
  push(f);
  f.id = j::make_can_id(7, 0x1EB00, kGlobal, 0x00);  // data page 1 is not TP
  push(f);
  f.id = j::make_can_id(6, 0xEA00, kGlobal, 0x00);  // Request: between the TP PGNs
  push(f);
  EXPECT_EQ(irregularities(tp_.counters()), 0u);
  EXPECT_TRUE(got_.empty());
}

// Random frames on the TP PGNs, with any length, kind and stamp: nothing may crash (the
// sanitizer build checks memory) and the session table stays within its bounds.
TEST_F(J1939TransportTest, GarbageFramesNeverCrash) {
  configure({.max_sessions = 4, .max_etp_sessions = 1, .max_etp_bytes = 4000});
  std::mt19937_64 rng(1939);
  constexpr j::Pgn kPgns[] = {j::kPgnTpCm, j::kPgnTpDt, j::kPgnEtpCm, j::kPgnEtpDt};
  constexpr std::uint8_t kControls[] = {kRts, kCts, kEoma, kBam, kEtpRts, kEtpCts, kEtpDpo, kEtpEoma, kAbort};
  std::int64_t t = 0;
  for (int i = 0; i < 200'000; ++i) {
    CanFrame f;
    const std::uint64_t r = rng();
    f.kind = (r & 0xF) == 0 ? static_cast<CanFrameKind>((r >> 4) % 5) : CanFrameKind::extended;
    f.id = j::make_can_id(byte(r >> 8), kPgns[(r >> 11) % 4], byte((r >> 13) % 3 == 0 ? 0xFF : (r >> 16) % 3),
                          byte((r >> 18) % 3));
    f.iface = byte((r >> 20) % 2);
    f.len = (r >> 22) % 16 == 0 ? byte(r >> 26) : 8;  // up to 255, beyond the data array
    for (auto& b : f.data) b = byte(rng());
    if ((r >> 34) % 3 == 0) f.data[0] = kControls[(r >> 36) % 9];
    if ((r >> 40) % 2 == 0) f.data[0] = byte(1 + (r >> 41) % 8);  // plausible sequence
    if ((r >> 44) % 4 == 0) std::fill_n(f.data.begin() + 2, 3, 0);  // small sizes and offsets
    t += static_cast<std::int64_t>((r >> 48) % 20'000'000);
    // Now and then a stamp at either end of the clock, or from the past.
    const std::int64_t extreme = (r >> 62) == 0 ? std::numeric_limits<std::int64_t>::max() - 5
                                                : std::numeric_limits<std::int64_t>::min() + 5;
    f.t = roadload::capture_time_from_ns((r >> 52) % 500 == 0 ? extreme : t);
    if (auto m = tp_.push(f)) {
      ASSERT_GE(m->data.size(), 9u);
    }
    ASSERT_LE(tp_.open_sessions(), 5u);
  }
  tp_.expire(CaptureTime::max());
  EXPECT_EQ(tp_.open_sessions(), 0u);
}

}  // namespace
