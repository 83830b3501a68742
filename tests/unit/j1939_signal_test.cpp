// Signal extraction and insertion, independent of any DBC: bit positions, byte orders, reserved
// ranges and quantisation.
#include <gtest/gtest.h>

#include <array>

#include "roadload/j1939/signal.hpp"

namespace roadload::j1939 {
namespace {

SignalDef def(std::uint16_t start, std::uint8_t len, double factor = 1.0, double offset = 0.0) {
  SignalDef s;
  s.name = "x";
  s.start_bit = start;
  s.length = len;
  s.factor = factor;
  s.offset = offset;
  return s;
}

TEST(Signal, LittleEndianTwoByteFieldReadsLowByteFirst) {
  // Engine speed, bytes 4-5, 0.125 rpm/bit: 0x1A40 = 6720 -> 840 rpm.
  const std::array<std::uint8_t, 8> p{0xFF, 0xFF, 0xFF, 0x40, 0x1A, 0xFF, 0xFF, 0xFF};
  const SignalReading r = decode(def(24, 16, 0.125), p);
  ASSERT_EQ(r.state, SignalState::valid);
  EXPECT_DOUBLE_EQ(r.value, 840.0);
}

TEST(Signal, NibbleInUpperHalfOfByte) {
  const std::array<std::uint8_t, 8> p{0xA5};
  EXPECT_EQ(extract_raw(def(4, 4), p), 0xAu);
  EXPECT_EQ(extract_raw(def(0, 4), p), 0x5u);
}

TEST(Signal, FieldCrossingByteBoundaryAtOddBit) {
  // 12 bits starting at bit 6: bits 6-7 of byte 0 and bits 0-9 of the rest.
  const std::array<std::uint8_t, 8> p{0xC0, 0xFF, 0x03};
  EXPECT_EQ(extract_raw(def(6, 12), p), 0xFFFu);
}

TEST(Signal, SixtyFourBitFieldStartingMidByteUsesNineBytes) {
  std::array<std::uint8_t, 9> p{};
  SignalDef s = def(4, 64);
  s.j1939_ranges = false;
  insert_raw(s, 0x0123456789ABCDEFull, p);
  EXPECT_EQ(extract_raw(s, p), 0x0123456789ABCDEFull);
  EXPECT_EQ(p[0], 0xF0);
  EXPECT_EQ(p[8], 0x00);
}

TEST(Signal, BigEndianFollowsDbcSawtooth) {
  // Motorola 16-bit signal with MSB at bit 7 of byte 0: bytes 0x12 0x34 read 0x1234.
  SignalDef s = def(7, 16);
  s.order = ByteOrder::big_endian;
  const std::array<std::uint8_t, 8> p{0x12, 0x34};
  EXPECT_EQ(extract_raw(s, p), 0x1234u);
  EXPECT_EQ(bytes_needed(s), 2u);
  std::array<std::uint8_t, 8> q{};
  insert_raw(s, 0xBEEF, q);
  EXPECT_EQ(q[0], 0xBE);
  EXPECT_EQ(q[1], 0xEF);
}

TEST(Signal, OneByteReservedRanges) {
  const SignalDef s = def(0, 8, 1.0, -125.0);
  const std::array<std::uint8_t, 1> fa{0xFA}, fb{0xFB}, fc{0xFC}, fe{0xFE}, ff{0xFF};
  EXPECT_EQ(decode(s, fa).state, SignalState::valid);
  EXPECT_DOUBLE_EQ(*decode(s, fa).get(), 125.0);
  EXPECT_EQ(decode(s, fb).state, SignalState::parameter_specific);
  EXPECT_EQ(decode(s, fc).state, SignalState::reserved);
  EXPECT_EQ(decode(s, fe).state, SignalState::error);
  EXPECT_EQ(decode(s, ff).state, SignalState::not_available);
  EXPECT_FALSE(decode(s, ff).get().has_value());
}

TEST(Signal, TwoByteRangesAreDecidedByMostSignificantByte) {
  const SignalDef s = def(0, 16, 0.125);
  const std::array<std::uint8_t, 2> max{0xFF, 0xFA}, err{0x00, 0xFE}, na{0xFF, 0xFF};
  EXPECT_DOUBLE_EQ(*decode(s, max).get(), 8031.875);
  EXPECT_EQ(decode(s, err).state, SignalState::error);
  EXPECT_EQ(decode(s, na).state, SignalState::not_available);
}

TEST(Signal, TwoBitFieldNotAvailableAndError) {
  const SignalDef s = def(4, 2);
  const std::array<std::uint8_t, 1> pressed{0x10}, error{0x20}, na{0x30};
  EXPECT_DOUBLE_EQ(*decode(s, pressed).get(), 1.0);
  EXPECT_EQ(decode(s, error).state, SignalState::error);
  EXPECT_EQ(decode(s, na).state, SignalState::not_available);
}

TEST(Signal, SignalBeyondPayloadIsMissingNotZero) {
  const std::array<std::uint8_t, 4> p{};
  EXPECT_EQ(decode(def(24, 16), p).state, SignalState::missing);
}

TEST(Signal, EncoderRoundsToNearestStepAndNeverWritesReservedPattern) {
  const SignalDef s = def(0, 16, 0.125);
  std::array<std::uint8_t, 2> p{};
  EXPECT_EQ(encode(s, 650.06, p), 5200u);  // 650.06 / 0.125 = 5200.48
  EXPECT_EQ(encode(s, 99999.0, p), 0xFAFFu);
  EXPECT_EQ(decode(s, p).state, SignalState::valid);
  EXPECT_EQ(encode(s, -5.0, p), 0u);
}

TEST(Signal, EncodeStateWritesNotAvailableAndError) {
  const SignalDef two_byte = def(8, 16);
  std::array<std::uint8_t, 3> p{};
  encode_state(two_byte, SignalState::not_available, p);
  EXPECT_EQ(decode(two_byte, p).state, SignalState::not_available);
  encode_state(two_byte, SignalState::error, p);
  EXPECT_EQ(decode(two_byte, p).state, SignalState::error);
  EXPECT_EQ(p[0], 0x00);  // neighbours untouched
  const SignalDef bits = def(2, 2);
  encode_state(bits, SignalState::error, p);
  EXPECT_EQ(decode(bits, p).state, SignalState::error);
}

TEST(Signal, WiderBitFieldsReserveOnlyAllOnes) {
  // A 7-bit occurrence count: 126 is a count, 127 is "not available".
  const SignalDef count = def(0, 7);
  const std::array<std::uint8_t, 1> c126{0x7E}, c127{0x7F};
  EXPECT_DOUBLE_EQ(*decode(count, c126).get(), 126.0);
  EXPECT_EQ(decode(count, c127).state, SignalState::not_available);
  EXPECT_EQ(max_valid_raw(count), 126u);
}

TEST(Signal, FieldWithoutJ1939RangesDecodesEveryPattern) {
  SignalDef s = def(0, 16);
  s.j1939_ranges = false;
  const std::array<std::uint8_t, 2> p{0xFF, 0xFF};
  EXPECT_DOUBLE_EQ(*decode(s, p).get(), 65535.0);
}

TEST(Signal, SignedSignalSignExtends) {
  SignalDef s = def(0, 12, 0.5);
  s.is_signed = true;
  std::array<std::uint8_t, 2> p{};
  encode(s, -3.0, p);
  EXPECT_DOUBLE_EQ(*decode(s, p).get(), -3.0);
}

}  // namespace
}  // namespace roadload::j1939
