#include "roadload/j1939/signal.hpp"

#include <cmath>

namespace roadload::j1939 {
namespace {

constexpr std::uint64_t all_ones(unsigned bits) { return bits >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << bits) - 1; }

std::uint64_t extract_le(std::span<const std::uint8_t> p, unsigned start, unsigned length) {
  const unsigned first = start / 8;
  const unsigned shift = start % 8;
  const unsigned last = (start + length - 1) / 8;
  std::uint64_t raw = 0;
  // Up to 9 bytes can hold a 64-bit field that starts mid-byte; gather the top byte separately.
  for (unsigned i = first; i <= last && i < first + 8; ++i) raw |= std::uint64_t{p[i]} << (8 * (i - first));
  raw >>= shift;
  if (last >= first + 8) raw |= std::uint64_t{p[first + 8]} << (64 - shift);
  return raw & all_ones(length);
}

// Motorola order walks from the most significant bit at `start` down the DBC "sawtooth".
std::uint64_t extract_be(std::span<const std::uint8_t> p, unsigned start, unsigned length) {
  std::uint64_t raw = 0;
  unsigned byte = start / 8;
  unsigned bit = start % 8;
  for (unsigned n = 0; n < length; ++n) {
    raw = (raw << 1) | ((p[byte] >> bit) & 1u);
    if (bit == 0) {
      ++byte;
      bit = 7;
    } else {
      --bit;
    }
  }
  return raw;
}

void insert_le(std::span<std::uint8_t> p, unsigned start, unsigned length, std::uint64_t raw) {
  for (unsigned n = 0; n < length; ++n) {
    const unsigned b = start + n;
    const auto mask = static_cast<std::uint8_t>(1u << (b % 8));
    if ((raw >> n) & 1u) {
      p[b / 8] |= mask;
    } else {
      p[b / 8] &= static_cast<std::uint8_t>(~mask);
    }
  }
}

void insert_be(std::span<std::uint8_t> p, unsigned start, unsigned length, std::uint64_t raw) {
  unsigned byte = start / 8;
  unsigned bit = start % 8;
  for (unsigned n = 0; n < length; ++n) {
    const auto mask = static_cast<std::uint8_t>(1u << bit);
    if ((raw >> (length - 1 - n)) & 1u) {
      p[byte] |= mask;
    } else {
      p[byte] &= static_cast<std::uint8_t>(~mask);
    }
    if (bit == 0) {
      ++byte;
      bit = 7;
    } else {
      --bit;
    }
  }
}

bool has_reserved_ranges(const SignalDef& s) { return s.j1939_ranges && !s.is_signed && s.length >= 2; }

double to_physical(const SignalDef& s, std::uint64_t raw) {
  if (s.is_signed && s.length < 64 && ((raw >> (s.length - 1)) & 1u)) {
    const auto v = static_cast<std::int64_t>(raw | ~all_ones(s.length));
    return static_cast<double>(v) * s.factor + s.offset;
  }
  if (s.is_signed) return static_cast<double>(static_cast<std::int64_t>(raw)) * s.factor + s.offset;
  return static_cast<double>(raw) * s.factor + s.offset;
}

}  // namespace

const char* to_string(SignalState s) {
  switch (s) {
    case SignalState::valid: return "valid";
    case SignalState::parameter_specific: return "parameter-specific";
    case SignalState::reserved: return "reserved";
    case SignalState::error: return "error";
    case SignalState::not_available: return "n/a";
    case SignalState::missing: return "missing";
  }
  return "?";
}

std::size_t bytes_needed(const SignalDef& s) {
  if (s.order == ByteOrder::little_endian) return (std::size_t{s.start_bit} + s.length + 7) / 8;
  const unsigned bits_in_first = s.start_bit % 8 + 1u;
  const std::size_t first = s.start_bit / 8;
  if (s.length <= bits_in_first) return first + 1;
  return first + 1 + (s.length - bits_in_first + 7) / 8;
}

std::uint64_t extract_raw(const SignalDef& s, std::span<const std::uint8_t> payload) {
  return s.order == ByteOrder::little_endian ? extract_le(payload, s.start_bit, s.length)
                                             : extract_be(payload, s.start_bit, s.length);
}

void insert_raw(const SignalDef& s, std::uint64_t raw, std::span<std::uint8_t> payload) {
  raw &= all_ones(s.length);
  if (s.order == ByteOrder::little_endian) {
    insert_le(payload, s.start_bit, s.length, raw);
  } else {
    insert_be(payload, s.start_bit, s.length, raw);
  }
}

// J1939-71: for fields of a byte or more the most significant byte carries the indicator
// (0xFB parameter specific, 0xFC-0xFD reserved, 0xFE error, 0xFF not available). Shorter bit
// fields reserve all ones for "not available"; only 2-bit status fields also reserve 10b for
// "error", since wider fields (torque mode, occurrence count) define all ones minus one as a value.
SignalState classify_raw(const SignalDef& s, std::uint64_t raw) {
  if (!has_reserved_ranges(s)) return SignalState::valid;
  if (s.length < 8) {
    const std::uint64_t ones = all_ones(s.length);
    if (raw == ones) return SignalState::not_available;
    if (s.length == 2 && raw == ones - 1) return SignalState::error;
    return SignalState::valid;
  }
  const std::uint64_t top = raw >> (s.length - 8);
  if (top <= 0xFA) return SignalState::valid;
  if (top == 0xFB) return SignalState::parameter_specific;
  if (top == 0xFE) return SignalState::error;
  if (top == 0xFF) return SignalState::not_available;
  return SignalState::reserved;
}

std::uint64_t max_valid_raw(const SignalDef& s) {
  if (!has_reserved_ranges(s)) return s.is_signed ? all_ones(s.length - 1u) : all_ones(s.length);
  if (s.length < 8) return all_ones(s.length) - (s.length == 2 ? 2 : 1);
  return (std::uint64_t{0xFA} << (s.length - 8)) | all_ones(s.length - 8u);
}

SignalReading decode(const SignalDef& s, std::span<const std::uint8_t> payload) {
  SignalReading r;
  if (bytes_needed(s) > payload.size()) return r;
  r.raw = extract_raw(s, payload);
  r.state = classify_raw(s, r.raw);
  if (r.state == SignalState::valid) r.value = to_physical(s, r.raw);
  return r;
}

std::uint64_t encode(const SignalDef& s, double physical, std::span<std::uint8_t> payload) {
  const double steps = std::nearbyint((physical - s.offset) / s.factor);
  std::uint64_t raw = 0;
  if (s.is_signed) {
    const auto hi = static_cast<double>(max_valid_raw(s));
    const double clamped = std::fmax(-hi - 1.0, std::fmin(hi, steps));
    raw = static_cast<std::uint64_t>(static_cast<std::int64_t>(clamped)) & all_ones(s.length);
  } else {
    const auto hi = static_cast<double>(max_valid_raw(s));
    raw = std::isnan(steps) ? 0 : static_cast<std::uint64_t>(std::fmax(0.0, std::fmin(hi, steps)));
  }
  insert_raw(s, raw, payload);
  return raw;
}

void encode_state(const SignalDef& s, SignalState state, std::span<std::uint8_t> payload) {
  const std::uint64_t ones = all_ones(s.length);
  const std::uint64_t low = s.length >= 8 ? all_ones(s.length - 8u) : 0;
  std::uint64_t raw = ones;
  if (state == SignalState::error) raw = s.length >= 8 ? (std::uint64_t{0xFE} << (s.length - 8)) | low : ones - 1;
  insert_raw(s, raw, payload);
}

}  // namespace roadload::j1939
