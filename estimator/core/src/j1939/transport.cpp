#include "roadload/j1939/transport.hpp"

#include <algorithm>

namespace roadload::j1939 {
namespace {

using namespace tp_control;

constexpr std::size_t kBytesPerPacket = 7;
constexpr std::size_t kTpMaxPackets = 255;
constexpr std::size_t kTpMinBytes = 9;  // 8 bytes or fewer go in a single frame
constexpr std::size_t kFrameBytes = 8;  // TP/ETP frames are classic CAN frames
constexpr std::size_t kWordBits = 64;

// Every TP/ETP PGN is PDU1 with EDP = DP = 0, so EDP|DP|PF alone identifies it.
constexpr std::uint32_t kTpCmPf = kPgnTpCm >> 8;
constexpr std::uint32_t kTpDtPf = kPgnTpDt >> 8;
constexpr std::uint32_t kEtpCmPf = kPgnEtpCm >> 8;
constexpr std::uint32_t kEtpDtPf = kPgnEtpDt >> 8;
static_assert(kEtpDtPf < kEtpCmPf && kEtpCmPf < kTpDtPf && kTpDtPf < kTpCmPf);

constexpr std::size_t packets_for(std::size_t bytes) { return (bytes + kBytesPerPacket - 1) / kBytesPerPacket; }
constexpr std::size_t words_for(std::size_t bits) { return (bits + kWordBits - 1) / kWordBits; }

std::uint8_t source(const CanFrame& f) { return static_cast<std::uint8_t>(f.id); }
// TP PGNs are PDU1, so PS is the destination (0xFF for BAM).
std::uint8_t destination(const CanFrame& f) { return static_cast<std::uint8_t>(f.id >> 8); }
std::uint8_t priority(const CanFrame& f) { return static_cast<std::uint8_t>((f.id >> 26) & 7u); }

// Little-endian field of `count` bytes starting at 0-based byte `first`.
std::uint32_t le(const CanFrame& f, std::size_t first, std::size_t count) {
  std::uint32_t v = 0;
  for (std::size_t i = count; i-- > 0;) v = (v << 8) | f.data[first + i];
  return v;
}

// All TP.CM and ETP.CM frames carry the PGN of the packeted message in bytes 6-8.
Pgn announced_pgn(const CanFrame& f) { return le(f, 5, 3); }

bool test_bit(const std::uint64_t* words, std::uint32_t index) {
  return ((words[index / kWordBits] >> (index % kWordBits)) & 1u) != 0;
}

}  // namespace

TpReassembler::TpReassembler(TpConfig config)
    : config_(config),
      sessions_(config.max_sessions + config.max_etp_sessions),
      storage_(config.max_sessions * kTpMaxBytes + config.max_etp_sessions * config.max_etp_bytes),
      received_(config.max_sessions * words_for(kTpMaxPackets) +
                config.max_etp_sessions * words_for(packets_for(config.max_etp_bytes))) {
  std::size_t data_at = 0;
  std::size_t bits_at = 0;
  for (std::size_t i = 0; i < sessions_.size(); ++i) {
    const bool etp = i >= config_.max_sessions;
    sessions_[i].data_at = data_at;
    sessions_[i].bits_at = bits_at;
    data_at += etp ? config_.max_etp_bytes : kTpMaxBytes;
    bits_at += words_for(etp ? packets_for(config_.max_etp_bytes) : kTpMaxPackets);
  }
}

std::optional<TpMessage> TpReassembler::push(const CanFrame& frame) {
  if (frame.t > next_deadline_) expire(frame.t);
  if (frame.kind != CanFrameKind::extended) return std::nullopt;
  // One unsigned compare rejects nearly all traffic (PDU2 broadcasts sit above 0xF0).
  const std::uint32_t page_pf = (frame.id >> 16) & 0x3FFu;
  if (page_pf - kEtpDtPf > kTpCmPf - kEtpDtPf) return std::nullopt;
  switch (page_pf) {
    case kTpCmPf: on_control(frame, false); break;
    case kEtpCmPf: on_control(frame, true); break;
    case kTpDtPf: return on_data(frame, false);
    case kEtpDtPf: return on_data(frame, true);
    default: break;
  }
  return std::nullopt;
}

void TpReassembler::expire(CaptureTime now) {
  next_deadline_ = CaptureTime::max();
  for (Session& s : sessions_) {
    if (s.state == Session::State::free) continue;
    const CaptureTime due = deadline(s);
    if (now <= due) {
      next_deadline_ = std::min(next_deadline_, due);
      continue;
    }
    // A complete session was only waiting for its EOMA: nothing was lost.
    if (s.state == Session::State::receiving) ++counters_.timed_out;
    s.state = Session::State::free;
  }
}

std::size_t TpReassembler::open_sessions() const {
  return static_cast<std::size_t>(
      std::count_if(sessions_.begin(), sessions_.end(), [](const Session& s) { return s.state == Session::State::receiving; }));
}

void TpReassembler::on_control(const CanFrame& frame, bool etp) {
  if (frame.len < kFrameBytes) {
    ++counters_.malformed;
    return;
  }
  const std::uint8_t c = frame.data[0];
  if (c == kAbort) {
    abort(frame, etp);
  } else if (etp ? c == kEtpRts : (c == kRts || c == kBam)) {
    announce(frame, etp);
  } else if (etp ? (c == kEtpCts || c == kEtpEoma) : (c == kCts || c == kEoma)) {
    follow_up(frame, etp);
  } else if (etp && c == kEtpDpo) {
    data_offset(frame);
  } else {
    ++counters_.malformed;
  }
}

void TpReassembler::announce(const CanFrame& frame, bool etp) {
  const bool bam = !etp && frame.data[0] == kBam;
  const std::uint32_t size = etp ? le(frame, 1, 4) : le(frame, 1, 2);
  // ETP exists only for what TP cannot carry; a TP announcement must agree with itself.
  const bool size_ok = etp ? size > kTpMaxBytes : size >= kTpMinBytes && size <= kTpMaxBytes && frame.data[3] == packets_for(size);
  // A BAM goes to everyone, an RTS to one node: otherwise the session key would be ambiguous.
  if (!size_ok || bam != (destination(frame) == kGlobalAddress)) {
    ++counters_.malformed;
    return;
  }
  if (etp && size > config_.max_etp_bytes) {
    ++counters_.too_large;
    return;
  }
  open(frame, bam ? Session::Mode::bam : etp ? Session::Mode::etp : Session::Mode::rts, size);
}

void TpReassembler::open(const CanFrame& frame, Session::Mode mode, std::uint32_t size) {
  const bool etp = mode == Session::Mode::etp;
  Session* s = find(etp, frame.iface, source(frame), destination(frame));
  if (s != nullptr && s->state == Session::State::receiving) ++counters_.superseded;
  if (s == nullptr) s = allocate(etp);
  if (s == nullptr) {
    ++counters_.no_free_session;
    return;
  }
  s->state = Session::State::receiving;
  s->mode = mode;
  s->iface = frame.iface;
  s->sa = source(frame);
  s->da = destination(frame);
  s->priority = priority(frame);
  s->pgn = announced_pgn(frame);
  s->size = size;
  s->packets = static_cast<std::uint32_t>(packets_for(size));
  s->received = 0;
  s->first_missing = 1;
  s->dpo_offset = 0;
  s->dpo_packets = 0;
  std::fill_n(received_.data() + s->bits_at, words_for(s->packets), std::uint64_t{0});
  touch(*s, frame.t);
  ++(mode == Session::Mode::bam ? counters_.bam_started : etp ? counters_.etp_started : counters_.rts_started);
}

void TpReassembler::follow_up(const CanFrame& frame, bool etp) {
  // CTS and EOMA come from the receiver: the session's source is this frame's destination.
  Session* s = find(etp, frame.iface, destination(frame), source(frame));
  if (s == nullptr || s->mode == Session::Mode::bam || s->pgn != announced_pgn(frame)) return;
  const bool eom = frame.data[0] == (etp ? kEtpEoma : kEoma);
  if (eom && s->state == Session::State::complete) {
    s->state = Session::State::free;
    return;
  }
  // A CTS (a hold, too) proves the session alive. An EOMA for data we partly missed leaves the
  // session to time out, so the loss is counted.
  touch(*s, frame.t);
}

void TpReassembler::data_offset(const CanFrame& frame) {
  Session* s = find(true, frame.iface, source(frame), destination(frame));
  if (s == nullptr || s->pgn != announced_pgn(frame)) return;
  const std::uint32_t count = frame.data[1];
  const std::uint32_t offset = le(frame, 2, 3);
  if (count == 0 || offset + count > s->packets) {
    ++counters_.malformed;
    return;
  }
  s->dpo_offset = offset;
  s->dpo_packets = count;
  touch(*s, frame.t);
}

void TpReassembler::abort(const CanFrame& frame, bool etp) {
  ++counters_.aborted;
  // Either side may abort; the PGN tells which direction's session ends when both exist.
  const std::uint8_t a = source(frame);
  const std::uint8_t b = destination(frame);
  for (Session* s : {find(etp, frame.iface, a, b), find(etp, frame.iface, b, a)}) {
    if (s != nullptr && s->mode != Session::Mode::bam && s->pgn == announced_pgn(frame)) {
      s->state = Session::State::free;
      return;
    }
  }
}

std::optional<TpMessage> TpReassembler::on_data(const CanFrame& frame, bool etp) {
  if (frame.len == 0) {
    ++counters_.malformed;
    return std::nullopt;
  }
  Session* s = find(etp, frame.iface, source(frame), destination(frame));
  if (s == nullptr) {
    ++counters_.orphan_packets;
    return std::nullopt;
  }
  // ETP sequence numbers count from the offset of the last DPO; before any DPO none is valid.
  const std::uint32_t seq = frame.data[0];
  if (seq == 0 || seq > (etp ? s->dpo_packets : s->packets)) {
    ++counters_.bad_sequence;
    return std::nullopt;
  }
  touch(*s, frame.t);
  return store(*s, (etp ? s->dpo_offset : 0) + seq, frame);
}

std::optional<TpMessage> TpReassembler::store(Session& s, std::uint32_t packet, const CanFrame& frame) {
  std::uint64_t* bits = received_.data() + s.bits_at;
  const std::uint32_t index = packet - 1;
  if (test_bit(bits, index)) {
    ++counters_.duplicate_packets;
    return std::nullopt;
  }
  const std::size_t at = std::size_t{index} * kBytesPerPacket;
  const std::size_t n = std::min(kBytesPerPacket, std::size_t{s.size} - at);
  // Only the padding may be missing from a short frame, never the message's own bytes.
  if (std::min<std::size_t>(frame.len, kFrameBytes) < n + 1) {
    ++counters_.malformed;
    return std::nullopt;
  }
  std::copy_n(frame.data.begin() + 1, n, storage_.begin() + static_cast<std::ptrdiff_t>(s.data_at + at));
  bits[index / kWordBits] |= std::uint64_t{1} << (index % kWordBits);
  ++s.received;
  // Out of order: an earlier packet is still missing (lost, or to be resent on a CTS).
  if (packet > s.first_missing) ++counters_.out_of_order_packets;
  while (s.first_missing <= s.packets && test_bit(bits, s.first_missing - 1)) ++s.first_missing;
  if (s.received < s.packets) return std::nullopt;
  return finish(s, frame.t);
}

TpMessage TpReassembler::finish(Session& s, CaptureTime t) {
  ++counters_.completed;
  // RTS/ETP: the data is emitted without waiting for EOMA, which may be lost; the slot lingers
  // so that resent packets are recognised as duplicates. A BAM has nothing more to come.
  s.state = s.mode == Session::Mode::bam ? Session::State::free : Session::State::complete;
  TpMessage m;
  m.t = t;
  m.pgn = s.pgn;
  m.sa = s.sa;
  m.da = s.da;
  m.priority = s.priority;
  m.iface = s.iface;
  m.extended = s.mode == Session::Mode::etp;
  m.data = std::span<const std::uint8_t>(storage_.data() + s.data_at, s.size);
  return m;
}

std::span<TpReassembler::Session> TpReassembler::slots(bool etp) {
  const std::span<Session> all(sessions_);
  return etp ? all.subspan(config_.max_sessions) : all.first(config_.max_sessions);
}

TpReassembler::Session* TpReassembler::find(bool etp, std::uint8_t iface, std::uint8_t sa, std::uint8_t da) {
  for (Session& s : slots(etp)) {
    if (s.state != Session::State::free && s.iface == iface && s.sa == sa && s.da == da) return &s;
  }
  return nullptr;
}

TpReassembler::Session* TpReassembler::allocate(bool etp) {
  // A complete session only waits for its EOMA; reuse it rather than drop a new message.
  for (const Session::State wanted : {Session::State::free, Session::State::complete}) {
    for (Session& s : slots(etp)) {
      if (s.state == wanted) return &s;
    }
  }
  return nullptr;
}

void TpReassembler::touch(Session& s, CaptureTime t) {
  s.last = t;
  next_deadline_ = std::min(next_deadline_, deadline(s));
}

CaptureTime TpReassembler::deadline(const Session& s) const {
  const Nanoseconds timeout = s.mode == Session::Mode::bam ? config_.bam_timeout : config_.connection_timeout;
  // Saturate: stamps come from recordings and may be anything.
  if (s.last > CaptureTime::max() - timeout) return CaptureTime::max();
  return s.last + timeout;
}

}  // namespace roadload::j1939
