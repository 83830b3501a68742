#pragma once
#include <array>
#include <cstdint>
#include <span>

#include "roadload/time.hpp"

namespace roadload {

enum class CanFrameKind : std::uint8_t {
  standard,  // 11-bit identifier
  extended,  // 29-bit identifier (J1939)
  remote,    // RTR, no payload
  error,     // error frame reported by the controller; id holds the error class bits
  fd,        // CAN FD, up to 64 bytes
};

struct CanFrame {
  CaptureTime t;
  std::uint32_t id = 0;  // without EFF/RTR/ERR flag bits
  CanFrameKind kind = CanFrameKind::extended;
  bool id29 = false;          // FD and remote frames may carry an 11- or 29-bit id
  std::uint8_t fd_flags = 0;  // BRS/ESI as candump writes them
  std::uint8_t iface = 0;     // index into the recording's interface table
  std::uint8_t len = 0;       // payload bytes
  std::array<std::uint8_t, 64> data{};

  std::span<const std::uint8_t> payload() const { return {data.data(), len}; }
  bool is_j1939() const { return kind == CanFrameKind::extended; }
};

}  // namespace roadload
