// Route files as a user writes them or `roadload route build` makes them: cells without a CRR,
// geometry from a GIS file, a grade profile named beside it, and a written route read back whole.
#include "roadload/route_file.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace roadload {
namespace {

std::string write(const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::temp_directory_path() / ("route_file_test_" + name)).string();
  std::ofstream(path) << text;
  return path;
}

// Appended rather than added: GCC 12 warns of a false overflow in operator+ on string temporaries.
std::string join(std::initializer_list<std::string_view> parts) {
  std::string out;
  for (std::string_view p : parts) out.append(p);
  return out;
}

constexpr const char* kPoints = R"(
[[point]]
lat_deg = 45.0
lon_deg = -93.0
elev_m = 280.0

[[point]]
lat_deg = 45.01
lon_deg = -93.0
)";

TEST(RouteFile, ACellNeedsNoCrr) {
  auto r = load_route_file(
      write("nocrr.toml", join({"name = \"own road\"\n", kPoints, "\n[[cell]]\nid = \"A\"\nstart_m = 0\nlength_m = 500\n"})));
  ASSERT_TRUE(r) << r.error().to_string();
  ASSERT_EQ(r.value().cells.size(), 1u);
  EXPECT_FALSE(r.value().cells[0].crr);
  EXPECT_TRUE(r.value().cells[0].surface.empty());
  EXPECT_TRUE(std::isnan(r.value().points[1].elev_m));
}

TEST(RouteFile, ABadCellValueIsNamed) {
  auto r = load_route_file(
      write("badcrr.toml", join({"name = \"r\"\n", kPoints, "\n[[cell]]\nid = \"A\"\nstart_m = 0\nlength_m = 500\ncrr = -0.001\n"})));
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().field, "cell[0].crr");
  EXPECT_EQ(r.error().line, 16);
}

TEST(RouteFile, GeometryAndGradeComeFromFilesBesideIt) {
  write("line.geojson", R"({"type": "LineString", "coordinates": [[-93.0, 45.0, 280], [-93.0, 45.01, 282]]})");
  auto r = load_route_file(write("geo.toml", "name = \"r\"\ngeometry = \"route_file_test_line.geojson\"\ngrade = \"g.csv\"\n"));
  ASSERT_TRUE(r) << r.error().to_string();
  ASSERT_EQ(r.value().points.size(), 2u);
  EXPECT_DOUBLE_EQ(r.value().points[1].elev_m, 282.0);
  EXPECT_EQ(std::filesystem::path(r.value().grade_file), std::filesystem::temp_directory_path() / "g.csv");
  auto both = load_route_file(write("both.toml", join({"name = \"r\"\ngeometry = \"route_file_test_line.geojson\"\n", kPoints})));
  ASSERT_FALSE(both);
  EXPECT_EQ(both.error().field, "geometry");
  auto missing = load_route_file(write("missing.toml", "name = \"r\"\ngeometry = \"no-such.gpx\"\n"));
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().file.find("no-such.gpx"), std::string::npos);
}

TEST(RouteFile, AWrittenRouteReadsBackAsItWas) {
  RouteFile r;
  r.name = "Highway \"7\"";
  r.source = "test";
  r.grade_file = "h7.grade.csv";
  r.points = {{45.0, -93.0, 280.123}, {45.001, -93.0001, std::nan("")}, {45.002, -93.0002, 281.5}};
  CellDef a;
  a.id = "0 m";
  a.start_m = 0;
  a.end_m = 100.005;
  a.surface = "concrete";
  a.joint_spacing_m = 4.57;
  a.iri_m_per_km = 1.8;
  CellDef b;
  b.id = "100 m";
  b.start_m = 100.005;
  b.end_m = 222.2;
  b.crr = 0.0061;
  r.cells = {a, b};
  auto back = load_route_file(write("roundtrip.toml", format_route_file(r)));
  ASSERT_TRUE(back) << back.error().to_string();
  const RouteFile& g = back.value();
  EXPECT_EQ(g.name, r.name);
  ASSERT_EQ(g.points.size(), 3u);
  EXPECT_NEAR(g.points[0].elev_m, 280.123, 1e-9);
  EXPECT_TRUE(std::isnan(g.points[1].elev_m));
  EXPECT_NEAR(g.points[2].lon_deg, -93.0002, 1e-9);
  ASSERT_EQ(g.cells.size(), 2u);  // touching cells still touch after rounding
  EXPECT_EQ(g.cells[0].surface, "concrete");
  EXPECT_DOUBLE_EQ(g.cells[0].joint_spacing_m, 4.57);
  EXPECT_FALSE(g.cells[0].crr);
  EXPECT_DOUBLE_EQ(*g.cells[1].crr, 0.0061);
  EXPECT_NEAR(g.cells[1].end_m, 222.2, 1e-9);
  EXPECT_EQ(std::filesystem::path(g.grade_file).filename(), "h7.grade.csv");
}

}  // namespace
}  // namespace roadload
