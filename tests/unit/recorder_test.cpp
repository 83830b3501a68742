// The daemon's recorder: segments that read back as recordings, rotation by size, the quota, and a
// write failure (the disk full) reported, survived and recovered from with every line accounted for.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>

#include <filesystem>
#include <vector>

#include "roadload/firmware/recorder.hpp"
#include "roadload/recording/flac_accel.hpp"
#include "roadload/recording/reader.hpp"
#include "scratch.hpp"

namespace roadload::firmware {
namespace {

namespace fs = std::filesystem;

std::string fresh_dir(const char* name) {
  const auto dir = test::scratch_path(name);
  fs::remove_all(dir);
  return dir.string();
}

CanFrame frame(std::int64_t i) {
  CanFrame f;
  f.t = capture_time_from_ns(1'000'000'000 + i * 250'000);
  f.id = 0x18FEF100u | static_cast<std::uint32_t>(i & 0xFF);
  f.len = 8;
  for (std::size_t b = 0; b < 8; ++b) f.data[b] = static_cast<std::uint8_t>(i >> (8 * (b % 4)));
  return f;
}

std::vector<fs::path> segments(const std::string& dir) {
  std::vector<fs::path> out(fs::directory_iterator(dir), {});
  std::sort(out.begin(), out.end());
  return out;
}

std::size_t frames_in(const fs::path& segment) {
  auto r = recording::RecordingReader::open(segment.string());
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().to_string());
  std::size_t n = 0;
  while (r.value().next() != nullptr) ++n;
  EXPECT_EQ(r.value().errors().count(), 0u);
  return n;
}

// 20,000 frames 0.25 ms apart, the recorder's clock ticked 25 ms every 100 of them.
void record_drive(Recorder& rec) {
  CaptureTime now = capture_time_from_ns(0);
  rec.tick(now);
  for (std::int64_t i = 0; i < 20'000; ++i) {
    rec.write(frame(i));
    if (i % 100 == 0) rec.tick(now += Nanoseconds{25'000'000});
  }
}

// Each test runs on plain text and on zstd frames; sizes that must be reached are smaller for the
// frames, which these counting payloads shrink about tenfold.
class RecorderStreams : public testing::TestWithParam<int> {
 protected:
  RecorderConfig config(const char* name) const {
    RecorderConfig c;
    c.data_dir = fresh_dir(name);
    c.compression_level = GetParam();
    return c;
  }
  std::uint64_t bytes(std::uint64_t plain) const { return GetParam() == 0 ? plain : plain / 4; }
};

INSTANTIATE_TEST_SUITE_P(PlainAndZstd, RecorderStreams, testing::Values(0, 3), [](const testing::TestParamInfo<int>& i) {
  return i.param == 0 ? std::string("Plain") : std::string("Zstd");
});

TEST_P(RecorderStreams, SegmentsRotateBySizeAndReadBackWhole) {
  RecorderConfig c = config("recorder-rotate");
  c.segment_max_bytes = bytes(200'000);
  Recorder rec(c, recording::Metadata{}, {"can0"});
  record_drive(rec);
  rec.end_segment();
  const auto segs = segments(c.data_dir);
  ASSERT_GE(segs.size(), 4u);
  std::size_t total = 0;
  for (const auto& s : segs) {
    EXPECT_TRUE(fs::exists(s / "meta.toml"));
    EXPECT_TRUE(fs::exists(s / (GetParam() == 0 ? "can.log" : "can.log.zst"))) << s;
    total += frames_in(s);
  }
  EXPECT_EQ(total, 20'000u);
  EXPECT_EQ(rec.status().lines, 20'000u);
  EXPECT_EQ(rec.status().lines_lost, 0u);
}

// The segments of one run carry its id and their places in it, so they join back into the drive:
// given in reverse, every frame comes back once and in order.
TEST_P(RecorderStreams, SegmentsOfOneRunJoinIntoTheWholeDrive) {
  RecorderConfig c = config("recorder-join");
  c.segment_max_bytes = bytes(200'000);
  {
    Recorder rec(c, recording::Metadata{}, {"can0"});
    record_drive(rec);
  }
  std::vector<std::string> given;
  for (const auto& s : segments(c.data_dir)) given.insert(given.begin(), s.string());
  ASSERT_GE(given.size(), 4u);
  auto ordered = recording::join_segments(given);
  ASSERT_TRUE(ordered) << ordered.error().to_string();
  auto r = recording::RecordingReader::open_drive(ordered.value());
  ASSERT_TRUE(r);
  EXPECT_FALSE(r.value().metadata().recording_id.empty());
  EXPECT_EQ(r.value().metadata().segment, 1);
  std::int64_t i = 0;
  while (const auto* rec = r.value().next()) {
    const auto* f = std::get_if<CanFrame>(rec);
    ASSERT_NE(f, nullptr);
    ASSERT_EQ(f->t, frame(i).t) << "frame " << i;
    ++i;
  }
  EXPECT_EQ(i, 20'000);
  EXPECT_EQ(r.value().errors().count(), 0u);
  EXPECT_EQ(r.value().streams().at(0)->counts().records, 20'000u);

  // A second run's segment is another drive.
  Recorder second(c, recording::Metadata{}, {"can0"});
  second.tick(capture_time_from_ns(0));
  second.write(frame(30'000));
  second.end_segment();
  const auto all = segments(c.data_dir);
  const std::vector<std::string> mixed{all.front().string(), all.back().string()};
  auto refused = recording::join_segments(mixed);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().field, "recording_id") << refused.error().to_string();
}

TEST_P(RecorderStreams, QuotaDeletesTheOldestSegments) {
  RecorderConfig c = config("recorder-quota");
  c.segment_max_bytes = bytes(100'000);
  c.quota_bytes = bytes(300'000);
  Recorder rec(c, recording::Metadata{}, {"can0"});
  CaptureTime now = capture_time_from_ns(0);
  for (std::int64_t i = 0; i < 40'000; ++i) {
    rec.write(frame(i));
    if (i % 100 == 0) rec.tick(now += Nanoseconds{25'000'000});
  }
  rec.end_segment();
  rec.tick(now);
  std::uint64_t in_dir = 0;
  for (const auto& e : fs::recursive_directory_iterator(c.data_dir))
    if (e.is_regular_file()) in_dir += e.file_size();
  EXPECT_LE(in_dir, c.quota_bytes + 50'000);  // plus the new segment's meta.toml and headers
  EXPECT_GT(rec.status().segments_deleted, 0u);
  // The newest segments stay: the last frame written is on disk.
  const auto segs = segments(c.data_dir);
  ASSERT_FALSE(segs.empty());
  EXPECT_EQ(segs.front().filename().string().substr(0, 6) > "000001", true);
}

// RLIMIT_FSIZE makes writes past a size fail as a full disk would (EFBIG instead of ENOSPC).
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &old_);
    signal(SIGXFSZ, SIG_IGN);
    rlimit l = old_;
    l.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &l);
  }
  ~FileSizeLimit() { setrlimit(RLIMIT_FSIZE, &old_); }

 private:
  rlimit old_{};
};

TEST_P(RecorderStreams, WriteFailureIsReportedAndEveryLineAccountedFor) {
  RecorderConfig c = config("recorder-full");
  Recorder rec(c, recording::Metadata{}, {"can0"});
  CaptureTime now = capture_time_from_ns(0);
  rec.tick(now);
  constexpr std::int64_t kFrames = 30'000;  // 1.5 MB of lines: more than the buffer holds
  std::int64_t i = 0;
  {
    const FileSizeLimit limit(bytes(100'000) / (GetParam() == 0 ? 1 : 4));
    for (; i < kFrames / 2; ++i) {
      rec.write(frame(i));
      if (i % 100 == 0) rec.tick(now += Nanoseconds{25'000'000});
    }
    EXPECT_NE(rec.status().error, 0);
    EXPECT_NE(rec.status().error_text.find("can.log"), std::string::npos) << rec.status().error_text;
  }
  for (; i < kFrames; ++i) {
    rec.write(frame(i));
    if (i % 100 == 0) rec.tick(now += Nanoseconds{25'000'000});
  }
  rec.tick(now += Nanoseconds{2'000'000'000});
  EXPECT_EQ(rec.status().error, 0) << rec.status().error_text;
  rec.end_segment();
  const auto segs = segments(c.data_dir);
  ASSERT_EQ(segs.size(), 1u);
  const std::size_t on_disk = frames_in(segs[0]);
  EXPECT_GT(rec.status().lines_lost, 0u);
  EXPECT_EQ(on_disk + rec.status().lines_lost, static_cast<std::size_t>(kFrames));
}

// Accelerometers with a known step go to their FLAC files, the others to accel.csv beside them.
constexpr double kStep = 9.80665 / 256000;

AccelSample accel(std::uint8_t sensor, std::int64_t i) {
  const double count = static_cast<double>((i * 7919 + sensor * 104729) % 20001 - 10000);
  return {capture_time_from_ns(1'000'000'000 + i * 250'000 + sensor), sensor, count * kStep, -count * kStep,
          (256000 + count) * kStep};
}

std::vector<AccelSample> accel_read(const std::vector<fs::path>& segs, std::uint64_t* errors = nullptr) {
  std::vector<std::string> paths;
  for (const auto& s : segs) paths.push_back(s.string());
  auto r = recording::RecordingReader::open_drive(paths);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().to_string());
  std::vector<AccelSample> out;
  if (!r.ok()) return out;
  while (const auto* rec = r.value().next()) out.push_back(std::get<AccelSample>(*rec));
  if (errors != nullptr) *errors = r.value().errors().count();
  return out;
}

TEST_P(RecorderStreams, AccelerometersWithAStepGoToFlacAcrossSegments) {
  RecorderConfig c = config("recorder-flac");
  c.segment_max = Nanoseconds{3'000'000'000};
  c.accel_flac = {{0, 4000, kStep}, {3, 4000, kStep}};
  Recorder rec(c, recording::Metadata{}, {"can0"});
  CaptureTime now = capture_time_from_ns(0);
  rec.tick(now);
  constexpr std::int64_t kSamples = 30'000;  // 7.5 s at 4 kHz
  for (std::int64_t i = 0; i < kSamples; ++i) {
    for (const std::uint8_t sensor : std::array<std::uint8_t, 3>{0, 3, 5}) rec.write(accel(sensor, i));
    if (i % 100 == 0) rec.tick(now += Nanoseconds{25'000'000});
  }
  // Off the sensor's steps: cannot be stored as counts, and is counted.
  rec.write(AccelSample{capture_time_from_ns(9'000'000'000), 0, 0.1, 0, 0});
  rec.end_segment();
  const auto segs = segments(c.data_dir);
  ASSERT_GE(segs.size(), 3u);
  EXPECT_TRUE(fs::exists(segs[0] / "accel-0.flac"));
  EXPECT_TRUE(fs::exists(segs[0] / "accel-3.flac"));
  EXPECT_TRUE(fs::exists(segs[0] / (GetParam() == 0 ? "accel.csv" : "accel.csv.zst")));
  EXPECT_EQ(rec.status().lines, 3u * kSamples);
  EXPECT_EQ(rec.status().lines_lost, 1u);
  // The drive reads back whole: the FLAC sensors exactly, the text one to its six decimals.
  std::uint64_t errors = 0;
  const auto got = accel_read(segs, &errors);
  EXPECT_EQ(errors, 0u);
  ASSERT_EQ(got.size(), 3u * kSamples);
  std::vector<std::int64_t> seen(6, 0);
  for (const AccelSample& a : got) {
    ASSERT_TRUE(a.sensor == 0 || a.sensor == 3 || a.sensor == 5);
    const AccelSample want = accel(a.sensor, seen[a.sensor]++);
    ASSERT_EQ(a.t, want.t);
    const double tolerance = a.sensor == 5 ? 1e-6 : 0.0;  // six decimals, rounded
    ASSERT_NEAR(a.x_mps2, want.x_mps2, tolerance);
    ASSERT_NEAR(a.z_mps2, want.z_mps2, tolerance);
  }
}

// What a power cut leaves: every file as it is on disk after an fsync, the recorder still running.
TEST_P(RecorderStreams, AFlacStreamOnDiskHoldsEverySampleUpToTheLastSync) {
  RecorderConfig c = config("recorder-flac-cut");
  c.fsync_interval = Nanoseconds{500'000'000};
  c.accel_flac = {{0, 4000, kStep}};
  Recorder rec(c, recording::Metadata{}, {"can0"});
  CaptureTime now = capture_time_from_ns(0);
  rec.tick(now);
  std::size_t synced = 0;
  for (std::int64_t i = 0; i < 10'050; ++i) {  // the last 50 after the last fsync
    rec.write(accel(0, i));
    if (i % 100 == 99) {
      rec.tick(now += Nanoseconds{25'000'000});
      if (i % 2000 == 1999) synced = static_cast<std::size_t>(i + 1);  // every 20 ticks: 500 ms, an fsync
    }
  }
  const auto segs = segments(c.data_dir);
  ASSERT_EQ(segs.size(), 1u);
  std::uint64_t errors = 0;
  const auto on_disk = accel_read(segs, &errors);
  EXPECT_EQ(errors, 0u);
  EXPECT_GE(on_disk.size(), synced);
  EXPECT_LT(on_disk.size(), synced + recording::FlacEncoder::kMaxBlock);
  for (std::size_t i = 0; i < on_disk.size(); ++i) ASSERT_EQ(on_disk[i].t, accel(0, static_cast<std::int64_t>(i)).t);
}

}  // namespace
}  // namespace roadload::firmware
