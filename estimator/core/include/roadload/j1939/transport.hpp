#pragma once
// J1939-21 transport protocol (TP.CM/TP.DT, and ETP) reassembled from a passive listener's view:
// the logger never sends CTS or acknowledgements, it watches both sides of each session.
// Memory is fixed at construction; no allocation per frame.
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "roadload/can_frame.hpp"
#include "roadload/j1939/id.hpp"
#include "roadload/time.hpp"

namespace roadload::j1939 {

inline constexpr Pgn kPgnTpCm = 0xEC00;
inline constexpr Pgn kPgnTpDt = 0xEB00;
inline constexpr Pgn kPgnEtpCm = 0xC800;
inline constexpr Pgn kPgnEtpDt = 0xC700;
inline constexpr std::size_t kTpMaxBytes = 255 * 7;

// Control bytes: byte 1 of TP.CM and ETP.CM.
namespace tp_control {
inline constexpr std::uint8_t kRts = 0x10;
inline constexpr std::uint8_t kCts = 0x11;
inline constexpr std::uint8_t kEoma = 0x13;
inline constexpr std::uint8_t kBam = 0x20;
inline constexpr std::uint8_t kEtpRts = 0x14;
inline constexpr std::uint8_t kEtpCts = 0x15;
inline constexpr std::uint8_t kEtpDpo = 0x16;
inline constexpr std::uint8_t kEtpEoma = 0x17;
inline constexpr std::uint8_t kAbort = 0xFF;
}  // namespace tp_control

struct TpConfig {
  // J1939-21 T1 (750 ms) bounds the gap between BAM packets; T2/T3 (1250 ms) bound a connection.
  Nanoseconds bam_timeout = Nanoseconds{750'000'000};
  Nanoseconds connection_timeout = Nanoseconds{1'250'000'000};
  std::size_t max_sessions = 32;          // TP sessions open at once, across all buses
  std::size_t max_etp_sessions = 2;       // ETP sessions open at once
  std::size_t max_etp_bytes = 64 * 1024;  // larger ETP messages are counted in too_large and dropped
};

struct TpMessage {
  CaptureTime t;  // stamp of the frame that completed the message
  Pgn pgn = 0;
  std::uint8_t sa = 0;
  std::uint8_t da = kGlobalAddress;
  std::uint8_t priority = 6;
  std::uint8_t iface = 0;
  bool extended = false;               // carried by ETP
  std::span<const std::uint8_t> data;  // valid until the next push()
};

struct TpCounters {
  std::uint64_t bam_started = 0;
  std::uint64_t rts_started = 0;
  std::uint64_t etp_started = 0;
  std::uint64_t completed = 0;
  std::uint64_t aborted = 0;  // abort seen on the bus
  std::uint64_t timed_out = 0;
  std::uint64_t superseded = 0;  // a new announcement replaced an unfinished session
  std::uint64_t duplicate_packets = 0;
  std::uint64_t out_of_order_packets = 0;
  std::uint64_t orphan_packets = 0;  // TP.DT with no open session
  std::uint64_t bad_sequence = 0;    // sequence number 0 or beyond the announced count
  std::uint64_t malformed = 0;       // control frame too short or inconsistent
  std::uint64_t too_large = 0;
  std::uint64_t no_free_session = 0;
};

class TpReassembler {
 public:
  explicit TpReassembler(TpConfig config = {});

  // Feeds any frame; frames that are not TP/ETP are ignored. Sessions older than their timeout
  // (judged by this frame's stamp) are closed first. Returns a completed message, if this frame
  // completed one.
  std::optional<TpMessage> push(const CanFrame& frame);
  // Closes sessions that have timed out by `now` (for a quiet bus).
  void expire(CaptureTime now);

  const TpCounters& counters() const { return counters_; }
  std::size_t open_sessions() const;

 private:
  // One reassembly slot. sessions_ holds config.max_sessions TP slots, then max_etp_sessions ETP
  // slots; each owns a fixed slice of storage_ (data) and of received_ (one bit per packet).
  struct Session {
    enum class Mode : std::uint8_t { bam, rts, etp };
    // An RTS/ETP message stays `complete` until EOMA, abort or timeout, so that packets resent
    // on the receiver's request count as duplicates rather than orphans.
    enum class State : std::uint8_t { free, receiving, complete };
    State state = State::free;
    Mode mode = Mode::bam;
    std::uint8_t iface = 0;
    std::uint8_t sa = 0;
    std::uint8_t da = kGlobalAddress;
    std::uint8_t priority = 6;
    Pgn pgn = 0;
    std::uint32_t size = 0;
    std::uint32_t packets = 0;
    std::uint32_t received = 0;
    std::uint32_t first_missing = 1;  // lowest packet number (1-based) not yet received
    std::uint32_t dpo_offset = 0;     // ETP: packets before the window of the last DPO
    std::uint32_t dpo_packets = 0;    // ETP: packets in that window
    CaptureTime last{};               // stamp of the latest frame of the session
    std::size_t data_at = 0;          // offset of this slot in storage_
    std::size_t bits_at = 0;          // offset of this slot in received_
  };

  void on_control(const CanFrame& frame, bool etp);
  void announce(const CanFrame& frame, bool etp);
  void follow_up(const CanFrame& frame, bool etp);
  void data_offset(const CanFrame& frame);
  void abort(const CanFrame& frame, bool etp);
  std::optional<TpMessage> on_data(const CanFrame& frame, bool etp);
  std::optional<TpMessage> store(Session& s, std::uint32_t packet, const CanFrame& frame);
  TpMessage finish(Session& s, CaptureTime t);
  void open(const CanFrame& frame, Session::Mode mode, std::uint32_t size);
  std::span<Session> slots(bool etp);
  Session* find(bool etp, std::uint8_t iface, std::uint8_t sa, std::uint8_t da);
  Session* allocate(bool etp);
  void touch(Session& s, CaptureTime t);
  CaptureTime deadline(const Session& s) const;

  TpConfig config_;
  TpCounters counters_;
  std::vector<Session> sessions_;
  std::vector<std::uint8_t> storage_;
  std::vector<std::uint64_t> received_;
  // Earliest time at which some session may expire; push() scans sessions only past it, so a
  // frame that is not TP costs a compare. It may be early (sessions refreshed since), never late.
  CaptureTime next_deadline_ = CaptureTime::max();
};

}  // namespace roadload::j1939
