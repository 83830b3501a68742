// roadload decode: what a recording's CAN log says, as signals, transport messages or statistics.
#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include <CLI/CLI.hpp>

#include "command.hpp"
#include "files.hpp"
#include "roadload/cli/help.hpp"
#include "roadload/cli/values.hpp"
#include "roadload/j1939/assembler.hpp"
#include "roadload/j1939/cadence.hpp"
#include "roadload/j1939/database.hpp"
#include "roadload/recording/read_ahead.hpp"
#include "roadload/recording/reader.hpp"

namespace roadload::cli {
namespace {

const HelpText kDecodeHelp{"usage: roadload decode [options] <recording-folder | can.log>...",
                           "Prints the J1939 signals of every message the definitions know, one line per message.",
                           "A summary of frame kinds, skipped lines, transport counters and the frames that the J1939 cadence\n"
                           "judges lost or repeated (the count roadloadd's status gives, over the same stamps) goes to\n"
                           "standard error.\n"
                           "Malformed lines are reported with file, line and field and make the exit status 65.\n"
                           "Of a recording folder only can.log is read. The log is read and parsed on a second thread, a batch\n"
                           "ahead of the decoding."};

struct DecodeOptions {
  bool pgn_stats = false;
  bool tp_only = false;
  std::vector<std::string> dbcs;
  std::vector<j1939::Pgn> only;
  std::vector<std::string> inputs;  // one recording or log, or one drive's segments
};

struct PgnStats {
  std::uint64_t frames = 0;
  std::uint64_t tp_messages = 0;
  std::array<bool, 256> sources{};
  CaptureTime first{};
  CaptureTime last{};
};

// The statistics indexed by the PGN itself (18 bits): a hash lookup per frame cost 7 % of a decode.
class PgnTable {
 public:
  PgnStats& operator[](j1939::Pgn pgn) {
    std::uint32_t& i = index_[pgn & kPgnMask];
    if (i == 0) {
      stats_.emplace_back(pgn, PgnStats{});
      i = static_cast<std::uint32_t>(stats_.size());
    }
    return stats_[i - 1].second;
  }
  // In PGN order.
  std::vector<std::pair<j1939::Pgn, PgnStats>> sorted() const {
    auto out = stats_;
    std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    return out;
  }

 private:
  static constexpr j1939::Pgn kPgnMask = 0x3FFFF;
  std::vector<std::uint32_t> index_ = std::vector<std::uint32_t>(kPgnMask + 1);  // 1 + place in stats_; 0: none
  std::vector<std::pair<j1939::Pgn, PgnStats>> stats_;
};

struct KindCounts {
  std::uint64_t extended = 0, standard = 0, remote = 0, error = 0, fd = 0;
  void add(CanFrameKind k) {
    switch (k) {
      case CanFrameKind::extended: ++extended; break;
      case CanFrameKind::standard: ++standard; break;
      case CanFrameKind::remote: ++remote; break;
      case CanFrameKind::error: ++error; break;
      case CanFrameKind::fd: ++fd; break;
    }
  }
  std::uint64_t total() const { return extended + standard + remote + error + fd; }
};

void print_stamp(std::FILE* out, CaptureTime t) {
  const std::int64_t ns = to_ns(t);
  std::fprintf(out, "(%010" PRId64 ".%06" PRId64 ")", ns / 1'000'000'000, (ns % 1'000'000'000) / 1000);
}

void print_signals(std::FILE* out, const j1939::Message& m, const j1939::MessageDef& def, const recording::InterfaceTable& ifaces) {
  print_stamp(out, m.t);
  const std::string_view iface = ifaces.name(m.iface);
  std::fprintf(out, " %.*s %02X %s", static_cast<int>(iface.size()), iface.data(), m.sa, def.name.c_str());
  for (const j1939::SignalDef& s : def.signals) {
    const j1939::SignalReading r = j1939::decode(s, m.data);
    if (r.state == j1939::SignalState::missing) continue;
    if (r.state == j1939::SignalState::valid) {
      std::fprintf(out, " %s=%.10g%s", s.name.c_str(), r.value, s.unit.c_str());
    } else {
      std::fprintf(out, " %s=%s", s.name.c_str(), j1939::to_string(r.state));
    }
  }
  std::fputc('\n', out);
}

void print_tp(std::FILE* out, const j1939::Message& m, const recording::InterfaceTable& ifaces) {
  print_stamp(out, m.t);
  const std::string_view iface = ifaces.name(m.iface);
  std::fprintf(out, " %.*s TP pgn=%u sa=0x%02x da=0x%02x len=%zu data=", static_cast<int>(iface.size()), iface.data(), m.pgn, m.sa,
               m.da, m.data.size());
  for (std::uint8_t b : m.data) std::fprintf(out, "%02x", b);
  std::fputc('\n', out);
}

void print_pgn_stats(std::FILE* out, const PgnTable& stats, const j1939::Database& db) {
  std::fprintf(out, "pgn,name,frames,sources,mean_period_ms,tp_messages\n");
  for (const auto& [pgn, s] : stats.sorted()) {
    const j1939::MessageDef* def = db.find(pgn);
    std::string sources;
    for (std::size_t a = 0; a < s.sources.size(); ++a) {
      if (!s.sources[a]) continue;
      char hex[4];
      std::snprintf(hex, sizeof hex, "%02X", static_cast<unsigned>(a));
      sources += (sources.empty() ? "" : ";") + std::string(hex);
    }
    const double period_ms = s.frames > 1 ? to_seconds(s.last - s.first) * 1e3 / static_cast<double>(s.frames - 1) : 0.0;
    std::fprintf(out, "%u,%s,%" PRIu64 ",%s,%.3f,%" PRIu64 "\n", pgn, def != nullptr ? def->name.c_str() : "", s.frames,
                 sources.c_str(), period_ms, s.tp_messages);
  }
}

void print_summary(const KindCounts& k, const recording::RecordingReader& rec, const j1939::TpCounters& tp,
                   const j1939::CadenceCounters& cadence) {
  std::uint64_t ignored = 0;
  for (const auto& s : rec.streams()) ignored += s->counts().ignored_lines;
  std::fprintf(stderr,
               "frames=%" PRIu64 " extended=%" PRIu64 " standard_11bit=%" PRIu64 " remote=%" PRIu64 " error=%" PRIu64 " fd=%" PRIu64
               " ignored_lines=%" PRIu64 " malformed_lines=%" PRIu64 "\n",
               k.total(), k.extended, k.standard, k.remote, k.error, k.fd, ignored, rec.errors().count());
  std::fprintf(stderr,
               "transport: completed=%" PRIu64 " bam=%" PRIu64 " rts=%" PRIu64 " etp=%" PRIu64 " aborted=%" PRIu64
               " timed_out=%" PRIu64 " superseded=%" PRIu64 " duplicates=%" PRIu64 " orphans=%" PRIu64 " malformed=%" PRIu64 "\n",
               tp.completed, tp.bam_started, tp.rts_started, tp.etp_started, tp.aborted, tp.timed_out, tp.superseded,
               tp.duplicate_packets, tp.orphan_packets, tp.malformed);
  std::fprintf(stderr, "cadence: gaps=%" PRIu64 " repeats=%" PRIu64 " untracked=%" PRIu64 " too_fast=%" PRIu64 "\n", cadence.gaps,
               cadence.repeats, cadence.untracked, cadence.too_fast);
  for (const ParseError& e : rec.errors().kept()) std::fprintf(stderr, "%s\n", e.to_string().c_str());
  if (rec.errors().count() > rec.errors().kept().size()) {
    std::fprintf(stderr, "... and %" PRIu64 " more malformed lines\n", rec.errors().count() - rec.errors().kept().size());
  }
}

int decode(const DecodeOptions& o) {
  j1939::Database db;
  if (auto rc = load_definitions("decode", o.dbcs, db)) return *rc;
  // Only the CAN stream: the sensors' streams would be read in full only to be skipped.
  auto rec = recording::RecordingReader::open_drive(o.inputs, recording::kCanStream);
  if (!rec) {
    std::fprintf(stderr, "roadload decode: %s\n", rec.error().to_string().c_str());
    return kExitNoInput;
  }
  auto wanted = [&](j1939::Pgn p) { return o.only.empty() || std::find(o.only.begin(), o.only.end(), p) != o.only.end(); };

  static char out_buf[1 << 16];
  std::setvbuf(stdout, out_buf, _IOFBF, sizeof out_buf);
  j1939::MessageAssembler assembler;
  PgnTable stats;
  KindCounts kinds;
  // The same judge of lost and repeated frames as roadloadd's status, over the same stamps.
  j1939::CadenceMonitor cadence;
  recording::ReadAhead ahead(rec.value());
  while (const recording::Record* r = ahead.next()) {
    const auto* frame = std::get_if<CanFrame>(r);
    if (frame == nullptr) continue;
    kinds.add(frame->kind);
    cadence.push(*frame);
    if (o.pgn_stats && frame->kind == CanFrameKind::extended) {
      const j1939::Id id = j1939::parse_id(frame->id);
      PgnStats& s = stats[id.pgn()];
      if (s.frames++ == 0) s.first = frame->t;
      s.last = frame->t;
      s.sources[id.sa] = true;
    }
    const auto m = assembler.push(*frame);
    if (!m || !wanted(m->pgn)) continue;
    if (o.pgn_stats) {
      if (m->reassembled) ++stats[m->pgn].tp_messages;
    } else if (o.tp_only) {
      if (m->reassembled) print_tp(stdout, *m, ahead.interfaces());
    } else if (const j1939::MessageDef* def = db.find(m->pgn)) {
      print_signals(stdout, *m, *def, ahead.interfaces());
    }
  }
  if (o.pgn_stats) print_pgn_stats(stdout, stats, db);
  std::fflush(stdout);
  print_summary(kinds, rec.value(), assembler.transport().counters(), cadence.counters());
  return rec.value().errors().count() > 0 ? kExitDataErr : kExitOk;
}

}  // namespace

Run add_decode(CLI::App& roadload) {
  auto o = std::make_shared<DecodeOptions>();
  CLI::App& cmd = *roadload.add_subcommand("decode",
                                           "print decoded J1939 signals, transport messages or per-PGN statistics of a recording");
  describe(cmd, kDecodeHelp);
  cmd.add_option("INPUT", o->inputs,
                 "a recording folder or a candump -L log; several: the segments of\none roadloadd run, read as one drive")
      ->required();
  cmd.add_flag("--pgn-stats", o->pgn_stats, "CSV with one row per PGN:\npgn,name,frames,sources,mean_period_ms,tp_messages");
  cmd.add_flag("--tp", o->tp_only, "one line per reassembled transport-protocol message (BAM,\nRTS/CTS, ETP)");
  cmd.add_option("--pgn", o->only, "only this PGN (decimal or 0x hex); repeatable")->type_name("N")->transform(whole_in(0, 0x3FFFF));
  cmd.add_option("--dbc", o->dbcs, "load FILE after the built-in definitions (overrides the same\nPGN); repeatable")
      ->type_name("FILE");
  return [o] { return on_one_drive("decode", o->inputs, [&] { return decode(*o); }); };
}

}  // namespace roadload::cli
