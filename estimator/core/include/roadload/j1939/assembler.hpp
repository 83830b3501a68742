#pragma once
// Turns the frame stream into J1939 messages: single-frame PGNs pass straight through, transport
// sessions come out once complete. TP.CM/TP.DT frames are consumed here and never decoded as data.
#include <optional>
#include <span>

#include "roadload/can_frame.hpp"
#include "roadload/j1939/id.hpp"
#include "roadload/j1939/transport.hpp"

namespace roadload::j1939 {

struct Message {
  CaptureTime t;
  Pgn pgn = 0;
  std::uint8_t sa = 0;
  std::uint8_t da = kGlobalAddress;
  std::uint8_t priority = 6;
  std::uint8_t iface = 0;
  bool reassembled = false;
  // Points into the pushed frame or the reassembler: valid until the next push() and while the
  // frame lives.
  std::span<const std::uint8_t> data;
};

class MessageAssembler {
 public:
  explicit MessageAssembler(TpConfig config = {}) : tp_(config) {}

  std::optional<Message> push(const CanFrame& frame);
  const TpReassembler& transport() const { return tp_; }

 private:
  TpReassembler tp_;
};

constexpr bool is_transport_pgn(Pgn pgn) { return pgn == kPgnTpCm || pgn == kPgnTpDt || pgn == kPgnEtpCm || pgn == kPgnEtpDt; }

}  // namespace roadload::j1939
