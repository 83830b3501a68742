// roadload replay: plays a recording's CAN frames onto a (virtual) CAN interface with their
// recorded spacing, N times faster, or as fast as the interface takes them, so that a running
// roadloadd hears the drive as a truck would send it.
#include <time.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "command.hpp"
#include "options.hpp"
#include "roadload/can/socketcan_sender.hpp"
#include "roadload/io/posix_time.hpp"
#include "roadload/io/replay_origin.hpp"
#include "replay_injector.hpp"
#include "roadload/recording/candump.hpp"
#include "roadload/recording/reader.hpp"
#include "roadload/recording/writer.hpp"

namespace roadload::cli {
namespace {

// Frames recorded within this of a batch's first go out with it, at the first one's time: one clock
// read and one sendmmsg a batch. Under User-Mode Linux every clock read is a system call (about
// 50 us); one per frame held a replay to 19,000 frames/s, half of ten times a full J1939 bus. In
// the recording's time, so that no frame goes out more than 1 ms early against its neighbours'
// spacing at any rate (J1939's fastest periods are 10 ms).
constexpr std::int64_t kBatchWindow_ns = 1'000'000;

constexpr const char* kHelp =
    "usage: roadload replay <recording | can.log> [options]\n\n"
    "Sends the recording's CAN frames onto a CAN interface, in order, with their recorded spacing\n"
    "divided by the rate; frames recorded within 1 ms of each other go out together, in one system call.\n"
    "Meant for vcan on a bench: it transmits, which a logger on a truck never does.\n\n"
    "  --iface IFACE   interface to send on (default vcan0)\n"
    "  --rate R        1 real time (default), N times faster, or max (as fast as the interface takes)\n"
    "  --origin FILE   write FILE as the first frame goes out (its recorded and capture time, the rate):\n"
    "                  roadloadd --replay REC --replay-origin FILE plays the sensor streams in step\n"
    "  --faults SPEC   inject faults on the way, comma-separated; T and D in seconds since the first frame:\n"
    "                  drop=P dup=P seed=N  lose or repeat each frame with probability P\n"
    "                  error@T              a CAN error frame\n"
    "                  busoff@T+D           bus-off: error frame, D s of silence, restarted frame\n"
    "                  tp-truncate@T        the next transport session loses its last packet\n"
    "                  gnss-outage@T+D      no GNSS fix for D s        (in roadloadd, through --origin)\n"
    "                  accel-overflow@T     an accelerometer FIFO overflow (in roadloadd, through --origin)\n"
    "                  clock-step@T=S       step the wall clock by S s (needs CAP_SYS_TIME)\n"
    "  --sent FILE     write what went onto the bus, faults included, as a candump -L log\n"
    "  -q, --quiet     no progress on standard error\n"
    "  -h, --help      this text\n";

// Steps CLOCK_REALTIME as an NTP daemon stepping a gateway's clock would.
bool step_wall_clock(Nanoseconds by) {
  const timespec ts = io::to_timespec(io::read_clock(CLOCK_REALTIME) + by);
  return clock_settime(CLOCK_REALTIME, &ts) == 0;
}

std::int64_t mono_ns() { return io::read_clock(CLOCK_MONOTONIC).count(); }

void sleep_until_ns(std::int64_t t) {
  const timespec ts = io::to_timespec(Nanoseconds{t});
  clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr);
}

}  // namespace

int run_replay(Args args) {
  OptionParser p("replay", args);
  std::string input, iface = "vcan0", origin, sent_log;
  io::ReplayFaults faults;
  double rate = 1.0;  // 0: max
  bool quiet = false;
  while (p.more()) {
    if (p.flag("-h", "--help")) {
      std::fputs(kHelp, stdout);
      return kExitOk;
    }
    if (p.flag("-q", "--quiet")) {
      quiet = true;
    } else if (auto v = p.value("--iface")) {
      iface = *v;
    } else if (auto o = p.value("--origin")) {
      origin = *o;
    } else if (auto f = p.value("--faults")) {
      auto parsed = io::parse_replay_faults(*f);
      if (!parsed) return p.fail(parsed.error().to_string());
      faults = std::move(parsed.value());
    } else if (auto sl = p.value("--sent")) {
      sent_log = *sl;
    } else if (auto r = p.value("--rate")) {
      if (*r == "max") {
        rate = 0;
      } else {
        char* end = nullptr;
        const std::string text(*r);
        rate = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || !(rate > 0 && rate <= 1e6)) {
          return p.fail("--rate: '" + text + "' is not 1, a positive factor or max");
        }
      }
    } else if (auto pos = p.positional()) {
      if (!input.empty()) return p.fail("one recording at a time");
      input = *pos;
    } else {
      return p.fail_unknown();
    }
  }
  if (p.failed()) return kExitUsage;
  if (input.empty()) return p.fail("a recording is required (see --help)");

  auto reader = recording::RecordingReader::open(input, recording::kCanStream);
  if (!reader) {
    std::fprintf(stderr, "roadload replay: %s\n", reader.error().to_string().c_str());
    return kExitNoInput;
  }
  auto sender = can::SocketCanSender::open(iface);
  if (!sender) {
    std::fprintf(stderr, "roadload replay: %s\n", sender.error().to_string().c_str());
    return kExitCantCreate;
  }
  std::optional<recording::OutputFile> sent_file;
  if (!sent_log.empty()) {
    auto f = recording::OutputFile::create(sent_log);
    if (!f) {
      std::fprintf(stderr, "roadload replay: %s\n", f.error().to_string().c_str());
      return kExitCantCreate;
    }
    sent_file.emplace(std::move(f.value()));
  }
  std::vector<CanFrame> batch, out;
  batch.reserve(can::SocketCanSender::kBatch);
  const std::int64_t start_ns = mono_ns();
  std::int64_t first_ns = -1, next_progress_ns = start_ns + 1'000'000'000;
  std::int64_t batch_first_ns = 0;  // the batch's first frame, recorded time (paced replays)
  std::optional<FaultInjector> injector;
  char line[recording::kMaxLineChars + 1];
  auto flush = [&]() {
    const bool ok = sender.value()->send(batch);
    for (std::size_t i = 0; sent_file && i < batch.size(); ++i) {
      const std::size_t n = recording::format_candump_line(batch[i], iface, line);
      line[n] = '\n';
      sent_file->write(std::string_view(line, n + 1));
    }
    batch.clear();
    // Progress once a batch, not once a frame (kBatchWindow_ns).
    if (!quiet && mono_ns() >= next_progress_ns) {
      std::fprintf(stderr, "replay: %llu frames sent\n", static_cast<unsigned long long>(sender.value()->sent()));
      next_progress_ns += 1'000'000'000;
    }
    return ok;
  };
  while (const recording::Record* r = reader.value().next()) {
    const auto* f = std::get_if<CanFrame>(r);
    if (f == nullptr) continue;
    if (first_ns < 0) {
      first_ns = to_ns(f->t);
      injector.emplace(faults, f->t);
      if (!origin.empty()) {
        const io::ReplayTiming timing{f->t, capture_time_from_ns(start_ns), rate};
        if (auto e = io::write_replay_origin(origin, {timing, faults})) {
          std::fprintf(stderr, "roadload replay: %s\n", e->to_string().c_str());
          return kExitCantCreate;
        }
      }
    }
    if (rate > 0) {
      const std::int64_t due = start_ns + static_cast<std::int64_t>(static_cast<double>(to_ns(f->t) - first_ns) / rate);
      if (!batch.empty() && to_ns(f->t) - batch_first_ns > kBatchWindow_ns && !flush()) break;
      if (batch.empty()) {
        batch_first_ns = to_ns(f->t);
        if (due > mono_ns()) sleep_until_ns(due);
      }
    }
    if (const auto step = injector->clock_step_due(f->t)) {
      if (!batch.empty() && !flush()) break;
      if (!step_wall_clock(*step)) {
        std::fprintf(stderr, "roadload replay: clock-step: %s (stepping the wall clock needs CAP_SYS_TIME)\n", std::strerror(errno));
        return kExitNoPerm;
      }
    }
    out.clear();
    injector->process(*f, out);
    for (const CanFrame& o : out) {
      batch.push_back(o);
      if (batch.size() == can::SocketCanSender::kBatch && !flush()) break;
    }
    if (!sender.value()->error().empty()) break;
  }
  if (sender.value()->error().empty() && !batch.empty()) flush();
  const double wall_s = static_cast<double>(mono_ns() - start_ns) * 1e-9;
  const auto sent = sender.value()->sent();
  if (!quiet || !sender.value()->error().empty()) {
    std::fprintf(stderr, "replay: %llu frames onto %s in %.3f s (%.0f frames/s, queue full %llu times)%s%s\n",
                 static_cast<unsigned long long>(sent), iface.c_str(), wall_s,
                 wall_s > 0 ? static_cast<double>(sent) / wall_s : 0.0,
                 static_cast<unsigned long long>(sender.value()->waits()),
                 sender.value()->error().empty() ? "" : "; stopped: ", sender.value()->error().c_str());
  }
  if (injector && !faults.empty()) {
    const InjectedCounts& c = injector->counts();
    std::fprintf(stderr, "replay: faults: %llu dropped, %llu duplicated, %llu error frames, %llu silenced by bus-off, %llu transport packets withheld\n",
                 static_cast<unsigned long long>(c.dropped), static_cast<unsigned long long>(c.duplicated),
                 static_cast<unsigned long long>(c.error_frames), static_cast<unsigned long long>(c.silenced),
                 static_cast<unsigned long long>(c.truncated));
  }
  if (sent_file) {
    if (auto e = sent_file->close()) {
      std::fprintf(stderr, "roadload replay: %s\n", e->to_string().c_str());
      return kExitCantCreate;
    }
  }
  if (!sender.value()->error().empty()) return kExitCantCreate;
  if (reader.value().errors().count() > 0) {
    const auto& e = reader.value().errors();
    std::fprintf(stderr, "roadload replay: %llu malformed lines skipped, first: %s\n",
                 static_cast<unsigned long long>(e.count()), e.kept().front().to_string().c_str());
    return kExitDataErr;
  }
  return kExitOk;
}

}  // namespace roadload::cli
