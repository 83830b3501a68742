// The built-in J1939 definition set (config/j1939-core.dbc) loaded through the codec and checked
// against frames decoded by hand. Real frames come from the CSS Electronics traces in
// tests/data/traces (MIT); the line each one was taken from is named next to it.
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "roadload/j1939/database.hpp"
#include "roadload/j1939/dbc.hpp"
#include "roadload/j1939/id.hpp"
#include "roadload/j1939/signal.hpp"
#include "roadload/parse_error.hpp"

namespace {

using roadload::j1939::ByteOrder;
using roadload::j1939::Database;
using roadload::j1939::MessageDef;
using roadload::j1939::SignalDef;
using roadload::j1939::SignalReading;
using roadload::j1939::SignalState;

constexpr double kExact = 1e-9;  // for factors such as 0.05 or 0.4 that binary floating point rounds

const std::string kCorePath = std::string(ROADLOAD_CONFIG_DIR "/j1939-core.dbc");

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The database is built once; every test only reads it.
const Database& core() {
  static const Database db = [] {
    Database d;
    const std::string text = read_file(kCorePath);
    EXPECT_FALSE(text.empty()) << "cannot read " << kCorePath;
    const auto err = roadload::j1939::load_dbc(d, text, kCorePath);
    EXPECT_FALSE(err.has_value()) << (err ? err->to_string() : std::string());
    return d;
  }();
  return db;
}

// "607D844A1400F084" -> {0x60, 0x7D, ...}, the data part of a candump line.
std::vector<std::uint8_t> bytes(const std::string& hex) {
  std::vector<std::uint8_t> out;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2) {
    out.push_back(static_cast<std::uint8_t>(std::stoul(hex.substr(i, 2), nullptr, 16)));
  }
  return out;
}

// Looks the SPN up, checks it lives in the expected PGN and decodes it from `payload`.
SignalReading spn(std::uint32_t number, roadload::j1939::Pgn expected_pgn, const std::vector<std::uint8_t>& payload) {
  const MessageDef* msg = nullptr;
  const SignalDef* sig = core().find_spn(number, &msg);
  EXPECT_NE(sig, nullptr) << "SPN " << number << " is not in the core DBC";
  if (sig == nullptr) return SignalReading{};
  EXPECT_NE(msg, nullptr);
  if (msg != nullptr) {
    EXPECT_EQ(msg->pgn, expected_pgn) << "SPN " << number;
  }
  return roadload::j1939::decode(*sig, payload);
}

double value(std::uint32_t number, roadload::j1939::Pgn pgn, const std::vector<std::uint8_t>& payload) {
  const SignalReading r = spn(number, pgn, payload);
  EXPECT_EQ(r.state, SignalState::valid) << "SPN " << number << " raw " << r.raw;
  return r.get().value_or(-99999.0);
}

constexpr roadload::j1939::Pgn kEEC1 = 61444, kEEC2 = 61443, kEEC3 = 65247, kEC1 = 65251, kCCVS1 = 65265,
                               kLFE1 = 65266, kETC1 = 61442, kETC2 = 61445, kAMB = 65269, kVD = 65248,
                               kVDHR = 65217, kVP1 = 65267, kFD1 = 65213, kEBC1 = 61441, kDM1 = 65226,
                               kERC1 = 61440, kEBC2 = 65215, kHOURS = 65253, kLFC = 65257, kET1 = 65262;

// ---------------------------------------------------------------------------------------------
// The file itself

TEST(CoreDbc, LoadsAndDefinesEveryRequiredPgn) {
  const Database& db = core();
  const std::vector<std::pair<roadload::j1939::Pgn, std::string>> required = {
      {kEEC1, "EEC1"},   {kEEC2, "EEC2"}, {kEEC3, "EEC3"}, {kEC1, "EC1"},     {kCCVS1, "CCVS1"},
      {kLFE1, "LFE1"},   {kETC1, "ETC1"}, {kETC2, "ETC2"}, {kAMB, "AMB"},     {kVD, "VD"},
      {kVDHR, "VDHR"},   {kVP1, "VP1"},   {kFD1, "FD1"},   {kEBC1, "EBC1"},   {kDM1, "DM1"},
      {kERC1, "ERC1"},   {kEBC2, "EBC2"}, {kHOURS, "HOURS"}, {kLFC, "LFC"}, {kET1, "ET1"}};
  for (const auto& [pgn, name] : required) {
    const MessageDef* m = db.find(pgn);
    ASSERT_NE(m, nullptr) << "PGN " << pgn;
    EXPECT_EQ(m->name, name);
    EXPECT_EQ(m->pgn, pgn);
  }
  EXPECT_GE(db.size(), required.size());
}

TEST(CoreDbc, MessageLengthsAndCycleTimesFollowTheStandard) {
  const Database& db = core();
  EXPECT_EQ(db.find(kEC1)->length, 40u);  // J1939DA 2018: 40 bytes, sent by BAM; older engines send 39
  EXPECT_EQ(db.find(kDM1)->length, 8u);   // a single-DTC DM1 fits one frame
  EXPECT_EQ(db.find(kEEC1)->length, 8u);
  EXPECT_EQ(db.find(kEEC1)->cycle_time_ms, 20u);  // engine-speed dependent, 20 ms nominal
  EXPECT_EQ(db.find(kEEC2)->cycle_time_ms, 50u);
  EXPECT_EQ(db.find(kETC1)->cycle_time_ms, 10u);
  EXPECT_EQ(db.find(kCCVS1)->cycle_time_ms, 100u);
  EXPECT_EQ(db.find(kLFE1)->cycle_time_ms, 100u);
  EXPECT_EQ(db.find(kAMB)->cycle_time_ms, 1000u);
  EXPECT_EQ(db.find(kEC1)->cycle_time_ms, 5000u);
  EXPECT_EQ(db.find(kHOURS)->cycle_time_ms, 0u);  // on request: no GenMsgCycleTime
}

TEST(CoreDbc, EverySignalHasAnSpnIsIntelUnsignedAndFitsWithoutOverlap) {
  for (const MessageDef& m : core().messages()) {
    std::set<unsigned> used_bits;
    for (const SignalDef& s : m.signals) {
      SCOPED_TRACE(m.name + "." + s.name);
      EXPECT_NE(s.spn, 0u);
      EXPECT_EQ(s.order, ByteOrder::little_endian);
      EXPECT_FALSE(s.is_signed);
      EXPECT_LE(roadload::j1939::bytes_needed(s), m.length);
      EXPECT_LT(s.minimum, s.maximum);
      for (unsigned b = s.start_bit; b < s.start_bit + s.length; ++b) {
        EXPECT_TRUE(used_bits.insert(b).second) << "bit " << b << " used twice";
      }
      // The physical range must cover the largest valid raw value (0xFA.., 0xFAFF, 0xFAFFFFFF).
      // SPN 4154 is narrower than the generic bit-field rule: J1939 defines only 0000b-0111b
      // (0 to 0.875 %), so its range stops at 0.875 on purpose.
      if (s.spn == 4154) continue;
      const double top = static_cast<double>(roadload::j1939::max_valid_raw(s)) * s.factor + s.offset;
      EXPECT_LE(top, s.maximum + 1e-6);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Identifiers: PDU1 / PDU2, data page, extended data page

TEST(CoreDbc, Pdu2IdentifierCarriesGroupExtensionInPgn) {
  // 0CF00400 = 000 0 1 1 | 0 0 | 11110000 | 00000100 | 00000000: priority 3, PF 0xF0 (>= 240 so PDU2),
  // PS 0x04 is the group extension -> PGN 0xF004 = 61444 (EEC1) from source 0x00.
  const auto id = roadload::j1939::parse_id(0x0CF00400);
  EXPECT_EQ(id.priority, 3);
  EXPECT_FALSE(id.edp);
  EXPECT_FALSE(id.dp);
  EXPECT_FALSE(id.pdu1());
  EXPECT_EQ(id.pgn(), 61444u);
  EXPECT_EQ(id.sa, 0x00);
  EXPECT_EQ(id.da(), 0xFF);  // PDU2 is always broadcast
  // 18FEF100: PF 0xFE, PS 0xF1 -> PGN 0xFEF1 = 65265 (CCVS1).
  EXPECT_EQ(roadload::j1939::pgn_of(0x18FEF100), 65265u);
}

TEST(CoreDbc, Pdu1IdentifierKeepsDestinationOutOfPgn) {
  // 18EAFF00 (request): PF 0xEA = 234 < 240 so PDU1; PS 0xFF is the destination (global), not part
  // of the PGN -> PGN 0xEA00 = 59904.
  const auto req = roadload::j1939::parse_id(0x18EAFF00);
  EXPECT_TRUE(req.pdu1());
  EXPECT_EQ(req.pgn(), 59904u);
  EXPECT_EQ(req.da(), 0xFF);
  EXPECT_EQ(req.sa, 0x00);
  // The same request sent to address 0x17 has the same PGN.
  EXPECT_EQ(roadload::j1939::pgn_of(0x18EA1700), 59904u);
  EXPECT_EQ(roadload::j1939::parse_id(0x18EA1700).da(), 0x17);
  // TP.CM and TP.DT seen in the idle trace are PDU1 too: 1CECFF00 -> 0xEC00, 1CEBFF00 -> 0xEB00.
  EXPECT_EQ(roadload::j1939::pgn_of(0x1CECFF00), 60416u);
  EXPECT_EQ(roadload::j1939::pgn_of(0x1CEBFF00), 60160u);
}

TEST(CoreDbc, DataPageAndExtendedDataPageBitsSelectOtherPgns) {
  // Bit 24 (DP) set: 19FEF100 -> PGN 0x1FEF1 = 130801, not CCVS1.
  const auto dp = roadload::j1939::parse_id(0x19FEF100);
  EXPECT_TRUE(dp.dp);
  EXPECT_FALSE(dp.edp);
  EXPECT_EQ(dp.pgn(), 0x1FEF1u);
  EXPECT_EQ(core().find(dp.pgn()), nullptr);
  // Bit 25 (EDP, formerly "reserved") set: 1AFEF100 -> PGN 0x2FEF1 = 196337.
  const auto edp = roadload::j1939::parse_id(0x1AFEF100);
  EXPECT_TRUE(edp.edp);
  EXPECT_FALSE(edp.dp);
  EXPECT_EQ(edp.pgn(), 0x2FEF1u);
  EXPECT_EQ(core().find(edp.pgn()), nullptr);
  // Round trips through make_can_id: PDU2 ignores the destination, PDU1 puts it in PS.
  EXPECT_EQ(roadload::j1939::make_can_id(3, 61444, 0x00, 0x00), 0x0CF00400u);
  EXPECT_EQ(roadload::j1939::make_can_id(6, 59904, 0xFF, 0x00), 0x18EAFF00u);
  EXPECT_EQ(roadload::j1939::make_can_id(6, 59904, 0x17, 0xF9), 0x18EA17F9u);
  EXPECT_EQ(roadload::j1939::make_can_id(6, 0x1FEF1, 0x42, 0x00), 0x19FEF100u);
  EXPECT_EQ(roadload::j1939::make_can_id(6, 0x2FEF1, 0x00, 0x00), 0x1AFEF100u);
}

TEST(CoreDbc, MessagesAreKeyedByPgnWhateverPriorityAndSource) {
  // The idle truck sends CCVS1 at priority 3 (0CFEF100); the DBC writes it at priority 6 from 0xFE.
  const MessageDef* a = core().find(roadload::j1939::pgn_of(0x0CFEF100));
  const MessageDef* b = core().find(roadload::j1939::pgn_of(0x18FEF1FE));
  ASSERT_NE(a, nullptr);
  EXPECT_EQ(a, b);
  EXPECT_EQ(a->name, "CCVS1");
}

// ---------------------------------------------------------------------------------------------
// EEC1 / EEC2 / EEC3 / EC1: engine

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
  const auto big = bytes("0000" "00F0E301");
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
  const auto third = bytes("43FF" "61020901");
  EXPECT_DOUBLE_EQ(value(1216, kDM1, third), 1.0);
  EXPECT_EQ(spn(1216, kDM1, bytes("43FF" "0000007F")).state, SignalState::not_available);
}

// ---------------------------------------------------------------------------------------------
// Users' DBC files

TEST(CoreDbc, UserDbcLoadedAfterCoreOverridesAPgn) {
  Database db;
  ASSERT_FALSE(roadload::j1939::load_dbc(db, read_file(kCorePath), kCorePath).has_value());
  const std::size_t before = db.size();
  // A user's CCVS1 from another source address (0x98FEF1EE = 0x80000000 | 18FEF1EE) with a speed
  // in 0.01 km/h; nothing is recompiled, the later definition of PGN 65265 simply wins.
  const std::string user =
      "VERSION \"\"\n"
      "NS_ :\n"
      "\tCM_\n"
      "\n"
      "BS_:\n"
      "BU_: Vector__XXX\n"
      "BO_ 2566844910 MyCCVS: 8 Vector__XXX\n"
      " SG_ MySpeed : 8|16@1+ (0.01,0) [0|642.55] \"km/h\" Vector__XXX\n"
      "BA_DEF_ SG_ \"SPN\" INT 0 524287;\n"
      "BA_ \"SPN\" SG_ 2566844910 MySpeed 84;\n";
  const auto err = roadload::j1939::load_dbc(db, user, "user.dbc");
  ASSERT_FALSE(err.has_value()) << err->to_string();
  EXPECT_EQ(db.size(), before);  // replaced, not added
  const MessageDef* m = db.find(kCCVS1);
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(m->name, "MyCCVS");
  const MessageDef* owner = nullptr;
  const SignalDef* s = db.find_spn(84, &owner);
  ASSERT_NE(s, nullptr);
  EXPECT_EQ(owner, m);
  EXPECT_EQ(s->name, "MySpeed");
  // bytes 2-3 = 0x1F40 = 8000 * 0.01 = 80 km/h (the core definition would say 31.25 km/h)
  EXPECT_NEAR(roadload::j1939::decode(*s, bytes("FF401FFFFFFFFFFF")).get().value_or(-1), 80.0, kExact);
  // Other PGNs keep the core definitions.
  ASSERT_NE(db.find(kEEC1), nullptr);
  EXPECT_EQ(db.find(kEEC1)->name, "EEC1");
  EXPECT_EQ(db.find(kCCVS1)->signals.size(), 1u);
}

TEST(CoreDbc, MalformedDbcLineNamesFileLineAndField) {
  Database db;
  ASSERT_FALSE(roadload::j1939::load_dbc(db, read_file(kCorePath), kCorePath).has_value());
  const std::size_t before = db.size();
  const std::string bad =
      "VERSION \"\"\n"
      "BO_ 2364540158 EEC1: 8 Vector__XXX\n"
      " SG_ EngineSpeed : 24|sixteen@1+ (0.125,0) [0|8031.875] \"rpm\" Vector__XXX\n";
  const auto err = roadload::j1939::load_dbc(db, bad, "user.dbc");
  ASSERT_TRUE(err.has_value());
  EXPECT_EQ(err->file, "user.dbc");
  EXPECT_EQ(err->line, 3);
  EXPECT_EQ(err->field, "SG_ length");
  const std::string text = err->to_string();
  EXPECT_NE(text.find("user.dbc:3"), std::string::npos) << text;
  EXPECT_NE(text.find("SG_ length"), std::string::npos) << text;
  // A failed load leaves the database as it was.
  EXPECT_EQ(db.size(), before);
  EXPECT_EQ(db.find(kEEC1)->signals.size(), core().find(kEEC1)->signals.size());

  const std::string bad_factor =
      "VERSION \"\"\n"
      "\n"
      "BO_ 2364540158 EEC1: 8 Vector__XXX\n"
      " SG_ EngineSpeed : 24|16@1+ (0.l25,0) [0|8031.875] \"rpm\" Vector__XXX\n";
  const auto err2 = roadload::j1939::load_dbc(db, bad_factor, "factor.dbc");
  ASSERT_TRUE(err2.has_value());
  EXPECT_EQ(err2->line, 4);
  EXPECT_NE(err2->to_string().find("factor.dbc:4"), std::string::npos) << err2->to_string();
  EXPECT_NE(err2->field.find("SG_"), std::string::npos) << err2->to_string();
}

}  // namespace
