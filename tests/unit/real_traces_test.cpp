// Real J1939 traffic nobody here wrote (CSS Electronics, MIT): decoded end to end with no error.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "roadload/definitions.hpp"
#include "roadload/j1939/assembler.hpp"
#include "roadload/recording/reader.hpp"

namespace roadload {
namespace {

struct Summary {
  std::map<CanFrameKind, std::uint64_t> kinds;
  std::uint64_t decoded_values = 0;
  std::vector<double> reference_torque_nm;
  std::vector<double> engine_speed_rpm;
  std::uint64_t errors = 0;
  j1939::TpCounters tp;
};

Summary decode_trace(const std::string& name) {
  j1939::Database db;
  EXPECT_FALSE(load_dbc_file(db, ROADLOAD_CONFIG_DIR "/j1939-core.dbc"));
  auto rec = recording::RecordingReader::open(ROADLOAD_TEST_DATA "/traces/" + name);
  EXPECT_TRUE(rec);
  Summary s;
  j1939::MessageAssembler assembler;
  while (const recording::Record* r = rec.value().next()) {
    const CanFrame& f = std::get<CanFrame>(*r);
    ++s.kinds[f.kind];
    const auto m = assembler.push(f);
    if (!m) continue;
    const j1939::MessageDef* def = db.find(m->pgn);
    if (def == nullptr) continue;
    for (const j1939::SignalDef& sig : def->signals) {
      const auto v = j1939::decode(sig, m->data).get();
      if (!v) continue;
      ++s.decoded_values;
      if (sig.spn == 544) s.reference_torque_nm.push_back(*v);
      if (sig.spn == 190) s.engine_speed_rpm.push_back(*v);
    }
  }
  s.errors = rec.value().errors().count();
  s.tp = assembler.transport().counters();
  return s;
}

TEST(RealTraces, TruckIdleReassemblesEc1ReferenceTorqueAndIdlesNear650Rpm) {
  const Summary s = decode_trace("css-truck-idle.log");
  EXPECT_EQ(s.errors, 0u);
  ASSERT_FALSE(s.reference_torque_nm.empty());
  for (double t : s.reference_torque_nm) EXPECT_DOUBLE_EQ(t, 2386.0);
  ASSERT_GT(s.engine_speed_rpm.size(), 10000u);
  double sum = 0;
  for (double v : s.engine_speed_rpm) sum += v;
  EXPECT_NEAR(sum / static_cast<double>(s.engine_speed_rpm.size()), 650.0, 15.0);
  EXPECT_EQ(s.tp.timed_out, 0u);
  EXPECT_EQ(s.tp.orphan_packets, 0u);
}

TEST(RealTraces, KeyOnLogCountsElevenBitFramesApart) {
  const Summary s = decode_trace("css-key-on-mixed-11bit.log");
  EXPECT_EQ(s.errors, 0u);
  EXPECT_EQ(s.kinds.at(CanFrameKind::standard), 11275u);
  EXPECT_EQ(s.kinds.at(CanFrameKind::standard) + s.kinds.at(CanFrameKind::extended), 150411u);
  EXPECT_GT(s.decoded_values, 0u);
}

TEST(RealTraces, TransportSampleDecodesWithoutErrors) {
  const Summary s = decode_trace("css-fcbf0606-tp-sample.log");
  EXPECT_EQ(s.errors, 0u);
  EXPECT_EQ(s.kinds.at(CanFrameKind::extended), 1815u);
  EXPECT_GT(s.tp.completed, 0u);
  EXPECT_EQ(s.tp.malformed, 0u);
}

}  // namespace
}  // namespace roadload
