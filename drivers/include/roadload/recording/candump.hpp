#pragma once
// candump -L log lines: `(sec.frac) iface ID#DATA`, the format every can-utils tool reads.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "roadload/can_frame.hpp"

namespace roadload::recording {

// Interface names interned to the small index a CanFrame carries.
class InterfaceTable {
 public:
  static constexpr std::size_t kMax = 16;
  // Returns the index of `name`, adding it if new; nullopt when the table is full.
  std::optional<std::uint8_t> intern(std::string_view name);
  // The index of `name` if it is in the table.
  std::optional<std::uint8_t> find(std::string_view name);
  std::string_view name(std::uint8_t index) const;
  std::size_t size() const { return count_; }
  // The interface found or added last ("" while the table is empty), and its index.
  std::string_view last() const { return count_ > 0 ? std::string_view(names_[last_]) : std::string_view(); }
  std::uint8_t last_index() const { return last_; }
  // The last name's first eight bytes, the first in the lowest byte, zero-padded: most names are
  // compared in one load.
  std::uint64_t last_word() const { return words_[last_]; }

 private:
  std::array<std::string, kMax> names_;
  std::array<std::uint64_t, kMax> words_{};
  std::size_t count_ = 0;
  std::uint8_t last_ = 0;  // most logs repeat one interface line after line
};

struct LineError {
  const char* field;  // "timestamp", "interface", "identifier", "data", ...
  const char* message;
};

enum class LineResult : std::uint8_t { frame, ignored };

// Parses one line. Lines that do not start with '(' are `ignored`, as canplayer ignores them.
// On malformed input returns the error and leaves `out` unspecified.
std::optional<LineError> parse_candump_line(std::string_view line, InterfaceTable& ifaces, CanFrame& out, LineResult& result);

// Formats a frame as candump -L does (microsecond stamps, so canplayer replays it).
// Returns the number of characters written; `buf` must hold kMaxLineChars.
inline constexpr std::size_t kMaxLineChars = 192;
std::size_t format_candump_line(const CanFrame& f, std::string_view iface, char* buf);

// A stamp as its candump line keeps it, whole microseconds: what reads a recording sees this,
// so a live judgement that must agree with it (the cadence counts) is made on it too.
inline CaptureTime candump_stamp(CaptureTime t) {
  const std::int64_t ns = to_ns(t);
  return capture_time_from_ns(ns - ns % 1000);
}

}  // namespace roadload::recording
