#pragma once
// Signal (SPN) extraction and insertion with J1939-71's reserved ranges: a "not available" or
// "error" raw value decodes to no value, never to a number.
#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace roadload::j1939 {

enum class ByteOrder : std::uint8_t {
  little_endian,  // DBC @1, Intel; every J1939 parameter
  big_endian,     // DBC @0, Motorola; accepted for users' own DBCs
};

struct SignalDef {
  std::string name;
  std::uint32_t spn = 0;        // 0 when the DBC names none
  std::uint16_t start_bit = 0;  // DBC numbering: LSB for little endian, MSB (sawtooth) for big endian
  std::uint8_t length = 1;      // bits, 1..64
  ByteOrder order = ByteOrder::little_endian;
  bool is_signed = false;
  double factor = 1.0;
  double offset = 0.0;
  double minimum = 0.0;  // physical range from the DBC; 0,0 means unspecified
  double maximum = 0.0;
  std::string unit;
  // A plain bit pattern (DBC signals of a raw nature) has no J1939 reserved ranges.
  bool j1939_ranges = true;
};

enum class SignalState : std::uint8_t {
  valid,
  parameter_specific,  // 0xFB in the most significant byte
  reserved,            // 0xFC-0xFD
  error,               // 0xFE..., or all ones minus one for bit fields
  not_available,       // 0xFF..., or all ones for bit fields
  missing,             // the signal lies beyond the received payload
};

const char* to_string(SignalState s);

struct SignalReading {
  SignalState state = SignalState::missing;
  double value = 0.0;  // physical value; only meaningful when state == valid
  std::uint64_t raw = 0;

  std::optional<double> get() const { return state == SignalState::valid ? std::optional<double>(value) : std::nullopt; }
};

std::uint64_t extract_raw(const SignalDef& s, std::span<const std::uint8_t> payload);
void insert_raw(const SignalDef& s, std::uint64_t raw, std::span<std::uint8_t> payload);
SignalState classify_raw(const SignalDef& s, std::uint64_t raw);
// Byte length the payload must have for the signal to be present.
std::size_t bytes_needed(const SignalDef& s);

SignalReading decode(const SignalDef& s, std::span<const std::uint8_t> payload);

// Quantises as an ECU does (round to nearest step) and clamps into the valid raw range, so the
// encoder never produces a reserved pattern by accident. Returns the raw value written.
std::uint64_t encode(const SignalDef& s, double physical, std::span<std::uint8_t> payload);
// Writes the reserved pattern for not_available or error.
void encode_state(const SignalDef& s, SignalState state, std::span<std::uint8_t> payload);

// Largest raw value that is a valid reading for this signal.
std::uint64_t max_valid_raw(const SignalDef& s);

}  // namespace roadload::j1939
