// The DBC reader: the dialect users' files come in, and errors that name file, line and field.
#include <gtest/gtest.h>

#include "roadload/j1939/dbc.hpp"

namespace roadload::j1939 {
namespace {

constexpr const char* kSmall = R"(VERSION ""

NS_ :
	NS_DESC_
	CM_
	BA_DEF_

BS_:

BU_: Engine Logger

BO_ 2364540158 EEC1: 8 Engine
 SG_ EngineSpeed : 24|16@1+ (0.125,0) [0|8031.875] "rpm" Logger,Other
 SG_ ActualEnginePercentTorque : 16|8@1+ (1,-125) [-125|125] "%" Logger

BO_ 2566844926 CCVS1: 8 Engine
 SG_ WheelBasedVehicleSpeed : 8|16@1+ (0.00390625,0) [0|250.996] "km/h" Vector__XXX
 SG_ Mux M : 0|2@1+ (1,0) [0|3] "" Vector__XXX
 SG_ Muxed m1 : 32|8@1+ (1,0) [0|250] "" Vector__XXX

BO_ 291 Standard11: 8 Engine
 SG_ X : 0|8@1+ (1,0) [0|255] "" Vector__XXX

CM_ SG_ 2364540158 EngineSpeed "Actual engine speed;
spans two lines";
BA_DEF_ SG_ "SPN" INT 0 524287;
BA_DEF_ BO_ "GenMsgCycleTime" INT 0 65535;
BA_DEF_DEF_ "SPN" 0;
BA_ "GenMsgCycleTime" BO_ 2364540158 10;
BA_ "SPN" SG_ 2364540158 EngineSpeed 190;
VAL_ 2566844926 Mux 0 "a" 1 "b" ;
)";

TEST(DbcReader, ReadsMessagesSignalsAndSpnAttributes) {
  Database db;
  ASSERT_FALSE(load_dbc(db, kSmall, "small.dbc"));
  const MessageDef* eec1 = db.find(61444);
  ASSERT_NE(eec1, nullptr);
  EXPECT_EQ(eec1->name, "EEC1");
  EXPECT_EQ(eec1->cycle_time_ms, 10u);
  ASSERT_EQ(eec1->signals.size(), 2u);
  EXPECT_EQ(eec1->signals[0].spn, 190u);
  EXPECT_EQ(eec1->signals[0].start_bit, 24);
  EXPECT_EQ(eec1->signals[0].length, 16);
  EXPECT_DOUBLE_EQ(eec1->signals[0].factor, 0.125);
  EXPECT_DOUBLE_EQ(eec1->signals[1].offset, -125.0);
  EXPECT_EQ(eec1->signals[0].unit, "rpm");
  const MessageDef* m = nullptr;
  EXPECT_EQ(db.find_spn(190, &m), &eec1->signals[0]);
  EXPECT_EQ(m, eec1);
}

TEST(DbcReader, MultiplexedSignalsAreNotLoadedAsPlainSignals) {
  Database db;
  ASSERT_FALSE(load_dbc(db, kSmall, "small.dbc"));
  const MessageDef* ccvs = db.find(65265);
  ASSERT_NE(ccvs, nullptr);
  ASSERT_EQ(ccvs->signals.size(), 2u);  // the multiplexor itself stays, the muxed signal does not
  EXPECT_EQ(ccvs->signals[1].name, "Mux");
}

TEST(DbcReader, ElevenBitMessagesAreNotJ1939) {
  Database db;
  ASSERT_FALSE(load_dbc(db, kSmall, "small.dbc"));
  EXPECT_EQ(db.size(), 2u);
}

TEST(DbcReader, PduOneIdentifierIsKeyedByPgnWithoutDestination) {
  // TSC1 0x0C000003 to destination 0x00: PGN 0.
  Database db;
  ASSERT_FALSE(load_dbc(db, "BO_ 2348810243 TSC1: 8 X\n SG_ A : 0|2@1+ (1,0) [0|3] \"\" Y\n", "t.dbc"));
  EXPECT_NE(db.find(0), nullptr);
}

TEST(DbcReader, LaterDefinitionOverridesSamePgn) {
  Database db;
  ASSERT_FALSE(load_dbc(db, kSmall, "core.dbc"));
  ASSERT_FALSE(load_dbc(db, "BO_ 2364540159 MyEEC1: 8 X\n SG_ Speed : 24|16@1+ (0.25,0) [0|1] \"rpm\" Y\n", "mine.dbc"));
  EXPECT_EQ(db.find(61444)->name, "MyEEC1");
  EXPECT_EQ(db.size(), 2u);
}

struct BadCase {
  const char* text;
  long line;
  const char* field;
};

class DbcReaderRejects : public testing::TestWithParam<BadCase> {};

TEST_P(DbcReaderRejects, WithFileLineAndField) {
  Database db;
  const auto err = load_dbc(db, GetParam().text, "bad.dbc");
  ASSERT_TRUE(err.has_value());
  EXPECT_EQ(err->file, "bad.dbc");
  EXPECT_EQ(err->line, GetParam().line) << err->to_string();
  EXPECT_EQ(err->field, GetParam().field) << err->to_string();
  EXPECT_EQ(db.size(), 0u);
}

INSTANTIATE_TEST_SUITE_P(
    Malformed, DbcReaderRejects,
    testing::Values(BadCase{"BO_ 2364540158 EEC1: 8 E\n SG_ S : 24|0@1+ (1,0) [0|1] \"\" X\n", 2, "SG_ length"},
                    BadCase{"BO_ 2364540158 EEC1: 8 E\n SG_ S : 24|16@1+ (0,0) [0|1] \"\" X\n", 2, "SG_ factor"},
                    BadCase{"BO_ 2364540158 EEC1: 8 E\n\n SG_ S : 24|16@2+ (1,0) [0|1] \"\" X\n", 3, "SG_ byte order"},
                    BadCase{"BO_ 2364540158 EEC1: 8 E\n SG_ S : 24|16@1+ (1,0) [0|1] \"rpm X\n", 2, "SG_ unit"},
                    BadCase{"BO_ 2364540158 EEC1: 8 E\n SG_ S : 24|16@1+ (x,0) [0|1] \"\" X\n", 2, "SG_ factor"},
                    BadCase{" SG_ S : 24|16@1+ (1,0) [0|1] \"\" X\n", 1, "SG_"}, BadCase{"BO_ 99999999999 EEC1: 8 E\n", 1, "BO_ id"},
                    BadCase{"FOO_ bar\n", 1, "keyword"}, BadCase{"BO_ 1 A: 8 E\nBA_ \"SPN\" SG_ 2 S 190;\n", 2, "BA_ message id"},
                    BadCase{"CM_ \"never ends\n", 1, "CM_"}));

TEST(DbcReader, ErrorTextNamesFileLineAndField) {
  Database db;
  const auto err = load_dbc(db, "BO_ 2364540158 EEC1: 8 E\n SG_ S : 24|16@1+ (1,0) [0|1 \"\" X\n", "user.dbc");
  ASSERT_TRUE(err.has_value());
  EXPECT_EQ(err->to_string().rfind("user.dbc:2: SG_ maximum: expected ']'", 0), 0u) << err->to_string();
}

}  // namespace
}  // namespace roadload::j1939
