// J1939 extended transport (ETP), several interfaces, a real truck's BAM, no allocation per frame,
// and frames that are not transport at all.
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
      "(1635188457.419000) can0 1CECFF00#20270006FFE3FE00", "(1635188457.420000) can0 0CF00400#507D84461400F084",
      "(1635188457.478950) can0 1CEBFF00#015014BD32418C20", "(1635188457.538950) can0 1CEBFF00#021CDFC02BE15834",
      "(1635188457.598950) can0 1CEBFF00#03D3A041FFFF5209", "(1635188457.658950) can0 1CEBFF00#04E0470341D07DE1",
      "(1635188457.718950) can0 1CEBFF00#053041BC03FFFF80", "(1635188457.778950) can0 1CEBFF00#06E0FFFFFFFFFFFF",
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
    f.id = j::make_can_id(byte(r >> 8), kPgns[(r >> 11) % 4], byte((r >> 13) % 3 == 0 ? 0xFF : (r >> 16) % 3), byte((r >> 18) % 3));
    f.iface = byte((r >> 20) % 2);
    f.len = (r >> 22) % 16 == 0 ? byte(r >> 26) : 8;  // up to 255, beyond the data array
    for (auto& b : f.data) b = byte(rng());
    if ((r >> 34) % 3 == 0) f.data[0] = kControls[(r >> 36) % 9];
    if ((r >> 40) % 2 == 0) f.data[0] = byte(1 + (r >> 41) % 8);    // plausible sequence
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
