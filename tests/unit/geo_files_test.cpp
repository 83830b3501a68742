// GIS files of roads and pavement sections: GeoJSON lines with their properties and GPX tracks
// read as an agency's layers give them; a bad value refused naming the file and the field (and,
// where the format keeps positions, the line).
#include "roadload/geo_files.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

namespace roadload {
namespace {

std::string write(const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::temp_directory_path() / ("geo_files_test_" + name)).string();
  std::ofstream(path) << text;
  return path;
}

TEST(GeoFiles, AGeoJsonCollectionGivesEverySectionWithItsProperties) {
  const std::string path = write("sections.geojson", R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": {"name": "JPCP 12", "surface": "concrete", "panel_length_m": 4.57, "iri_m_per_km": 1.9},
     "geometry": {"type": "LineString", "coordinates": [[-93.1, 45.0, 280.5], [-93.09, 45.001, 281.0]]}},
    {"type": "Feature", "properties": {"id": 7, "surface": "Asphalt"},
     "geometry": {"type": "MultiLineString", "coordinates": [[[-93.09, 45.001], [-93.08, 45.002]], [[-93.08, 45.002], [-93.07, 45.003]]]}}]})");
  auto s = load_geo_sections(path);
  ASSERT_TRUE(s) << s.error().to_string();
  ASSERT_EQ(s.value().size(), 2u);
  const GeoSection& a = s.value()[0];
  EXPECT_EQ(a.name, "JPCP 12");
  EXPECT_EQ(a.surface, "concrete");
  EXPECT_DOUBLE_EQ(*a.panel_length_m, 4.57);
  EXPECT_DOUBLE_EQ(*a.iri_m_per_km, 1.9);
  ASSERT_EQ(a.line.size(), 2u);
  EXPECT_DOUBLE_EQ(a.line[0].lat_deg, 45.0);  // GeoJSON puts longitude first
  EXPECT_DOUBLE_EQ(a.line[0].lon_deg, -93.1);
  EXPECT_DOUBLE_EQ(a.line[1].elev_m, 281.0);
  const GeoSection& b = s.value()[1];
  EXPECT_EQ(b.name, "7");
  EXPECT_EQ(b.surface, "bituminous");
  EXPECT_FALSE(b.panel_length_m);
  EXPECT_EQ(b.line.size(), 4u);
  EXPECT_TRUE(std::isnan(b.line[0].elev_m));
}

TEST(GeoFiles, ABadGeoJsonValueIsNamedByItsPath) {
  auto s = load_geo_sections(write("bad.geojson", R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "properties": {}, "geometry": {"type": "LineString", "coordinates": [[-93.1, 45.0], [-93.09, 95.0]]}}]})"));
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().field, "features[0].geometry.coordinates[1][1]");
  EXPECT_NE(s.error().message.find("latitude"), std::string::npos);
  auto iri = load_geo_sections(write("iri.geojson", R"({"type": "Feature", "properties": {"iri_m_per_km": -1},
    "geometry": {"type": "LineString", "coordinates": [[-93.1, 45.0], [-93.09, 45.0]]}})"));
  ASSERT_FALSE(iri);
  EXPECT_EQ(iri.error().field, "feature.properties.iri_m_per_km");
}

TEST(GeoFiles, AGeoJsonSyntaxErrorNamesItsLine) {
  auto s = load_geo_sections(write("syntax.geojson", "{\"type\": \"Feature\",\n  \"geometry\": {\n  \"type\": \"LineString\",,\n}}"));
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().line, 3);
}

TEST(GeoFiles, OneLineIsTheOnlyLineAGeoJsonDraws) {
  const std::string two = write("two.geojson", R"({"type": "FeatureCollection", "features": [
    {"type": "Feature", "geometry": {"type": "LineString", "coordinates": [[0, 0], [0, 1]]}},
    {"type": "Feature", "geometry": {"type": "LineString", "coordinates": [[0, 1], [0, 2]]}}]})");
  EXPECT_FALSE(load_geo_line(two));
  auto one = load_geo_line(write("one.json", R"({"type": "LineString", "coordinates": [[10, 50, 100], [10.001, 50, 101]]})"));
  ASSERT_TRUE(one) << one.error().to_string();
  EXPECT_EQ(one.value().size(), 2u);
}

TEST(GeoFiles, AGpxTrackIsALineWithItsHeights) {
  const std::string path = write("drive.gpx", R"(<?xml version="1.0"?>
<gpx version="1.1" creator="test" xmlns="http://www.topografix.com/GPX/1/1">
  <trk><name>TH 10 westbound</name><type>asphalt</type>
    <trkseg><trkpt lat="45.5" lon="-94.1"><ele>300.5</ele></trkpt><trkpt lat="45.501" lon="-94.1"><ele>301</ele></trkpt></trkseg>
    <trkseg><trkpt lat="45.502" lon="-94.1"/></trkseg>
  </trk>
  <trk><name>second</name><trkseg><trkpt lat="46" lon="-94"/><trkpt lat="46.1" lon="-94"/></trkseg></trk>
</gpx>)");
  auto line = load_geo_line(path);
  ASSERT_TRUE(line) << line.error().to_string();
  ASSERT_EQ(line.value().size(), 3u);  // the first track, its segments joined
  EXPECT_DOUBLE_EQ(line.value()[1].elev_m, 301.0);
  EXPECT_TRUE(std::isnan(line.value()[2].elev_m));
  auto sections = load_geo_sections(path);
  ASSERT_TRUE(sections);
  ASSERT_EQ(sections.value().size(), 2u);
  EXPECT_EQ(sections.value()[0].name, "TH 10 westbound");
  EXPECT_EQ(sections.value()[0].surface, "bituminous");
}

TEST(GeoFiles, ABadGpxValueNamesItsLine) {
  auto s = load_geo_line(write("bad.gpx", "<gpx>\n<trk>\n<trkseg>\n<trkpt lat=\"45\" lon=\"x\"/>\n</trkseg></trk></gpx>"));
  ASSERT_FALSE(s);
  EXPECT_EQ(s.error().line, 4);
  EXPECT_EQ(s.error().field, "trkpt.lon");
  auto broken = load_geo_line(write("broken.gpx", "<gpx>\n<trk>\n</gpx>"));
  ASSERT_FALSE(broken);
  EXPECT_EQ(broken.error().line, 3);
  EXPECT_NE(broken.error().message.find("not XML"), std::string::npos);
}

TEST(GeoFiles, AnUnknownKindIsRefused) {
  auto s = load_geo_line(write("road.kml", "<kml/>"));
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find(".gpx"), std::string::npos);
}

}  // namespace
}  // namespace roadload
