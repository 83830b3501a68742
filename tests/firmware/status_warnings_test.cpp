// The warnings of a status line: what happened in the interval, not only the state at its end.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "roadload/firmware/status_report.hpp"

namespace roadload::firmware {
namespace {

SourceReport bus(io::SourceState state, const char* detail, std::uint64_t restarts_recent) {
  SourceReport s;
  s.name = "vcan0";
  s.status.state = state;
  s.status.items = 1000;
  s.restarts_recent = restarts_recent;
  std::snprintf(s.status.detail, sizeof s.status.detail, "%s", detail);
  return s;
}

bool has(const std::vector<std::string>& w, const std::string& text) { return std::find(w.begin(), w.end(), text) != w.end(); }

TEST(StatusWarnings, ABusOffWithinOneIntervalIsReportedAsARecovery) {
  StatusReport r;
  r.sources.push_back(bus(io::SourceState::up, "restarted after bus-off", 1));
  EXPECT_TRUE(has(warnings_for(r), "vcan0 recovered 1x (restarted after bus-off)"));
}

TEST(StatusWarnings, ABusStillOffIsReportedDownOnly) {
  StatusReport r;
  r.sources.push_back(bus(io::SourceState::down, "bus-off", 1));
  const auto w = warnings_for(r);
  EXPECT_TRUE(has(w, "vcan0 down: bus-off"));
  EXPECT_EQ(w.size(), 1u);
}

TEST(StatusWarnings, AQuietIntervalWarnsOfNothing) {
  StatusReport r;
  r.sources.push_back(bus(io::SourceState::up, "receiving", 0));
  EXPECT_TRUE(warnings_for(r).empty());
}

// A transport-protocol flood (orphan TP.DT, RTS never answered) is a security warning with its rate;
// the odd orphan of a noisy bus is not.
TEST(StatusWarnings, ATransportFloodIsASecurityWarningWithItsRate) {
  StatusReport r;
  r.j1939.tp_anomalies_recent = 3;
  r.j1939.tp_anomaly_rate = 3;
  EXPECT_TRUE(warnings_for(r).empty());
  r.j1939.tp_anomalies_recent = 341;
  r.j1939.tp_anomaly_rate = 341;
  const auto w = warnings_for(r);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].rfind("SECURITY j1939: transport-protocol flood, 341 ", 0), 0u) << w[0];
  EXPECT_NE(format_json(r).find("\"tp_anomaly_rate\":341.0"), std::string::npos) << format_json(r);
}

}  // namespace
}  // namespace roadload::firmware
