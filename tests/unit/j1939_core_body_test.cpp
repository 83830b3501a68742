// The core DBC's ambient, distance, position, fan, brake and diagnostic signals decoded from real
// and hand-built frames (CSS Electronics traces in tests/data/traces, MIT).
#include <gtest/gtest.h>

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "j1939_core_dbc.hpp"
#include "roadload/j1939/id.hpp"
#include "roadload/parse_error.hpp"

namespace {

using namespace roadload::j1939::core_dbc_test;

TEST(CoreDbc, AmbientTemperatureAndBarometricPressureFromRealAmbFrame) {
  // css-truck-idle.log line 320: 18FEF500#C5FFFFC923FFFFFF
  const auto p = bytes("C5FFFFC923FFFFFF");
  // SPN 108, byte 1: 0xC5 = 197; 197 * 0.5 = 98.5 kPa
  EXPECT_DOUBLE_EQ(value(108, kAMB, p), 98.5);
  // SPN 171, bytes 4-5: 0x23C9 = 9161; 9161 * 0.03125 - 273 = 286.28125 - 273 = 13.28125 C
  EXPECT_DOUBLE_EQ(value(171, kAMB, p), 13.28125);
  // SPN 170 cab interior, bytes 2-3 0xFFFF, and SPN 79 road surface, bytes 7-8: not available
  EXPECT_EQ(spn(170, kAMB, p).state, SignalState::not_available);
  EXPECT_EQ(spn(79, kAMB, p).state, SignalState::not_available);
  // Temperature range ends: raw 0 -> -273 C, 0xFAFF -> 64255 * 0.03125 - 273 = 1734.96875 C
  EXPECT_DOUBLE_EQ(value(171, kAMB, bytes("FFFFFF0000FFFFFF")), -273.0);
  EXPECT_DOUBLE_EQ(value(171, kAMB, bytes("FFFFFFFFFAFFFFFF")), 1734.96875);
}

TEST(CoreDbc, EngineTemperaturesFromRealEt1Frame) {
  // css-truck-idle.log line 135: 18FEEE00#6F3F392BFFFFFFFF
  const auto p = bytes("6F3F392BFFFFFFFF");
  // SPN 110 byte 1: 0x6F = 111 - 40 = 71 C; SPN 174 byte 2: 0x3F = 63 - 40 = 23 C
  EXPECT_DOUBLE_EQ(value(110, kET1, p), 71.0);
  EXPECT_DOUBLE_EQ(value(174, kET1, p), 23.0);
  // SPN 175 bytes 3-4: 0x2B39 = 11065; 11065 * 0.03125 - 273 = 345.78125 - 273 = 72.78125 C
  EXPECT_DOUBLE_EQ(value(175, kET1, p), 72.78125);
  EXPECT_EQ(spn(176, kET1, p).state, SignalState::not_available);
}

// ---------------------------------------------------------------------------------------------
// Distance, position, hours, fuel

TEST(CoreDbc, TotalVehicleDistanceFromRealVdFrame) {
  // css-truck-idle.log line 23: 18FEE000#FFFFFFFF47B00100
  const auto p = bytes("FFFFFFFF47B00100");
  EXPECT_EQ(spn(244, kVD, p).state, SignalState::not_available);
  // SPN 245 bytes 5-8: 0x0001B047 = 110663; 110663 * 0.125 = 13832.875 km
  EXPECT_DOUBLE_EQ(value(245, kVD, p), 13832.875);
}

TEST(CoreDbc, HighResolutionDistanceFromRealVdhrFrame) {
  // css-key-on-mixed-11bit.log, 18FEC117#E8F4E40141B11600
  const auto p = bytes("E8F4E40141B11600");
  // SPN 917 bytes 1-4: 0x01E4F4E8 = 31782120; * 5 m = 158910600 m
  EXPECT_DOUBLE_EQ(value(917, kVDHR, p), 158910600.0);
  // SPN 918 bytes 5-8: 0x0016B141 = 1487169; * 5 m = 7435845 m
  EXPECT_DOUBLE_EQ(value(918, kVDHR, p), 7435845.0);
}

TEST(CoreDbc, LatitudeAndLongitudeWithMinus210Offset) {
  // 48.1234567 N: (48.1234567 + 210) / 1e-7 = 2581234567 = 0x99DA8387 -> bytes 87 83 DA 99
  // 11.5 E:       (11.5 + 210) / 1e-7 = 2215000000 = 0x840637C0 -> bytes C0 37 06 84
  const auto p = bytes("8783DA99C0370684");
  EXPECT_NEAR(value(584, kVP1, p), 48.1234567, 1e-7);
  EXPECT_NEAR(value(585, kVP1, p), 11.5, 1e-7);
  // raw 0 -> -210 deg (south/west end of the range)
  EXPECT_DOUBLE_EQ(value(584, kVP1, bytes("00000000FFFFFFFF")), -210.0);
  EXPECT_EQ(spn(585, kVP1, bytes("00000000FFFFFFFF")).state, SignalState::not_available);
}

TEST(CoreDbc, EngineHoursFromRealHoursFrame) {
  // css-fcbf0606-tp-sample.log line 14: 18FEE500#20110000FFFFFFFF
  const auto p = bytes("20110000FFFFFFFF");
  // SPN 247 bytes 1-4: 0x00001120 = 4384; 4384 * 0.05 = 219.2 h
  EXPECT_NEAR(value(247, kHOURS, p), 219.2, 1e-6);
  EXPECT_EQ(spn(249, kHOURS, p).state, SignalState::not_available);
}

TEST(CoreDbc, TotalFuelUsedIsHalfLitrePerBit) {
  // SPN 250 bytes 5-8: 0x00030D40 = 200000; * 0.5 = 100000 L
  EXPECT_DOUBLE_EQ(value(250, kLFC, bytes("FFFFFFFF400D0300")), 100000.0);
}

// ---------------------------------------------------------------------------------------------
// FD1, EBC1, EBC2, ERC1

TEST(CoreDbc, FanDriveStateAndSpeeds) {
  // byte 1 0x7D = 125 * 0.4 = 50 %; byte 2 bits 1-4 = 4 (excessive coolant temperature);
  // bytes 3-4 0x1F40 = 8000 * 0.125 = 1000 rpm
  const auto p = bytes("7DF4401FFFFFFFFF");
  EXPECT_NEAR(value(975, kFD1, p), 50.0, kExact);
  EXPECT_DOUBLE_EQ(value(977, kFD1, p), 4.0);
  EXPECT_DOUBLE_EQ(value(1639, kFD1, p), 1000.0);
  // fan drive state 1111 not available, 1110 error for a 4-bit field
  EXPECT_EQ(spn(977, kFD1, bytes("FFFFFFFFFFFFFFFF")).state, SignalState::not_available);
}

TEST(CoreDbc, BrakeStatusFromRealEbc1Frame) {
  // css-key-on-mixed-11bit.log, 18F0010B#4F6CC3FFFF010BF3 (brakes, SA 0x0B)
  const auto p = bytes("4F6CC3FFFF010BF3");
  // byte 1 = 0x4F = 01 00 11 11: ASR engine 11 (n/a), ASR brake 11 (n/a), ABS active 00, EBS brake switch 01
  EXPECT_EQ(spn(561, kEBC1, p).state, SignalState::not_available);
  EXPECT_DOUBLE_EQ(value(563, kEBC1, p), 0.0);
  EXPECT_DOUBLE_EQ(value(1121, kEBC1, p), 1.0);
  // SPN 521 byte 2: 0x6C = 108 * 0.4 = 43.2 %
  EXPECT_NEAR(value(521, kEBC1, p), 43.2, kExact);
  // SPN 1243 byte 6 bits 1-2: 0x01 -> fully operational; SPN 1481 byte 7: 0x0B, the sender itself
  EXPECT_DOUBLE_EQ(value(1243, kEBC1, p), 1.0);
  EXPECT_DOUBLE_EQ(value(1481, kEBC1, p), 11.0);
}

TEST(CoreDbc, WheelSpeedsRelativeToAxleSpeed) {
  // bytes 1-2 0x5000 = 80 km/h; relative speeds: 0x7D = 125 * 0.0625 - 7.8125 = 0,
  // 0x80 = 128 * 0.0625 - 7.8125 = 0.1875, 0x00 = -7.8125, 0xFA = 250 * 0.0625 - 7.8125 = 7.8125
  const auto p = bytes("00507D8000FAFFFF");
  EXPECT_DOUBLE_EQ(value(904, kEBC2, p), 80.0);
  EXPECT_DOUBLE_EQ(value(905, kEBC2, p), 0.0);
  EXPECT_DOUBLE_EQ(value(906, kEBC2, p), 0.1875);
  EXPECT_DOUBLE_EQ(value(907, kEBC2, p), -7.8125);
  EXPECT_DOUBLE_EQ(value(908, kEBC2, p), 7.8125);
  EXPECT_EQ(spn(909, kEBC2, p).state, SignalState::not_available);
}

TEST(CoreDbc, RetarderTorqueIsNegativePercent) {
  // ERC1 byte 2: 0x64 = 100 - 125 = -25 % of retarder reference torque
  EXPECT_DOUBLE_EQ(value(520, kERC1, bytes("FF64FFFFFFFFFFFF")), -25.0);
}

// ---------------------------------------------------------------------------------------------
// DM1

// DM1 of the idle truck, from the BAM in css-truck-idle.log:
//   line 178: 1CECFF00#20120003FFCAFE00  BAM, 0x12 = 18 bytes, 3 packets, PGN 0xFECA = 65226
//   line 204: 1CEBFF00#0143FFD403097E90  -> 43 FF D4 03 09 7E 90
//   line 229: 1CEBFF00#020C140261020901  -> 0C 14 02 61 02 09 01
//   line 252: 1CEBFF00#0361020C03FFFFFF  -> 61 02 0C 03 (then padding)
const std::vector<std::uint8_t> kIdleDm1 = bytes("43FFD403097E900C14026102090161020C03");

TEST(CoreDbc, Dm1LampsFromRealBam) {
  ASSERT_EQ(kIdleDm1.size(), 18u);
  // byte 1 = 0x43 = 01 00 00 11: MIL (bits 7-8) 01 on, red stop 00, amber 00, protect 11 n/a
  EXPECT_DOUBLE_EQ(value(1213, kDM1, kIdleDm1), 1.0);
  EXPECT_DOUBLE_EQ(value(623, kDM1, kIdleDm1), 0.0);
  EXPECT_DOUBLE_EQ(value(624, kDM1, kIdleDm1), 0.0);
  EXPECT_EQ(spn(987, kDM1, kIdleDm1).state, SignalState::not_available);
  // byte 2 = 0xFF: no flash information
  EXPECT_EQ(spn(3038, kDM1, kIdleDm1).state, SignalState::not_available);
}

TEST(CoreDbc, Dm1FirstDtcSpnAndFmiFromRealBam) {
  // DTC 1 = D4 03 09 7E: SPN low 16 bits = 0x03D4 = 980; byte 5 = 0x09 = 000 01001 ->
  // SPN bits 17-19 = 000, FMI = 9 (abnormal update rate); SPN = 980 + 0 * 65536 = 980
  const MessageDef* dm1 = core().find(kDM1);
  ASSERT_NE(dm1, nullptr);
  const SignalDef* low = nullptr;
  const SignalDef* high = nullptr;
  for (const SignalDef& s : dm1->signals) {
    if (s.name == "Dtc1SpnLow16") low = &s;
    if (s.name == "Dtc1SpnHigh3") high = &s;
  }
  ASSERT_NE(low, nullptr);
  ASSERT_NE(high, nullptr);
  const auto spn_low = roadload::j1939::extract_raw(*low, kIdleDm1);
  const auto spn_high = roadload::j1939::extract_raw(*high, kIdleDm1);
  EXPECT_EQ(spn_low + (spn_high << 16), 980u);
  EXPECT_DOUBLE_EQ(value(1215, kDM1, kIdleDm1), 9.0);
  // byte 6 = 0x7E: conversion method (bit 8) 0
  EXPECT_DOUBLE_EQ(value(1706, kDM1, kIdleDm1), 0.0);
  // An SPN above 65535 uses the 3 high bits: SPN 520192 = 0x7F000 -> low 0xF000, high 7;
  // byte 5 = 111 00011 (FMI 3) = 0xE3
  const auto big = bytes(
      "0000"
      "00F0E301");
  EXPECT_EQ(roadload::j1939::extract_raw(*low, big) + (roadload::j1939::extract_raw(*high, big) << 16), 520192u);
  EXPECT_DOUBLE_EQ(value(1215, kDM1, big), 3.0);
}

TEST(CoreDbc, Dm1OccurrenceCount126IsAValidCount) {
  // J1939-73: the 7-bit occurrence count is valid up to 126; only 127 means "not available".
  // The first DTC of the idle truck has byte 6 = 0x7E: OC = 126.
  const SignalReading oc = spn(1216, kDM1, kIdleDm1);
  EXPECT_EQ(oc.raw, 126u);
  EXPECT_EQ(oc.state, SignalState::valid);
  // The third DTC (61 02 09 01) counts 1; shift it into the first DTC's place to decode it.
  const auto third = bytes(
      "43FF"
      "61020901");
  EXPECT_DOUBLE_EQ(value(1216, kDM1, third), 1.0);
  EXPECT_EQ(spn(1216, kDM1,
                bytes("43FF"
                      "0000007F"))
                .state,
            SignalState::not_available);
}

// ---------------------------------------------------------------------------------------------
// Users' DBC files

}  // namespace
