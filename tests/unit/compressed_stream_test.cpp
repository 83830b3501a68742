// The daemon's compressed streams: a zstd frame closed at every sync, so that a crash leaves whole
// frames (the open one never reached the file) and a power cut inside a frame costs that frame
// alone; the reader reads frames as it reads text, and names a cut or damaged frame.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "roadload/firmware/append_file.hpp"
#include "roadload/recording/line_reader.hpp"

namespace roadload::firmware {
namespace {

namespace fs = std::filesystem;

class CompressedStream : public testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("roadload-zst-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  static std::string line(int i) {
    return "(" + std::to_string(1000 + i) + ".000000) can0 18FEF100#" + std::to_string(i % 97) + "\n";
  }

  // Lines 0..n-1 appended, a sync after each `per_frame`; the file's bytes copied before the file
  // is closed, as a crash would leave them.
  std::string crash_after(int n, int per_frame, std::uint64_t* frames = nullptr) {
    FrameCompressor compressor(3, AppendFile::kBufferBytes);
    AppendFile f;
    EXPECT_TRUE(f.open((dir_ / "can.log.zst").string(), &compressor));
    for (int i = 0; i < n; ++i) {
      EXPECT_TRUE(f.append(line(i)));
      if ((i + 1) % per_frame == 0) {
        EXPECT_TRUE(f.sync());
      }
    }
    EXPECT_TRUE(f.flush());  // leaves the open frame where it is
    if (frames != nullptr) *frames = f.frames();
    std::ifstream in(dir_ / "can.log.zst", std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
  }

  // The lines a LineReader gives of `bytes`, and its error, if any.
  std::vector<std::string> read(const std::string& bytes, std::string* error = nullptr) {
    const fs::path copy = dir_ / "copy.zst";
    std::ofstream(copy, std::ios::binary) << bytes;
    auto r = recording::LineReader::open(copy.string());
    EXPECT_TRUE(r.ok());
    std::vector<std::string> lines;
    while (const auto l = r.value().next()) lines.emplace_back(*l);
    if (error != nullptr && r.value().error()) *error = r.value().error()->to_string();
    return lines;
  }

  fs::path dir_;
};

TEST_F(CompressedStream, ACrashLeavesTheSyncedFramesWholeAndLosesOnlyTheOpenOne) {
  std::uint64_t frames = 0;
  const std::string bytes = crash_after(2500, 1000, &frames);
  EXPECT_EQ(frames, 2u);
  std::string error;
  const auto lines = read(bytes, &error);
  EXPECT_EQ(error, "");
  ASSERT_EQ(lines.size(), 2000u);
  for (int i = 0; i < 2000; ++i) ASSERT_EQ(lines[i] + "\n", line(i)) << "line " << i + 1;
}

TEST_F(CompressedStream, AFrameCutShortCostsItsOwnLinesAndIsNamed) {
  const std::string bytes = crash_after(3000, 1000);
  std::string error;
  const auto lines = read(bytes.substr(0, bytes.size() - 100), &error);
  EXPECT_GE(lines.size(), 2000u);
  EXPECT_LT(lines.size(), 3000u);
  for (std::size_t i = 0; i < lines.size(); ++i) ASSERT_EQ(lines[i] + "\n", line(static_cast<int>(i))) << "line " << i + 1;
  EXPECT_NE(error.find("copy.zst:" + std::to_string(lines.size() + 1)), std::string::npos) << error;
  EXPECT_NE(error.find("ends inside its frame 3"), std::string::npos) << error;
}

TEST_F(CompressedStream, ADamagedFrameStopsTheStreamWithItsNumber) {
  std::string bytes = crash_after(3000, 1000);
  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x5a);
  std::string error;
  const auto lines = read(bytes, &error);
  EXPECT_LT(lines.size(), 3000u);
  EXPECT_NE(error.find("damaged compressed stream in frame"), std::string::npos) << error;
}

TEST_F(CompressedStream, ABufferThatFillsClosesAFrameWithoutASync) {
  const int n = static_cast<int>(AppendFile::kBufferBytes / line(0).size()) * 3;
  std::uint64_t frames = 0;
  const std::string bytes = crash_after(n, n + 1, &frames);
  EXPECT_GE(frames, 2u);
  const auto lines = read(bytes);
  EXPECT_GT(lines.size(), static_cast<std::size_t>(n) / 2);
  EXPECT_LT(lines.size(), static_cast<std::size_t>(n));
}

}  // namespace
}  // namespace roadload::firmware
