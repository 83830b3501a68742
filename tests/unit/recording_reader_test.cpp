// A recording folder read back as one stream in capture-time order, with bad lines reported by
// file, line and field and skipped, never silently lost.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <tuple>

#include "roadload/recording/reader.hpp"

namespace roadload::recording {
namespace {

namespace fs = std::filesystem;

class RecordingFolder : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("roadload-rec-" + std::to_string(::getpid()) + "-" + testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  void write(const char* name, const std::string& text) { std::ofstream(dir_ / name) << text; }

  fs::path dir_;
};

constexpr const char* kMeta = R"(format = "roadload-recording"
version = 1
created_by = "test"
[clock]
source = "simulated"
utc_offset_ns = 1413792000000000000
[vehicle]
name = "MnROAD truck"
mass_kg = 36152.0
[can]
interfaces = ["can0"]
[[sensor]]
id = 0
name = "TLF1"
kind = "accelerometer"
position = "tractor-front-axle-left"
part = "ADXL355"
rate_hz = 1200
)";

TEST_F(RecordingFolder, MergesStreamsInCaptureTimeOrder) {
  write("meta.toml", kMeta);
  write("can.log", "(0.000000) can0 0CF00400#607D844A1400F084\n(0.002000) can0 0CF00400#607D844A1400F084\n");
  write("accel.csv", "t_ns,sensor,x_mps2,y_mps2,z_mps2\n500000,0,0.1,0.2,9.81\n2500000,0,0.1,0.2,9.80\n");
  write("gnss.csv",
        "t_ns,utc_ns,lat_deg,lon_deg,alt_m,speed_mps,course_deg,mode,hdop\n"
        "1000000,1413792000001000000,45.249694,-93.686217,290.5,13.4,270.0,4,0.8\n");
  write("weather.csv", "t_ns,station,air_temp_c,pressure_pa,wind_speed_mps,wind_from_deg\n0,1,14.3,98100,3.8,292\n");
  auto rec = RecordingReader::open(dir_.string());
  ASSERT_TRUE(rec) << rec.error().to_string();
  std::vector<std::int64_t> stamps;
  std::vector<std::size_t> kinds;
  while (const Record* r = rec.value().next()) {
    stamps.push_back(std::visit([](const auto& s) { return to_ns(s.t); }, *r));
    kinds.push_back(r->index());
  }
  EXPECT_EQ(stamps, (std::vector<std::int64_t>{0, 0, 500000, 1000000, 2000000, 2500000}));
  EXPECT_EQ(kinds, (std::vector<std::size_t>{0, 3, 1, 2, 0, 1}));  // ties: can before weather
  EXPECT_EQ(rec.value().errors().count(), 0u);
  EXPECT_TRUE(rec.value().has_metadata());
  EXPECT_EQ(rec.value().metadata().sensors.at(0).name, "TLF1");
  EXPECT_DOUBLE_EQ(rec.value().metadata().vehicle.at("mass_kg"), 36152.0);
}

TEST_F(RecordingFolder, BadRowsAreReportedWithFileLineAndFieldAndSkipped) {
  write("accel.csv",
        "t_ns,sensor,x_mps2,y_mps2,z_mps2\n"
        "1,0,0,0,9.8\n"
        "2,0,zero,0,9.8\n"  // line 3: x_mps2
        "3,0,0,0\n"         // line 4: wrong field count
        "4,300,0,0,9.8\n"   // line 5: sensor out of range
        "5,0,0,0,nan\n"     // line 6: not finite
        "6,0,0,0,9.8\n");
  auto rec = RecordingReader::open(dir_.string());
  ASSERT_TRUE(rec);
  int good = 0;
  while (rec.value().next() != nullptr) ++good;
  EXPECT_EQ(good, 2);
  const auto& errors = rec.value().errors();
  ASSERT_EQ(errors.count(), 4u);
  EXPECT_EQ(errors.kept()[0].line, 3);
  EXPECT_EQ(errors.kept()[0].field, "x_mps2");
  EXPECT_EQ(errors.kept()[1].field, "row");
  EXPECT_EQ(errors.kept()[2].field, "sensor");
  EXPECT_EQ(errors.kept()[3].field, "z_mps2");
  EXPECT_NE(errors.kept()[0].file.find("accel.csv"), std::string::npos);
}

// A line a megabyte long (a logger's corrupted buffer) costs that line, not the rest of the file.
TEST_F(RecordingFolder, AnOverlongLineIsSkippedAndReportedAndReadingGoesOn) {
  const std::string frame = "can0 0CF00400#607D844A1400F084\n";
  write("can.log", "(0.000000) " + frame + std::string(1 << 20, 'x') + "\n(0.002000) " + frame + "(0.004000) " + frame);
  write("accel.csv",
        "t_ns,sensor,x_mps2,y_mps2,z_mps2\n1,0,0,0,9.8\n" + std::string(3 << 20, '7') + "\n3,0,0,0,9.8\n" + std::string(70000, ','));
  auto rec = RecordingReader::open(dir_.string());
  ASSERT_TRUE(rec) << rec.error().to_string();
  int frames = 0, samples = 0;
  while (const Record* r = rec.value().next()) (r->index() == 0 ? frames : samples) += 1;
  EXPECT_EQ(frames, 3);
  EXPECT_EQ(samples, 2);
  const auto& errors = rec.value().errors();
  ASSERT_EQ(errors.count(), 3u);
  std::vector<std::string> where;
  for (const ParseError& e : errors.kept())
    where.push_back(fs::path(e.file).filename().string() + ":" + std::to_string(e.line) + ": " + e.message);
  std::sort(where.begin(), where.end());
  EXPECT_EQ(where, (std::vector<std::string>{"accel.csv:3: line longer than 65536 bytes, skipped",
                                             "accel.csv:5: line longer than 65536 bytes, skipped",
                                             "can.log:2: line longer than 65536 bytes, skipped"}));
}

TEST_F(RecordingFolder, MissingColumnIsFatalAtOpen) {
  write("gnss.csv", "t_ns,lat_deg,lon_deg\n1,45,-93\n");
  auto rec = RecordingReader::open(dir_.string());
  ASSERT_FALSE(rec);
  EXPECT_EQ(rec.error().field, "alt_m");
  EXPECT_EQ(rec.error().line, 1);
}

// A receiver that gives neither UTC nor course nor HDOP: the fixes read, with UTC unknown (0) and
// course NaN. What no sensor reports is refused with its line and field.
TEST_F(RecordingFolder, GnssWithoutUtcOrCourseReadsAndNonsenseIsRefused) {
  write("gnss.csv",
        "t_ns,lat_deg,lon_deg,alt_m,speed_mps,mode\n"
        "1000,45.25,-93.69,290.5,13.4,3\n"
        "-5,45.25,-93.69,290.5,13.4,3\n"                                                 // line 3: a stamp before the clock's zero
        "9223372036854775807,45.25,-93.69,290.5,13.4,3\n"                                // line 4: beyond any clock
        "2000,45.25,-93.69,290.5,1e9,3\n");                                              // line 5: speed
  write("accel.csv", "t_ns,sensor,x_mps2,y_mps2,z_mps2\n1,0,0,0,9.8\n2,0,0,1e6,9.8\n");  // line 3: y
  auto rec = RecordingReader::open(dir_.string());
  ASSERT_TRUE(rec) << rec.error().to_string();
  std::vector<GnssFix> fixes;
  while (const Record* r = rec.value().next()) {
    if (const auto* f = std::get_if<GnssFix>(r)) fixes.push_back(*f);
  }
  ASSERT_EQ(fixes.size(), 1u);
  EXPECT_EQ(fixes[0].utc_ns, 0);
  EXPECT_TRUE(std::isnan(fixes[0].course_deg));
  EXPECT_DOUBLE_EQ(fixes[0].lat_deg, 45.25);
  std::vector<std::string> errors;
  for (const ParseError& e : rec.value().errors().kept()) {
    errors.push_back(fs::path(e.file).filename().string() + ":" + std::to_string(e.line) + ": " + e.field);
  }
  std::sort(errors.begin(), errors.end());
  EXPECT_EQ(errors,
            (std::vector<std::string>{"accel.csv:3: y_mps2", "gnss.csv:3: t_ns", "gnss.csv:4: t_ns", "gnss.csv:5: speed_mps"}));
}

TEST_F(RecordingFolder, MetadataErrorsNameTheKeyAndLine) {
  write("can.log", "");
  write("meta.toml", "format = \"roadload-recording\"\nversion = 1\n[[sensor]]\nid = \"zero\"\nname = \"a\"\nkind = \"b\"\n");
  auto rec = RecordingReader::open(dir_.string());
  ASSERT_FALSE(rec);
  EXPECT_EQ(rec.error().field, "sensor[0].id");
  EXPECT_EQ(rec.error().line, 4);
}

TEST(Metadata, NonAsciiIsRejectedWithItsLine) {
  auto m = parse_metadata("format = \"roadload-recording\"\nversion = 1\n\xcf\xa6 = 1\n", "meta.toml");
  ASSERT_FALSE(m);
  EXPECT_EQ(m.error().line, 3);
}

// Keys the format defines, of the wrong type, are errors rather than absent: a mass given as text
// would leave the truck's mass unknown without a word.
TEST(Metadata, WrongTypesAreNamedNotIgnored) {
  const std::string head = "format = \"roadload-recording\"\nversion = 1\n";
  const std::tuple<std::string, std::string, long> cases[] = {
      {"[vehicle]\nmass_kg = \"heavy\"\n", "vehicle.mass_kg", 4},
      {"vehicle = 5\n", "vehicle", 3},
      {"clock = \"x\"\n", "clock", 3},
      {"can = [1]\n", "can", 3},
  };
  for (const auto& [body, field, line] : cases) {
    auto m = parse_metadata(head + body, "meta.toml");
    ASSERT_FALSE(m) << body;
    EXPECT_EQ(m.error().field, field) << body;
    EXPECT_EQ(m.error().line, line) << body;
  }
  auto labelled = parse_metadata(head + "[vehicle]\nname = \"truck 7\"\nmass_kg = 36000\n", "meta.toml");
  ASSERT_TRUE(labelled) << labelled.error().to_string();
  EXPECT_EQ(labelled.value().vehicle_text.at("name"), "truck 7");
}

TEST_F(RecordingFolder, AMetaTomlThatIsADirectoryIsSaidToBeOne) {
  write("can.log", "");
  fs::create_directories(dir_ / "meta.toml");
  auto rec = RecordingReader::open(dir_.string());
  ASSERT_FALSE(rec);
  EXPECT_EQ(rec.error().message, "Is a directory");
}

TEST_F(RecordingFolder, MetadataRoundTrips) {
  auto m = parse_metadata(kMeta, "meta.toml");
  ASSERT_TRUE(m) << m.error().to_string();
  auto again = parse_metadata(format_metadata(m.value()), "formatted");
  ASSERT_TRUE(again) << again.error().to_string();
  EXPECT_EQ(again.value().utc_offset_ns, m.value().utc_offset_ns);
  EXPECT_EQ(again.value().vehicle_text, m.value().vehicle_text);
  EXPECT_EQ(again.value().vehicle, m.value().vehicle);
  EXPECT_EQ(again.value().can_interfaces, m.value().can_interfaces);
  ASSERT_EQ(again.value().sensors.size(), 1u);
  EXPECT_EQ(again.value().sensors[0].position, "tractor-front-axle-left");
  EXPECT_DOUBLE_EQ(again.value().sensors[0].rate_hz, 1200.0);
}

TEST_F(RecordingFolder, EmptyFolderIsNotARecording) {
  auto rec = RecordingReader::open(dir_.string());
  ASSERT_FALSE(rec);
  EXPECT_NE(rec.error().message.find("not a recording"), std::string::npos);
}

TEST(RecordingReader, MissingFileNamesPath) {
  auto rec = RecordingReader::open("/nonexistent/can.log");
  ASSERT_FALSE(rec);
  EXPECT_EQ(rec.error().file, "/nonexistent/can.log");
}

}  // namespace
}  // namespace roadload::recording
