// A drive given as several segment folders: joined in order when they are one run's, refused with
// the reason otherwise, and a segment that overlaps the previous one in time reported.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "roadload/recording/reader.hpp"

namespace roadload::recording {
namespace {

namespace fs = std::filesystem;

class Segments : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("segments-test-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A segment folder whose can.log holds one frame per second from `first_s`, on `iface`.
  std::string segment(const std::string& name, const std::string& id, int number, int first_s, int frames,
                      const std::string& iface = "can0") {
    const fs::path d = dir_ / name;
    fs::create_directories(d);
    std::ofstream meta(d / kMetaFile);
    meta << "format = \"roadload-recording\"\nversion = 1\n";
    if (!id.empty()) meta << "recording_id = \"" << id << "\"\nsegment = " << number << "\n";
    std::ofstream can(d / kCanFile);
    for (int i = 0; i < frames; ++i) can << "(" << first_s + i << ".000000) " << iface << " 18FEF100#0102030405060708\n";
    return d.string();
  }

  fs::path dir_;
};

TEST_F(Segments, OneRunsSegmentsJoinInOrderWhateverOrderGiven) {
  const std::string a = segment("a", "run1", 1, 0, 3), b = segment("b", "run1", 2, 3, 3), c = segment("c", "run1", 3, 6, 3);
  const std::vector<std::string> given{c, a, b};
  auto ordered = join_segments(given);
  ASSERT_TRUE(ordered) << ordered.error().to_string();
  EXPECT_EQ(ordered.value(), (std::vector<std::string>{a, b, c}));
  auto r = RecordingReader::open_drive(ordered.value());
  ASSERT_TRUE(r);
  std::vector<double> stamps;
  while (const Record* rec = r.value().next()) stamps.push_back(to_seconds(std::get<CanFrame>(*rec).t - CaptureTime{}));
  EXPECT_EQ(stamps, (std::vector<double>{0, 1, 2, 3, 4, 5, 6, 7, 8}));
  EXPECT_EQ(r.value().errors().count(), 0u);
}

TEST_F(Segments, InterfaceNamesKeepTheirMeaningAcrossSegments) {
  const std::string a = segment("a", "run1", 1, 0, 2, "can1"), b = segment("b", "run1", 2, 2, 2, "can0");
  std::ofstream(fs::path(a) / kCanFile, std::ios::app) << "(1.500000) can0 18FEF100#01\n";
  const std::vector<std::string> given{a, b};
  auto r = RecordingReader::open_drive(join_segments(given).value());
  ASSERT_TRUE(r);
  std::vector<std::string> names;
  while (const Record* rec = r.value().next()) names.emplace_back(r.value().interfaces().name(std::get<CanFrame>(*rec).iface));
  EXPECT_EQ(names, (std::vector<std::string>{"can1", "can1", "can0", "can0", "can0"}));
}

TEST_F(Segments, RefusesWhatIsNotOneRun) {
  const std::string a = segment("a", "run1", 1, 0, 2), b = segment("b", "run2", 2, 2, 2), c = segment("c", "run1", 3, 4, 2),
                    d = segment("d", "run1", 1, 6, 2), plain = segment("plain", "", 0, 8, 2);
  const auto refuse = [](std::vector<std::string> paths) {
    auto r = join_segments(paths);
    return r ? std::string("joined") : r.error().field + ": " + r.error().message;
  };
  EXPECT_EQ(refuse({a, b}).rfind("recording_id: 'run2' is another drive", 0), 0u) << refuse({a, b});
  EXPECT_NE(refuse({a, c}).find("segment 2 of the drive is missing"), std::string::npos) << refuse({a, c});
  EXPECT_NE(refuse({a, d}).find("segment 1 given twice"), std::string::npos) << refuse({a, d});
  EXPECT_NE(refuse({a, plain}).find("no recording_id"), std::string::npos) << refuse({a, plain});
  EXPECT_NE(refuse({a, (dir_ / "none").string()}).find("not a recording folder"), std::string::npos);
  // One path is itself, joined or not.
  EXPECT_EQ(refuse({plain}), "joined");
}

TEST_F(Segments, ASegmentThatStartsBeforeThePreviousEndsIsReported) {
  const std::string a = segment("a", "run1", 1, 0, 5), b = segment("b", "run1", 2, 2, 3);
  const std::vector<std::string> given{a, b};
  auto r = RecordingReader::open_drive(join_segments(given).value());
  ASSERT_TRUE(r);
  std::size_t n = 0;
  while (r.value().next() != nullptr) ++n;
  EXPECT_EQ(n, 8u);
  ASSERT_EQ(r.value().errors().count(), 1u);
  EXPECT_NE(r.value().errors().kept()[0].message.find("starts before the previous one ends"), std::string::npos);
  EXPECT_EQ(r.value().errors().count_in(kCanFile), 1u);
}

}  // namespace
}  // namespace roadload::recording
