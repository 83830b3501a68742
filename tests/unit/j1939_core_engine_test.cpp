// The core DBC's engine, driveline and speed signals decoded from real and hand-built frames (CSS
// Electronics traces in tests/data/traces, MIT; the line each one was taken from is named next to it).
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

TEST(CoreDbc, EngineSpeedFromRealIdleFrame) {
  // css-truck-idle.log line 6: 0CF00400#607D844A1400F084
  const auto p = bytes("607D844A1400F084");
  // SPN 190, bytes 4-5 little endian: 0x4A + 0x14 * 256 = 0x144A = 5194; 5194 * 0.125 = 649.25 rpm
  EXPECT_DOUBLE_EQ(value(190, kEEC1, p), 649.25);
  // SPN 513, byte 3: 0x84 = 132; 132 - 125 = 7 %
  EXPECT_DOUBLE_EQ(value(513, kEEC1, p), 7.0);
  // SPN 512, byte 2: 0x7D = 125 -> 0 %
  EXPECT_DOUBLE_EQ(value(512, kEEC1, p), 0.0);
  // SPN 899, byte 1 bits 1-4: 0x60 & 0x0F = 0 (low idle governor / no request)
  EXPECT_DOUBLE_EQ(value(899, kEEC1, p), 0.0);
  // SPN 4154, byte 1 bits 5-8: 0x60 >> 4 = 6; 6 * 0.125 = 0.75 %
  EXPECT_DOUBLE_EQ(value(4154, kEEC1, p), 0.75);
  // SPN 1483, byte 6: controlling device 0x00
  EXPECT_DOUBLE_EQ(value(1483, kEEC1, p), 0.0);
  // SPN 2432, byte 8: 0x84 -> 7 %
  EXPECT_DOUBLE_EQ(value(2432, kEEC1, p), 7.0);
}

TEST(CoreDbc, EngineSpeedLargestValidValueIs8031875Rpm) {
  // 0xFAFF = 64255; 64255 * 0.125 = 8031.875 rpm
  EXPECT_DOUBLE_EQ(value(190, kEEC1, bytes("FFFFFFFFFAFFFFFF")), 8031.875);
  // 0xFB00..0xFBFF parameter specific, 0xFC00..0xFDFF reserved, 0xFExx error, 0xFFxx not available
  EXPECT_EQ(spn(190, kEEC1, bytes("FFFFFF00FBFFFFFF")).state, SignalState::parameter_specific);
  EXPECT_EQ(spn(190, kEEC1, bytes("FFFFFF00FCFFFFFF")).state, SignalState::reserved);
  EXPECT_EQ(spn(190, kEEC1, bytes("FFFFFF00FEFFFFFF")).state, SignalState::error);
  EXPECT_EQ(spn(190, kEEC1, bytes("FFFFFF12FEFFFFFF")).state, SignalState::error);
  EXPECT_EQ(spn(190, kEEC1, bytes("FFFFFFFFFFFFFFFF")).state, SignalState::not_available);
  EXPECT_FALSE(spn(190, kEEC1, bytes("FFFFFFFFFFFFFFFF")).get().has_value());
  EXPECT_FALSE(spn(190, kEEC1, bytes("FFFFFF00FEFFFFFF")).get().has_value());
}

TEST(CoreDbc, ActualEngineTorqueUsesMinus125Offset) {
  // byte 3 raw 0 -> -125 %, 125 -> 0 %, 250 (0xFA) -> +125 %
  EXPECT_DOUBLE_EQ(value(513, kEEC1, bytes("FFFF00FFFFFFFFFF")), -125.0);
  EXPECT_DOUBLE_EQ(value(513, kEEC1, bytes("FFFF7DFFFFFFFFFF")), 0.0);
  EXPECT_DOUBLE_EQ(value(513, kEEC1, bytes("FFFFFAFFFFFFFFFF")), 125.0);
  // 0xFE error and 0xFF not available decode to no value, never to 129 or 130 %
  const SignalReading err = spn(513, kEEC1, bytes("FFFFFEFFFFFFFFFF"));
  EXPECT_EQ(err.state, SignalState::error);
  EXPECT_EQ(err.raw, 0xFEu);
  EXPECT_FALSE(err.get().has_value());
  EXPECT_EQ(spn(513, kEEC1, bytes("FFFFFFFFFFFFFFFF")).state, SignalState::not_available);
}

TEST(CoreDbc, AcceleratorPedalAndLoadFromRealEec2Frame) {
  // css-truck-idle.log line 12: 0CF00300#DD000CFFFF0C607D
  const auto p = bytes("DD000CFFFF0C607D");
  // SPN 558, byte 1 bits 1-2: 0xDD & 3 = 01 -> pedal in low idle
  EXPECT_DOUBLE_EQ(value(558, kEEC2, p), 1.0);
  // SPN 91, byte 2: 0 * 0.4 = 0 %
  EXPECT_DOUBLE_EQ(value(91, kEEC2, p), 0.0);
  // SPN 92, byte 3: 0x0C = 12 %
  EXPECT_DOUBLE_EQ(value(92, kEEC2, p), 12.0);
  // SPN 974 remote pedal, byte 4 = 0xFF: not available
  EXPECT_EQ(spn(974, kEEC2, p).state, SignalState::not_available);
}

TEST(CoreDbc, NominalFrictionTorqueFromRealEec3Frame) {
  // css-truck-idle.log line 2: 18FEDF00#82FFFFFF7D090201
  const auto p = bytes("82FFFFFF7D090201");
  // SPN 514, byte 1: 0x82 = 130 -> 130 - 125 = 5 % of reference torque
  EXPECT_DOUBLE_EQ(value(514, kEEC3, p), 5.0);
  // SPN 515, bytes 2-3 0xFFFF: not available
  EXPECT_EQ(spn(515, kEEC3, p).state, SignalState::not_available);
  // SPN 2978, byte 5: 0x7D -> 0 %
  EXPECT_DOUBLE_EQ(value(2978, kEEC3, p), 0.0);
  // SPN 3236, bytes 6-7: 0x0209 = 521; 521 * 0.2 = 104.2 kg/h
  EXPECT_NEAR(value(3236, kEEC3, p), 104.2, kExact);
  // With EC1's 2386 Nm (see below) the friction torque is 5 % * 2386 Nm = 119.3 Nm.
}

// EC1 of the idle truck, reassembled by hand from the BAM in css-truck-idle.log:
//   line 850: 1CECFF00#20270006FFE3FE00  BAM (0x20), 0x0027 = 39 bytes, 6 packets, PGN E3 FE 00 = 0xFEE3 = 65251
//   line 873: 1CEBFF00#015014BD32418C20  seq 1 -> bytes  1- 7: 50 14 BD 32 41 8C 20
//   line 894: 1CEBFF00#021CDFC02BE15834  seq 2 -> bytes  8-14: 1C DF C0 2B E1 58 34
//   line 920: 1CEBFF00#03D3A041FFFF5209  seq 3 -> bytes 15-21: D3 A0 41 FF FF 52 09
//   line 945: 1CEBFF00#04E0470341D07DE1  seq 4 -> bytes 22-28: E0 47 03 41 D0 7D E1
//   line 968: 1CEBFF00#053041BC03FFFF80  seq 5 -> bytes 29-35: 30 41 BC 03 FF FF 80
//   line 989: 1CEBFF00#06E0FFFFFFFFFFFF  seq 6 -> bytes 36-39: E0 FF FF FF (the rest is padding)
std::vector<std::uint8_t> idle_truck_ec1() {
  const std::vector<std::string> packets = {"015014BD32418C20", "021CDFC02BE15834", "03D3A041FFFF5209",
                                            "04E0470341D07DE1", "053041BC03FFFF80", "06E0FFFFFFFFFFFF"};
  std::vector<std::uint8_t> payload;
  for (std::size_t i = 0; i < packets.size(); ++i) {
    const auto frame = bytes(packets[i]);
    EXPECT_EQ(static_cast<std::size_t>(frame[0]), i + 1) << "sequence number";
    payload.insert(payload.end(), frame.begin() + 1, frame.end());
  }
  const auto announce = bytes("20270006FFE3FE00");
  const std::size_t size = static_cast<std::size_t>(announce[1] | (announce[2] << 8));
  EXPECT_EQ(size, 39u);
  EXPECT_EQ(static_cast<std::uint32_t>(announce[5] | (announce[6] << 8) | (announce[7] << 16)), kEC1);
  payload.resize(size);
  return payload;
}

TEST(CoreDbc, EngineReferenceTorqueFromRealEc1Bam) {
  const auto p = idle_truck_ec1();
  ASSERT_EQ(p.size(), 39u);
  // SPN 544, bytes 20-21: 0x52 + 0x09 * 256 = 0x0952 = 2386 Nm
  EXPECT_DOUBLE_EQ(value(544, kEC1, p), 2386.0);
}

TEST(CoreDbc, EngineMapPointsFromRealEc1Bam) {
  const auto p = idle_truck_ec1();
  // SPN 188, bytes 1-2: 0x1450 = 5200 * 0.125 = 650 rpm (low idle, matches EEC1's ~649 rpm)
  EXPECT_DOUBLE_EQ(value(188, kEC1, p), 650.0);
  // SPN 539, byte 3: 0xBD = 189 - 125 = 64 %
  EXPECT_DOUBLE_EQ(value(539, kEC1, p), 64.0);
  // SPN 529, bytes 7-8: 0x1C20 = 7200 * 0.125 = 900 rpm; SPN 541, byte 9: 0xDF = 223 - 125 = 98 %
  EXPECT_DOUBLE_EQ(value(529, kEC1, p), 900.0);
  EXPECT_DOUBLE_EQ(value(541, kEC1, p), 98.0);
  // SPN 530, bytes 10-11: 0x2BC0 = 11200 * 0.125 = 1400 rpm; SPN 542, byte 12: 0xE1 = 100 %
  EXPECT_DOUBLE_EQ(value(530, kEC1, p), 1400.0);
  EXPECT_DOUBLE_EQ(value(542, kEC1, p), 100.0);
  // SPN 532, bytes 16-17: 0x41A0 = 16800 * 0.125 = 2100 rpm (high idle)
  EXPECT_DOUBLE_EQ(value(532, kEC1, p), 2100.0);
  // SPN 545 gain, bytes 18-19 0xFFFF: not available
  EXPECT_EQ(spn(545, kEC1, p).state, SignalState::not_available);
  // SPN 533, bytes 22-23: 0x47E0 = 18400 * 0.125 = 2300 rpm; SPN 534, byte 24: 3 * 0.1 = 0.3 s
  EXPECT_DOUBLE_EQ(value(533, kEC1, p), 2300.0);
  EXPECT_NEAR(value(534, kEC1, p), 0.3, kExact);
  // SPN 535/536, bytes 25/26: 0x41 = 65 * 10 = 650 rpm, 0xD0 = 208 * 10 = 2080 rpm
  EXPECT_DOUBLE_EQ(value(535, kEC1, p), 650.0);
  EXPECT_DOUBLE_EQ(value(536, kEC1, p), 2080.0);
  // SPN 537/538, bytes 27/28: 0x7D -> 0 %, 0xE1 -> 100 %
  EXPECT_DOUBLE_EQ(value(537, kEC1, p), 0.0);
  EXPECT_DOUBLE_EQ(value(538, kEC1, p), 100.0);
  // SPN 1794, bytes 31-32: 0x03BC = 956 * 0.004 = 3.824 kg m2
  EXPECT_NEAR(value(1794, kEC1, p), 3.824, kExact);
  // SPN 1846, bytes 33-34 0xFFFF: no default torque limit
  EXPECT_EQ(spn(1846, kEC1, p).state, SignalState::not_available);
}

// ---------------------------------------------------------------------------------------------
// CCVS1: vehicle speed and switches

TEST(CoreDbc, WheelBasedVehicleSpeedIsOneTwoHundredFiftySixthKmh) {
  // bytes 2-3 = 00 50 -> 0x5000 = 20480; 20480 / 256 = 80 km/h
  EXPECT_DOUBLE_EQ(value(84, kCCVS1, bytes("FF0050FFFFFFFFFF")), 80.0);
  // 0x2180 = 8576 / 256 = 33.5 km/h
  EXPECT_DOUBLE_EQ(value(84, kCCVS1, bytes("FF8021FFFFFFFFFF")), 33.5);
  // 0xFAFF = 64255 / 256 = 250.99609375 km/h, the largest valid speed
  EXPECT_DOUBLE_EQ(value(84, kCCVS1, bytes("FFFFFAFFFFFFFFFF")), 250.99609375);
  EXPECT_EQ(spn(84, kCCVS1, bytes("FFFFFFFFFFFFFFFF")).state, SignalState::not_available);
  EXPECT_EQ(spn(84, kCCVS1, bytes("FF00FEFFFFFFFFFF")).state, SignalState::error);
}

TEST(CoreDbc, VehicleStandingWithParkingBrakeInRealCcvs1Frame) {
  // css-truck-idle.log line 4: 0CFEF100#F7000004000000FF
  const auto p = bytes("F7000004000000FF");
  // SPN 84, bytes 2-3: 0 -> 0 km/h
  EXPECT_DOUBLE_EQ(value(84, kCCVS1, p), 0.0);
  // SPN 70, byte 1 bits 3-4: 0xF7 = 1111 0111 -> (0xF7 >> 2) & 3 = 01 = parking brake set
  EXPECT_DOUBLE_EQ(value(70, kCCVS1, p), 1.0);
  // byte 4 = 0x04 = 0000 0100: SPN 595 bits 1-2 = 00 (off), SPN 596 bits 3-4 = 01 (enabled),
  // SPN 597 bits 5-6 = 00 (brake released), SPN 598 bits 7-8 = 00 (clutch released)
  EXPECT_DOUBLE_EQ(value(595, kCCVS1, p), 0.0);
  EXPECT_DOUBLE_EQ(value(596, kCCVS1, p), 1.0);
  EXPECT_DOUBLE_EQ(value(597, kCCVS1, p), 0.0);
  EXPECT_DOUBLE_EQ(value(598, kCCVS1, p), 0.0);
}

TEST(CoreDbc, BrakeSwitchTwoBitStates) {
  // SPN 597 sits in byte 4 bits 5-6 (DBC start bit 29): 0x00 released, 0x10 pressed, 0x20 error, 0x30 n/a
  EXPECT_DOUBLE_EQ(value(597, kCCVS1, bytes("FFFFFF00FFFFFFFF")), 0.0);
  EXPECT_DOUBLE_EQ(value(597, kCCVS1, bytes("FFFFFF10FFFFFFFF")), 1.0);
  EXPECT_EQ(spn(597, kCCVS1, bytes("FFFFFF20FFFFFFFF")).state, SignalState::error);
  EXPECT_EQ(spn(597, kCCVS1, bytes("FFFFFF30FFFFFFFF")).state, SignalState::not_available);
  EXPECT_FALSE(spn(597, kCCVS1, bytes("FFFFFF30FFFFFFFF")).get().has_value());
  // The neighbouring bits do not leak in: 0xCF = 11 00 11 11 -> bits 5-6 = 00
  EXPECT_DOUBLE_EQ(value(597, kCCVS1, bytes("FFFFFFCFFFFFFFFF")), 0.0);
  // Cruise control active (byte 4 bits 1-2): 0xFD = ...01 -> on
  EXPECT_DOUBLE_EQ(value(595, kCCVS1, bytes("FFFFFFFDFFFFFFFF")), 1.0);
}

// ---------------------------------------------------------------------------------------------
// LFE1, ETC1/ETC2, AMB, ET1

TEST(CoreDbc, FuelRateFromRealLfe1Frame) {
  // css-truck-idle.log line 16: 18FEF200#37000000870100FF
  const auto p = bytes("37000000870100FF");
  // SPN 183, bytes 1-2: 0x0037 = 55; 55 * 0.05 = 2.75 L/h
  EXPECT_NEAR(value(183, kLFE1, p), 2.75, kExact);
  // SPN 184, bytes 3-4: 0 km/L (standing)
  EXPECT_DOUBLE_EQ(value(184, kLFE1, p), 0.0);
  // SPN 185, bytes 5-6: 0x0187 = 391; 391 / 512 = 0.763671875 km/L
  EXPECT_DOUBLE_EQ(value(185, kLFE1, p), 0.763671875);
  // Largest fuel rate 0xFAFF * 0.05 = 3212.75 L/h
  EXPECT_NEAR(value(183, kLFE1, bytes("FFFAFFFFFFFFFFFF")), 3212.75, 1e-6);
}

TEST(CoreDbc, CurrentGearAndGearRatio) {
  // ETC2 built by hand: selected gear 0x89 = 137 -> 12, ratio 0x03E8 = 1000 * 0.001 = 1.000,
  // current gear 0x87 = 135 -> 10
  const auto p = bytes("89E80387FFFFFFFF");
  EXPECT_DOUBLE_EQ(value(524, kETC2, p), 12.0);
  EXPECT_NEAR(value(526, kETC2, p), 1.0, kExact);
  EXPECT_DOUBLE_EQ(value(523, kETC2, p), 10.0);
  // ratio 0x3138 = 12600 -> 12.6; reverse gear 0x7C = 124 -> -1
  EXPECT_NEAR(value(526, kETC2, bytes("FF38317CFFFFFFFF")), 12.6, kExact);
  EXPECT_DOUBLE_EQ(value(523, kETC2, bytes("FF38317CFFFFFFFF")), -1.0);
  // 251 (0xFB) is "park": parameter specific, not gear 126
  const SignalReading park = spn(523, kETC2, bytes("FFFFFFFBFFFFFFFF"));
  EXPECT_EQ(park.state, SignalState::parameter_specific);
  EXPECT_EQ(park.raw, 251u);
}

TEST(CoreDbc, NeutralGearFromRealKeyOnEtc2Frame) {
  // css-key-on-mixed-11bit.log, 18F00503#FFFFFF7DFFFFFFFF (transmission, SA 0x03)
  const auto p = bytes("FFFFFF7DFFFFFFFF");
  EXPECT_EQ(spn(524, kETC2, p).state, SignalState::not_available);
  EXPECT_EQ(spn(526, kETC2, p).state, SignalState::not_available);
  // byte 4 = 0x7D = 125 -> 0 = neutral
  EXPECT_DOUBLE_EQ(value(523, kETC2, p), 0.0);
}

TEST(CoreDbc, ShaftSpeedsFromHandBuiltEtc1Frame) {
  // output shaft bytes 2-3 = 0x2EE0 = 12000 * 0.125 = 1500 rpm; clutch slip byte 4 = 0x05 * 0.4 = 2 %;
  // input shaft bytes 6-7 = 0x3E80 = 16000 * 0.125 = 2000 rpm
  const auto p = bytes("FFE02E05FF803EFF");
  EXPECT_DOUBLE_EQ(value(191, kETC1, p), 1500.0);
  EXPECT_NEAR(value(522, kETC1, p), 2.0, kExact);
  EXPECT_DOUBLE_EQ(value(161, kETC1, p), 2000.0);
}

}  // namespace
