// What roadloadd's recorder spends to write each stream of a recording plain and as zstd frames:
// bytes per hour and the writer's CPU, side by side in one run, through the recorder's own
// AppendFile and FrameCompressor, a frame closed every second of the drive as the fsync interval
// closes them. The streams come from a recording (the simulator's, whose accelerometers carry
// real noise): synthetic samples would compress better than any truck's.
// usage: bench_streams RECORDING_DIR SECONDS
#include <time.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "roadload/firmware/append_file.hpp"

namespace {

using roadload::firmware::AppendFile;
using roadload::firmware::FrameCompressor;
namespace fs = std::filesystem;

double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Written {
  std::uint64_t bytes = 0;
  double cpu_s = 0;
};

// The lines written as the recorder writes them: a sync (a frame, compressed) each `per_sync` lines.
Written write(const std::vector<std::string>& lines, std::size_t per_sync, int level, const fs::path& out) {
  fs::remove(out);
  std::unique_ptr<FrameCompressor> compressor;
  if (level > 0) compressor = std::make_unique<FrameCompressor>(level, AppendFile::kBufferBytes);
  AppendFile f;
  if (!f.open(out.string(), compressor.get())) return {};
  const double t0 = thread_cpu_s();
  for (std::size_t i = 0; i < lines.size(); ++i) {
    f.append(lines[i]);
    if ((i + 1) % per_sync == 0) f.sync();
  }
  f.close();
  Written w{fs::file_size(out), thread_cpu_s() - t0};
  fs::remove(out);
  return w;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: bench_streams RECORDING_DIR SECONDS\n");
    return 64;
  }
  const fs::path dir = argv[1];
  const double seconds = std::atof(argv[2]);
  const fs::path out = fs::temp_directory_path() / ("bench-streams-" + std::to_string(::getpid()));
  std::printf("recorder streams: %s, %.0f s of driving, a frame closed each second; per hour of driving\n", dir.c_str(), seconds);
  std::printf("  %-12s %12s %12s %8s %12s %8s %10s %10s %10s\n", "stream", "plain MB/h", "zstd-1 MB/h", "ratio", "zstd-3 MB/h",
              "ratio", "CPU plain", "CPU zstd-1", "CPU zstd-3");
  for (const char* name : {"can.log", "accel.csv", "gnss.csv", "weather.csv"}) {
    std::ifstream in(dir / name);
    if (!in) continue;
    std::vector<std::string> lines;
    for (std::string l; std::getline(in, l);) lines.push_back(l + "\n");
    const std::size_t per_sync = std::max<std::size_t>(1, static_cast<std::size_t>(static_cast<double>(lines.size()) / seconds));
    const Written plain = write(lines, per_sync, 0, out), fast = write(lines, per_sync, 1, out),
                  zstd = write(lines, per_sync, 3, out);
    const double per_hour = 3600.0 / seconds;
    const auto mb_h = [&](const Written& w) { return static_cast<double>(w.bytes) * per_hour / 1e6; };
    const auto ratio = [&](const Written& w) { return static_cast<double>(plain.bytes) / static_cast<double>(w.bytes); };
    std::printf("  %-12s %12.1f %12.1f %7.2fx %12.1f %7.2fx %9.3f%% %9.3f%% %9.3f%%\n", name, mb_h(plain), mb_h(fast), ratio(fast),
                mb_h(zstd), ratio(zstd), 100 * plain.cpu_s / seconds, 100 * fast.cpu_s / seconds, 100 * zstd.cpu_s / seconds);
  }
  std::printf("  (CPU: the writer's own, as a fraction of one core while the drive is recorded in real time)\n");
  return 0;
}
