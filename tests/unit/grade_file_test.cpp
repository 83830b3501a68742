// A grade file keeps what its profile's errors need: the slopes' base, so a route traced with a
// long base is analysed with its errors correlated over that base, and files without it (written
// before it was kept) read as the default's.
#include "roadload/grade_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "roadload/route_geometry.hpp"

namespace roadload {
namespace {

RouteGeometry straight_route() {
  const std::vector<GeoPoint> points = {{45.0, -93.0, 300.0}, {45.0 + 1000.0 / 111132.0, -93.0, 305.0}};
  return *RouteGeometry::build(points);
}

std::string temp_path(const char* name) { return (std::filesystem::temp_directory_path() / name).string(); }

TEST(GradeFile, KeepsTheSlopesBaseAndWithItTheErrorsCorrelation) {
  const RouteGeometry route = straight_route();
  GradeConfig cfg;
  cfg.base_m = 100.0;
  const GradeProfile written = GradeProfile::from_survey(route, 0.1, cfg);
  const std::string path = temp_path("roadload-grade-file-test.csv");
  ASSERT_FALSE(write_grade_file(path, written));
  auto read = load_grade_file(path, route.length_m());
  ASSERT_TRUE(read) << read.error().to_string();
  EXPECT_DOUBLE_EQ(read.value().config().base_m, 100.0);
  EXPECT_DOUBLE_EQ(read.value().error_correlation_m(), 5.0 / 6.0 * 100.0);
  ASSERT_EQ(read.value().bins().size(), written.bins().size());
  EXPECT_NEAR(read.value().grade_rad(500.0), written.grade_rad(500.0), 1e-6);
  std::filesystem::remove(path);
}

TEST(GradeFile, AFileWithoutItsBaseReadsAsTheDefaults) {
  const RouteGeometry route = straight_route();
  const GradeProfile written = GradeProfile::from_survey(route, 0.1);
  const std::string path = temp_path("roadload-grade-file-old.csv");
  ASSERT_FALSE(write_grade_file(path, written));
  // Drop the comment line, as files written before the base was kept.
  std::ifstream in(path);
  std::string line, rest;
  while (std::getline(in, line)) {
    if (line.rfind('#', 0) != 0) rest += line + "\n";
  }
  in.close();
  std::ofstream(path) << rest;
  auto read = load_grade_file(path, route.length_m());
  ASSERT_TRUE(read) << read.error().to_string();
  EXPECT_DOUBLE_EQ(read.value().config().base_m, GradeConfig{}.base_m);
  EXPECT_DOUBLE_EQ(read.value().error_correlation_m(), 5.0 / 6.0 * GradeConfig{}.base_m);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace roadload
