#pragma once
// J1939-21 29-bit identifier: priority(3) EDP(1) DP(1) PF(8) PS(8) SA(8).
#include <cstdint>

namespace roadload::j1939 {

using Pgn = std::uint32_t;
inline constexpr std::uint8_t kGlobalAddress = 0xFF;
inline constexpr std::uint8_t kPdu2Threshold = 240;  // PF >= 240: PS is a group extension

struct Id {
  std::uint8_t priority = 6;
  bool edp = false;  // extended data page; EDP=1,DP=1 is ISO 15765-3, not J1939
  bool dp = false;   // data page
  std::uint8_t pf = 0;
  std::uint8_t ps = 0;
  std::uint8_t sa = 0;

  constexpr bool pdu1() const { return pf < kPdu2Threshold; }
  // PDU1 messages are addressed: PS is the destination and is not part of the PGN.
  constexpr Pgn pgn() const {
    const Pgn page = (Pgn{edp} << 17) | (Pgn{dp} << 16) | (Pgn{pf} << 8);
    return pdu1() ? page : page | ps;
  }
  constexpr std::uint8_t da() const { return pdu1() ? ps : kGlobalAddress; }
  constexpr bool operator==(const Id&) const = default;
};

constexpr Id parse_id(std::uint32_t can_id) {
  return Id{static_cast<std::uint8_t>((can_id >> 26) & 0x7),
            ((can_id >> 25) & 1) != 0,
            ((can_id >> 24) & 1) != 0,
            static_cast<std::uint8_t>(can_id >> 16),
            static_cast<std::uint8_t>(can_id >> 8),
            static_cast<std::uint8_t>(can_id)};
}

constexpr std::uint32_t to_can_id(const Id& id) {
  return (std::uint32_t{id.priority & 7u} << 26) | (std::uint32_t{id.edp} << 25) | (std::uint32_t{id.dp} << 24) |
         (std::uint32_t{id.pf} << 16) | (std::uint32_t{id.ps} << 8) | id.sa;
}

// For a PDU1 PGN the destination goes into PS; for PDU2 it is ignored (the PGN fixes PS).
constexpr std::uint32_t make_can_id(std::uint8_t priority, Pgn pgn, std::uint8_t da, std::uint8_t sa) {
  Id id;
  id.priority = priority;
  id.edp = ((pgn >> 17) & 1) != 0;
  id.dp = ((pgn >> 16) & 1) != 0;
  id.pf = static_cast<std::uint8_t>(pgn >> 8);
  id.ps = id.pdu1() ? da : static_cast<std::uint8_t>(pgn);
  id.sa = sa;
  return to_can_id(id);
}

constexpr Pgn pgn_of(std::uint32_t can_id) { return parse_id(can_id).pgn(); }

}  // namespace roadload::j1939
