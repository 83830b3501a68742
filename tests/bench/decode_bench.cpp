// Parse + decode throughput of a large candump log against `wc -l` of the same file, the floor
// any line-oriented reader pays. Prints figures; it does not pass or fail.
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "roadload/definitions.hpp"
#include "roadload/j1939/assembler.hpp"
#include "roadload/recording/candump.hpp"
#include "roadload/recording/reader.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Repeats a real trace with stamps shifted forward so the file looks like one long drive.
std::uint64_t make_log(const std::string& trace, const std::string& out, std::uint64_t frames) {
  std::ifstream in(trace);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  std::FILE* f = std::fopen(out.c_str(), "w");
  if (f == nullptr || lines.empty()) {
    std::fprintf(stderr, "bench: cannot read %s or write %s\n", trace.c_str(), out.c_str());
    std::exit(1);
  }
  roadload::recording::InterfaceTable ifaces;
  roadload::CanFrame frame;
  roadload::recording::LineResult result;
  char buf[roadload::recording::kMaxLineChars];
  const std::int64_t span_ns = 200'000'000'000;
  std::uint64_t written = 0;
  for (std::int64_t pass = 0; written < frames; ++pass) {
    for (const std::string& l : lines) {
      if (written == frames) break;
      if (roadload::recording::parse_candump_line(l, ifaces, frame, result)) continue;
      frame.t += roadload::Nanoseconds{pass * span_ns};
      const std::size_t n = roadload::recording::format_candump_line(frame, ifaces.name(frame.iface), buf);
      buf[n] = '\n';
      std::fwrite(buf, 1, n + 1, f);
      ++written;
    }
  }
  std::fclose(f);
  return written;
}

double time_wc(const std::string& path) {
  const auto t0 = Clock::now();
  const std::string cmd = "wc -l < '" + path + "' > /dev/null";
  if (std::system(cmd.c_str()) != 0) std::fprintf(stderr, "bench: wc failed\n");
  return seconds_since(t0);
}

}  // namespace

int main(int argc, char** argv) {
  const std::uint64_t want = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 5'000'000;
  const std::string trace = argc > 2 ? argv[2] : ROADLOAD_TEST_DATA "/traces/css-truck-idle.log";
  const std::string path = "/tmp/roadload-bench-decode.log";
  const std::uint64_t frames = make_log(trace, path, want);

  roadload::j1939::Database db;
  if (auto e = roadload::load_dbc_file(db, ROADLOAD_CONFIG_DIR "/j1939-core.dbc")) {
    std::fprintf(stderr, "bench: %s\n", e->to_string().c_str());
    return 1;
  }
  time_wc(path);  // warm the page cache for both runs alike
  const double wc_s = time_wc(path);

  const auto tp = Clock::now();
  {
    auto only = roadload::recording::CandumpStream::open(path);
    roadload::recording::ErrorLog errs;
    roadload::CanFrame g;
    while (only.value()->next_frame(g, errs)) {
    }
  }
  const double parse_s = seconds_since(tp);

  const auto t0 = Clock::now();
  auto stream = roadload::recording::CandumpStream::open(path);
  roadload::recording::ErrorLog errors;
  roadload::j1939::MessageAssembler assembler;
  roadload::CanFrame f;
  std::uint64_t parsed = 0, values = 0;
  double checksum = 0;
  while (stream.value()->next_frame(f, errors)) {
    ++parsed;
    const auto m = assembler.push(f);
    if (!m) continue;
    const roadload::j1939::MessageDef* def = db.find(m->pgn);
    if (def == nullptr) continue;
    for (const auto& s : def->signals) {
      const auto r = roadload::j1939::decode(s, m->data);
      if (r.state == roadload::j1939::SignalState::valid) {
        checksum += r.value;
        ++values;
      }
    }
  }
  const double decode_s = seconds_since(t0);
  std::remove(path.c_str());

  const double fps = static_cast<double>(parsed) / decode_s;
  std::printf("decode benchmark: %" PRIu64 " frames (%" PRIu64 " signal values, %" PRIu64 " errors, checksum %.6g)\n", parsed, values,
              errors.count(), checksum);
  std::printf("  wc -l          %8.3f s\n", wc_s);
  std::printf("  parse only     %8.3f s   %.2f M frames/s   ratio to wc -l %.1fx\n", parse_s,
              static_cast<double>(parsed) / parse_s / 1e6, parse_s / wc_s);
  std::printf("  parse+decode   %8.3f s   %.2f M frames/s   ratio to wc -l %.1fx   (goals: >= 2 M frames/s, <= 5x)\n", decode_s,
              fps / 1e6, decode_s / wc_s);
  std::printf("  8-hour drive at full 500 kbit/s (110 M frames): %.1f s projected (goal < 60 s)\n", 110e6 / fps);
  return frames == parsed && errors.count() == 0 ? 0 : 1;
}
