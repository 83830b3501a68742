// Why a drive's CRR is withheld: the filter's consistency named with its side, since a cautious
// filter (NIS below 1) and a model that misses the drive (above 1) ask different things of the user.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "roadload/identification.hpp"

namespace roadload {
namespace {

// A drive that passes every check but the one under test.
TripResult consistent_drive(double mean_nis) {
  TripResult t;
  t.filter.updates = 3600;
  t.mean_nis = mean_nis;
  t.mean_nis_se = 0.0025;
  t.wind_samples = 100;
  t.gnss_used = 3600;
  return t;
}

std::string nis_failure(const TripResult& t) {
  const std::vector<std::string> f = drive_failures(t, IdentificationLimits{});
  const auto it = std::find_if(f.begin(), f.end(), [](const std::string& s) { return s.find("mean NIS") != std::string::npos; });
  return it == f.end() ? std::string() : *it;
}

TEST(Identification, AFilterInsideItsNisBandWithholdsNothing) {
  EXPECT_TRUE(drive_failures(consistent_drive(1.005), IdentificationLimits{}).empty());
}

TEST(Identification, ANisBelowTheBandIsACautiousFilterAndSaysSo) {
  const std::string why = nis_failure(consistent_drive(0.21));
  EXPECT_EQ(why.rfind("the filter is not consistent with this drive: mean NIS 0.21 outside 1 +- 0.01", 0), 0u) << why;
  EXPECT_NE(why.find("wider than the data warrant"), std::string::npos) << why;
}

TEST(Identification, ANisAboveTheBandIsAModelThatMissesTheDriveAndSaysSo) {
  const std::string why = nis_failure(consistent_drive(1.5));
  EXPECT_EQ(why.rfind("the filter is not consistent with this drive: mean NIS 1.50", 0), 0u) << why;
  EXPECT_NE(why.find("its estimate may be wrong"), std::string::npos) << why;
}

}  // namespace
}  // namespace roadload
