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

}  // namespace
}  // namespace roadload::firmware
