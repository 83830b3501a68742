// The built-in J1939 definition set (config/j1939-core.dbc) loaded through the codec and checked
// against frames decoded by hand. Real frames come from the CSS Electronics traces in
// tests/data/traces (MIT); the line each one was taken from is named next to it.
// This file: the file itself, identifiers, and user DBCs over it.
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

// ---------------------------------------------------------------------------------------------
// The file itself

TEST(CoreDbc, LoadsAndDefinesEveryRequiredPgn) {
  const Database& db = core();
  const std::vector<std::pair<roadload::j1939::Pgn, std::string>> required = {
      {kEEC1, "EEC1"}, {kEEC2, "EEC2"}, {kEEC3, "EEC3"}, {kEC1, "EC1"},     {kCCVS1, "CCVS1"}, {kLFE1, "LFE1"}, {kETC1, "ETC1"},
      {kETC2, "ETC2"}, {kAMB, "AMB"},   {kVD, "VD"},     {kVDHR, "VDHR"},   {kVP1, "VP1"},     {kFD1, "FD1"},   {kEBC1, "EBC1"},
      {kDM1, "DM1"},   {kERC1, "ERC1"}, {kEBC2, "EBC2"}, {kHOURS, "HOURS"}, {kLFC, "LFC"},     {kET1, "ET1"}};
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
