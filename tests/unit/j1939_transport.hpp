#pragma once
// The J1939 transport tests' bus: frames stamped on a test clock pushed into a reassembler, with
// the control and data frames of BAM, RTS/CTS and ETP sessions built by their fields.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <vector>

#include "roadload/j1939/transport.hpp"

namespace roadload::j1939::transport_test {

namespace j = roadload::j1939;
using roadload::CanFrame;
using roadload::CanFrameKind;
using roadload::CaptureTime;
using roadload::Nanoseconds;
using namespace std::chrono_literals;

using namespace roadload::j1939::tp_control;
inline constexpr std::uint8_t kGlobal = 0xFF;
inline constexpr j::Pgn kEc1 = 0xFEE3;
inline constexpr j::Pgn kDm1 = 0xFECA;
inline constexpr j::Pgn kProprietaryA = 0xEF00;
inline constexpr Nanoseconds kStep = 10ms;  // spacing between consecutive frames in these tests

using Bytes = std::vector<std::uint8_t>;

inline std::uint8_t byte(std::size_t v) { return static_cast<std::uint8_t>(v & 0xFFu); }

// Distinct bytes across a long message, so a misplaced packet shows up.
inline Bytes pattern(std::size_t n, std::size_t seed = 0) {
  Bytes v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = byte(seed + i * 31 + i / 251);
  return v;
}

inline std::uint8_t packets(std::size_t size) { return byte((size + 6) / 7); }

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
inline std::uint64_t irregularities(const j::TpCounters& c) {
  return c.aborted + c.timed_out + c.superseded + c.duplicate_packets + c.out_of_order_packets + c.orphan_packets + c.bad_sequence +
         c.malformed + c.too_large + c.no_free_session;
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
      got_.push_back(Received{m->t, m->pgn, m->sa, m->da, m->priority, m->iface, m->extended, Bytes(m->data.begin(), m->data.end())});
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
    control(j::kPgnEtpCm, receiver, sender, {kEtpEoma, byte(size), byte(size >> 8), byte(size >> 16), byte(size >> 24)}, pgn);
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

}  // namespace roadload::j1939::transport_test
