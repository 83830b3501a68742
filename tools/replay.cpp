// roadload replay: plays a recording's CAN frames onto a (virtual) CAN interface with their
// recorded spacing, N times faster, or as fast as the interface takes them, so that a running
// roadloadd hears the drive as a truck would send it.
#include <time.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command.hpp"
#include "files.hpp"
#include "replay_injector.hpp"
#include "roadload/can/socketcan_sender.hpp"
#include "roadload/cli/help.hpp"
#include "roadload/io/posix_time.hpp"
#include "roadload/io/replay_origin.hpp"
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

const HelpText kReplayHelp{"usage: roadload replay <recording | can.log> [options]",
                           "Sends the recording's CAN frames onto a CAN interface, in order, with their recorded spacing\n"
                           "divided by the rate; frames recorded within 1 ms of each other go out together, in one system call.\n"
                           "Meant for vcan on a bench: it transmits, which a logger on a truck never does.",
                           "--faults SPEC, comma-separated; T and D in seconds since the first frame:\n"
                           "  drop=P dup=P seed=N  lose or repeat each frame with probability P\n"
                           "  error@T              a CAN error frame\n"
                           "  busoff@T+D           bus-off: error frame, D s of silence, restarted frame\n"
                           "  tp-truncate@T        the next transport session loses its last packet\n"
                           "  gnss-outage@T+D      no GNSS fix for D s        (in roadloadd, through --origin)\n"
                           "  accel-overflow@T     an accelerometer FIFO overflow (in roadloadd, through --origin)\n"
                           "  clock-step@T=S       step the wall clock by S s (needs CAP_SYS_TIME)"};

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

struct ReplayOptions {
  std::vector<std::string> inputs;  // one recording or log, or one drive's segments
  std::string iface = "vcan0", origin, sent_log;
  io::ReplayFaults faults;
  double rate = 1.0;  // 0: as fast as the interface takes them
  bool quiet = false;
};

// --rate: 1, a positive factor or max (0).
std::optional<double> parse_rate(std::string_view text) {
  if (text == "max") return 0.0;
  const std::string t(text);
  char* end = nullptr;
  const double rate = std::strtod(t.c_str(), &end);
  if (end == t.c_str() || *end != '\0' || !(rate > 0 && rate <= 1e6)) return std::nullopt;
  return rate;
}

// --faults and --rate are read into `o` as they are checked: a spec that does not read is a usage
// error naming the option.
void add_options(CLI::App& cmd, ReplayOptions& o) {
  cmd.add_option("RECORDING", o.inputs,
                 "a recording folder or a candump -L log; several: the segments of\none roadloadd run, played as one drive")
      ->required();
  cmd.add_option("--iface", o.iface, "interface to send on (default vcan0)")->type_name("IFACE");
  cmd.add_option("--rate", "1 real time (default), N times faster, or max (as fast as the\ninterface takes)")
      ->type_name("R")
      ->each([&o](const std::string& text) {
        const auto rate = parse_rate(text);
        if (!rate) throw CLI::ValidationError("'" + text + "' is not 1, a positive factor or max");
        o.rate = *rate;
      });
  cmd.add_option("--origin", o.origin,
                 "write FILE as the first frame goes out (its recorded and capture time,\n"
                 "the rate): roadloadd --replay REC --replay-origin FILE plays the sensor\n"
                 "streams in step")
      ->type_name("FILE");
  cmd.add_option("--faults", "inject faults on the way (below)")->type_name("SPEC")->each([&o](const std::string& spec) {
    auto parsed = io::parse_replay_faults(spec);
    if (!parsed) {
      const ParseError& e = parsed.error();  // its file is "--faults", which CLI11 puts first
      throw CLI::ValidationError(e.field.empty() ? e.message : e.field + ": " + e.message);
    }
    o.faults = std::move(parsed.value());
  });
  cmd.add_option("--sent", o.sent_log, "write what went onto the bus, faults included, as a candump -L log")->type_name("FILE");
  cmd.add_flag("-q,--quiet", o.quiet, "no progress on standard error");
}

// The frames onto the bus in batches, at the recorded pace times the rate, faults injected, each
// batch also written to the --sent log.
class Replay {
 public:
  Replay(const ReplayOptions& o, can::SocketCanSender& sender, recording::OutputFile* sent)
      : o_(o), sender_(sender), sent_(sent), start_ns_(mono_ns()), next_progress_ns_(start_ns_ + kNsPerS) {
    batch_.reserve(can::SocketCanSender::kBatch);
  }

  // Nothing to stop for, or the exit status.
  std::optional<int> frame(const CanFrame& f) {
    if (first_ns_ < 0) {
      if (auto rc = start(f)) return rc;
    }
    if (o_.rate > 0) {
      const std::int64_t due = start_ns_ + static_cast<std::int64_t>(static_cast<double>(to_ns(f.t) - first_ns_) / o_.rate);
      if (!batch_.empty() && to_ns(f.t) - batch_first_ns_ > kBatchWindow_ns && !flush()) return kExitCantCreate;
      if (batch_.empty()) {
        batch_first_ns_ = to_ns(f.t);
        if (due > mono_ns()) sleep_until_ns(due);
      }
    }
    if (const auto step = injector_->clock_step_due(f.t)) {
      if (!batch_.empty() && !flush()) return kExitCantCreate;
      if (!step_wall_clock(*step)) {
        std::fprintf(stderr, "roadload replay: clock-step: %s (stepping the wall clock needs CAP_SYS_TIME)\n", std::strerror(errno));
        return kExitNoPerm;
      }
    }
    out_.clear();
    injector_->process(f, out_);
    for (const CanFrame& o : out_) {
      batch_.push_back(o);
      if (batch_.size() == can::SocketCanSender::kBatch && !flush()) return kExitCantCreate;
    }
    if (!sender_.error().empty()) return kExitCantCreate;
    return std::nullopt;
  }

  // What is left in the batch.
  void finish() {
    if (sender_.error().empty() && !batch_.empty()) flush();
  }

  void print_summary() const {
    const double wall_s = static_cast<double>(mono_ns() - start_ns_) * 1e-9;
    const auto sent = sender_.sent();
    if (!o_.quiet || !sender_.error().empty()) {
      std::fprintf(stderr, "replay: %llu frames onto %s in %.3f s (%.0f frames/s, queue full %llu times)%s%s\n",
                   static_cast<unsigned long long>(sent), o_.iface.c_str(), wall_s,
                   wall_s > 0 ? static_cast<double>(sent) / wall_s : 0.0, static_cast<unsigned long long>(sender_.waits()),
                   sender_.error().empty() ? "" : "; stopped: ", sender_.error().c_str());
    }
    if (!injector_ || o_.faults.empty()) return;
    const InjectedCounts& c = injector_->counts();
    std::fprintf(stderr,
                 "replay: faults: %llu dropped, %llu duplicated, %llu error frames, %llu silenced by bus-off, %llu transport packets "
                 "withheld\n",
                 static_cast<unsigned long long>(c.dropped), static_cast<unsigned long long>(c.duplicated),
                 static_cast<unsigned long long>(c.error_frames), static_cast<unsigned long long>(c.silenced),
                 static_cast<unsigned long long>(c.truncated));
  }

 private:
  // The first frame starts the fault clock and, with --origin, the shared timeline.
  std::optional<int> start(const CanFrame& f) {
    first_ns_ = to_ns(f.t);
    injector_.emplace(o_.faults, f.t);
    if (o_.origin.empty()) return std::nullopt;
    const io::ReplayTiming timing{f.t, capture_time_from_ns(start_ns_), o_.rate};
    if (auto e = io::write_replay_origin(o_.origin, {timing, o_.faults})) return failed("replay", *e, kExitCantCreate);
    return std::nullopt;
  }

  bool flush() {
    const bool ok = sender_.send(batch_);
    for (std::size_t i = 0; sent_ != nullptr && i < batch_.size(); ++i) {
      const std::size_t n = recording::format_candump_line(batch_[i], o_.iface, line_);
      line_[n] = '\n';
      sent_->write(std::string_view(line_, n + 1));
    }
    batch_.clear();
    // Progress once a batch, not once a frame (kBatchWindow_ns).
    if (!o_.quiet && mono_ns() >= next_progress_ns_) {
      std::fprintf(stderr, "replay: %llu frames sent\n", static_cast<unsigned long long>(sender_.sent()));
      next_progress_ns_ += kNsPerS;
    }
    return ok;
  }

  const ReplayOptions& o_;
  can::SocketCanSender& sender_;
  recording::OutputFile* sent_;
  std::vector<CanFrame> batch_, out_;
  std::int64_t start_ns_, first_ns_ = -1, next_progress_ns_;
  std::int64_t batch_first_ns_ = 0;  // the batch's first frame, recorded time (paced replays)
  std::optional<FaultInjector> injector_;
  char line_[recording::kMaxLineChars + 1];
};

int replay(const ReplayOptions& o) {
  auto reader = recording::RecordingReader::open_drive(o.inputs, recording::kCanStream);
  if (!reader) return failed("replay", reader.error(), kExitNoInput);
  auto sender = can::SocketCanSender::open(o.iface);
  if (!sender) return failed("replay", sender.error(), kExitCantCreate);
  std::optional<recording::OutputFile> sent_file;
  if (!o.sent_log.empty()) {
    auto f = recording::OutputFile::create(o.sent_log);
    if (!f) return failed("replay", f.error(), kExitCantCreate);
    sent_file.emplace(std::move(f.value()));
  }
  Replay replay(o, *sender.value(), sent_file ? &*sent_file : nullptr);
  std::optional<int> stopped;
  while (const recording::Record* r = reader.value().next()) {
    const auto* f = std::get_if<CanFrame>(r);
    if (f == nullptr) continue;
    if ((stopped = replay.frame(*f))) break;
  }
  // A bus that refused frames ends the replay with its summary; anything else ends it at once.
  if (stopped && sender.value()->error().empty()) return *stopped;
  replay.finish();
  replay.print_summary();
  if (sent_file) {
    if (auto e = sent_file->close()) return failed("replay", *e, kExitCantCreate);
  }
  if (!sender.value()->error().empty()) return kExitCantCreate;
  const auto& errors = reader.value().errors();
  if (errors.count() > 0) {
    std::fprintf(stderr, "roadload replay: %llu malformed lines skipped, first: %s\n",
                 static_cast<unsigned long long>(errors.count()), errors.kept().front().to_string().c_str());
    return kExitDataErr;
  }
  return kExitOk;
}

}  // namespace

Run add_replay(CLI::App& roadload) {
  auto o = std::make_shared<ReplayOptions>();
  CLI::App& cmd = *roadload.add_subcommand("replay",
                                           "play a recording's CAN frames onto a (virtual) CAN interface, in real time or faster");
  describe(cmd, kReplayHelp);
  add_options(cmd, *o);
  return [o] { return on_one_drive("replay", o->inputs, [&] { return replay(*o); }); };
}

}  // namespace roadload::cli
