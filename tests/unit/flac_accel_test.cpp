// The accelerometers as FLAC: what the recorder's encoder writes, libFLAC reads back bit for bit
// (counts and stamps), `flac -t` accepts, and damage is reported rather than read as data.
#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>

#include "roadload/recording/flac_accel.hpp"
#include "roadload/recording/flac_encoder.hpp"
#include "roadload/recording/reader.hpp"
#include "roadload/recording/writer.hpp"

namespace roadload::recording {
namespace {

namespace fs = std::filesystem;

constexpr double kStep2g = 2 * 9.80665 / (1 << 19);
constexpr double kStep8g = 8 * 9.80665 / (1 << 19);
constexpr std::size_t kBlock = FlacEncoder::kMaxBlock;

fs::path fresh_dir(const char* tag) {
  const fs::path d = fs::temp_directory_path() / ("roadload-flac-" + std::to_string(::getpid()) + "-" + tag);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// A sensor's samples as a driver gives them: counts times the step, stamped on a clock with jitter.
std::vector<AccelSample> drive(std::uint8_t sensor, double step, std::int64_t t0_ns, std::int64_t period_ns, std::size_t n,
                               unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 150.0);
  std::uniform_int_distribution<int> jitter(-3, 3);
  std::vector<AccelSample> out;
  for (std::size_t i = 0; i < n; ++i) {
    const double wave = 4000.0 * std::sin(static_cast<double>(i) * 0.01);
    AccelSample s;
    s.t = capture_time_from_ns(t0_ns + static_cast<std::int64_t>(i) * period_ns + jitter(rng));
    s.sensor = sensor;
    s.x_mps2 = std::round(noise(rng)) * step;
    s.y_mps2 = std::round(wave + noise(rng)) * step;
    s.z_mps2 = std::round(9.80665 / step + noise(rng)) * step;
    out.push_back(s);
  }
  return out;
}

std::vector<AccelSample> read_all(const fs::path& dir, ErrorLog* errors = nullptr) {
  auto r = RecordingReader::open(dir.string());
  EXPECT_TRUE(r.ok()) << r.error().to_string();
  std::vector<AccelSample> out;
  if (!r.ok()) return out;
  while (const Record* rec = r.value().next()) out.push_back(std::get<AccelSample>(*rec));
  if (errors != nullptr) *errors = r.value().errors();
  return out;
}

void write_sensor(const fs::path& path, std::uint8_t sensor, double step, const std::vector<AccelSample>& samples) {
  auto w = AccelFlacWriter::create(path.string(), sensor, 4000, step);
  ASSERT_TRUE(w.ok()) << w.error().to_string();
  for (const AccelSample& s : samples) ASSERT_FALSE(w.value().write(s).has_value());
  ASSERT_FALSE(w.value().close().has_value());
}

void expect_same(const AccelSample& a, const AccelSample& b, std::size_t i) {
  EXPECT_EQ(a.t, b.t) << "sample " << i;
  EXPECT_EQ(a.sensor, b.sensor) << "sample " << i;
  EXPECT_EQ(a.x_mps2, b.x_mps2) << "sample " << i;
  EXPECT_EQ(a.y_mps2, b.y_mps2) << "sample " << i;
  EXPECT_EQ(a.z_mps2, b.z_mps2) << "sample " << i;
}

TEST(FlacAccel, TwoSensorsReadBackExactlyMergedByStamp) {
  const fs::path dir = fresh_dir("two");
  // Stamps cross whole seconds (the nanosecond channel wraps) and several full blocks.
  const auto a = drive(0, kStep2g, 999'000'000, 250'000, 10'000, 1);
  const auto b = drive(5, kStep8g, 999'000'000, 250'000, 9'000, 2);
  write_sensor(dir / accel_flac_file(0), 0, kStep2g, a);
  write_sensor(dir / accel_flac_file(5), 5, kStep8g, b);
  std::vector<AccelSample> want(a);
  want.insert(want.end(), b.begin(), b.end());
  std::stable_sort(want.begin(), want.end(), [](const AccelSample& l, const AccelSample& r) { return l.t < r.t; });
  ErrorLog errors;
  const auto got = read_all(dir, &errors);
  EXPECT_EQ(errors.count(), 0U);
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) expect_same(got[i], want[i], i);
  // The text it stands for is at least eight times larger (the goal of issue 27).
  const auto flac_bytes = fs::file_size(dir / accel_flac_file(0));
  EXPECT_LT(flac_bytes * 8, a.size() * std::string_view("1000250000,0,-0.001234,0.123456,9.806650\n").size());
  if (std::system("command -v flac >/dev/null") == 0) {
    EXPECT_EQ(std::system(("flac -t -s " + (dir / accel_flac_file(0)).string() + " 2>/dev/null").c_str()), 0);
  }
  fs::remove_all(dir);
}

TEST(FlacAccel, ExtremesUseVerbatimAndEscapedPartitionsAndStillReadBack) {
  const fs::path dir = fresh_dir("extremes");
  std::vector<AccelSample> s;
  // Full-scale steps, a constant channel, a stamp near 2^31 s and a jump of a day: every coding path.
  for (int i = 0; i < 5000; ++i) {
    AccelSample a;
    const std::int64_t day = i >= 2500 ? 86'400'000'000'000 : 0;
    a.t = capture_time_from_ns(2'147'000'000'000'000'000 + day + i * 250'000);
    a.sensor = 9;
    a.x_mps2 = ((i % 2) != 0 ? 524287 : -524288) * kStep2g;
    a.y_mps2 = 0;
    a.z_mps2 = (i % 97 == 0 ? 300000 : -2) * kStep2g;
    s.push_back(a);
  }
  write_sensor(dir / accel_flac_file(9), 9, kStep2g, s);
  const auto got = read_all(dir);
  ASSERT_EQ(got.size(), s.size());
  for (std::size_t i = 0; i < got.size(); ++i) expect_same(got[i], s[i], i);
  fs::remove_all(dir);
}

TEST(FlacAccel, AValueThatIsNotAWholeStepIsAnErrorNamingTheSample) {
  const fs::path dir = fresh_dir("step");
  auto w = AccelFlacWriter::create((dir / accel_flac_file(1)).string(), 1, 4000, kStep2g);
  ASSERT_TRUE(w.ok());
  EXPECT_FALSE(w.value().write({capture_time_from_ns(1000), 1, 3 * kStep2g, 0, 0}).has_value());
  const auto e = w.value().write({capture_time_from_ns(2000), 1, 0, 0.1234567, 0});
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->field, "sample 2 y");
  EXPECT_NE(e->file.find("accel-1.flac"), std::string::npos);
  fs::remove_all(dir);
}

TEST(FlacAccel, ADamagedFrameIsReportedAndOnlyWhatWasWrittenIsRead) {
  const fs::path dir = fresh_dir("damaged");
  const auto a = drive(2, kStep2g, 1'000'000'000, 250'000, 5 * kBlock, 3);  // five full frames
  const fs::path path = dir / accel_flac_file(2);
  write_sensor(path, 2, kStep2g, a);
  {
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    const auto size = static_cast<std::streamoff>(fs::file_size(path));
    f.seekp(size * 3 / 10);  // inside the second frame
    f.put('\x5A');
  }
  ErrorLog errors;
  const auto got = read_all(dir, &errors);
  EXPECT_GE(errors.count(), 1U);
  // A frame has no length: a damaged one can take the next with it as the decoder finds its way
  // back. Whatever is read is what was written, in order; the frames before and the last are read.
  ASSERT_LT(got.size(), a.size());
  ASSERT_GE(got.size(), 2 * kBlock);
  std::size_t j = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    while (j < a.size() && a[j].t != got[i].t) ++j;
    ASSERT_LT(j, a.size()) << "sample " << i << " was never written";
    expect_same(got[i], a[j], i);
  }
  for (std::size_t i = 0; i < kBlock; ++i) expect_same(got[i], a[i], i);
  expect_same(got.back(), a.back(), got.size() - 1);
  fs::remove_all(dir);
}

TEST(FlacAccel, AFileCutInsideAFrameReadsEveryWholeFrameAndSaysSo) {
  const fs::path dir = fresh_dir("cut");
  const auto a = drive(4, kStep2g, 1'000'000'000, 250'000, 4 * kBlock + kBlock / 2, 4);
  const fs::path path = dir / accel_flac_file(4);
  write_sensor(path, 4, kStep2g, a);
  fs::resize_file(path, fs::file_size(path) - 100);  // into the last frame, as a power cut leaves it
  ErrorLog errors;
  const auto got = read_all(dir, &errors);
  EXPECT_EQ(got.size(), 4 * kBlock);  // the whole frames before the cut one
  EXPECT_GE(errors.count(), 1U);
  for (std::size_t i = 0; i < got.size(); ++i) expect_same(got[i], a[i], i);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace roadload::recording
