// roadload cat: one stream of a recording as the text of docs/recording-format.md, however it is
// stored (plain, zstd frames, the accelerometers' FLAC files): what zstdcat is to a compressed
// stream, for every layout, so awk, pandas and can-utils read any recording.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include <CLI/CLI.hpp>

#include "command.hpp"
#include "files.hpp"
#include "roadload/cli/help.hpp"
#include "roadload/recording/candump.hpp"
#include "roadload/recording/reader.hpp"
#include "roadload/recording/writer.hpp"

namespace roadload::cli {
namespace {

const HelpText kCatHelp{"usage: roadload cat STREAM RECORDING... [-o FILE]",
                        "Writes one stream of a recording as text: can.log (candump -L), accel.csv, gnss.csv or\n"
                        "weather.csv (docs/recording-format.md), whether the folder holds it plain, as zstd frames\n"
                        "or, for the accelerometers, as accel-ID.flac files. Several recordings: the segments of one\n"
                        "roadloadd run, written as one drive.",
                        "Malformed lines or damaged frames are reported on standard error with file, line and field;\n"
                        "the rest is written and the exit status is 65."};

struct CatOptions {
  std::string stream;
  std::vector<std::string> inputs;
  std::string out;
};

// A stream by its file name, and the CSV header it starts with (none for can.log).
struct StreamChoice {
  unsigned bit;
  std::string_view header;
};

std::optional<StreamChoice> stream_named(std::string_view name) {
  if (name == recording::kCanFile) return StreamChoice{recording::kCanStream, {}};
  if (name == recording::kAccelFormat.file) return StreamChoice{recording::kAccelStream, recording::kAccelFormat.header};
  if (name == recording::kGnssFormat.file) return StreamChoice{recording::kGnssStream, recording::kGnssFormat.header};
  if (name == recording::kWeatherFormat.file) return StreamChoice{recording::kWeatherStream, recording::kWeatherFormat.header};
  return std::nullopt;
}

int cat(const CatOptions& o) {
  const auto choice = stream_named(o.stream);
  if (!choice) return usage_error("cat", "STREAM must be can.log, accel.csv, gnss.csv or weather.csv, not '" + o.stream + "'");
  auto rec = recording::RecordingReader::open_drive(o.inputs, choice->bit);
  if (!rec) return failed("cat", rec.error());
  std::optional<recording::OutputFile> file;
  if (!o.out.empty()) {
    auto f = recording::OutputFile::create(o.out);
    if (!f) return failed("cat", f.error(), kExitCantCreate);
    file.emplace(std::move(f.value()));
  } else {
    static char buffer[1 << 16];
    std::setvbuf(stdout, buffer, _IOFBF, sizeof buffer);
  }
  auto emit = [&](std::string_view text) {
    if (text.empty()) return;  // can.log's header is none: its view holds no pointer for fwrite
    if (file) {
      file->write(text);
    } else {
      std::fwrite(text.data(), 1, text.size(), stdout);
    }
  };
  emit(choice->header);
  recording::LineBuilder line;
  char frame_line[recording::kMaxLineChars + 1];
  while (const recording::Record* r = rec.value().next()) {
    if (const auto* f = std::get_if<CanFrame>(r)) {
      const std::size_t n = recording::format_candump_line(*f, rec.value().interfaces().name(f->iface), frame_line);
      frame_line[n] = '\n';
      emit({frame_line, n + 1});
    } else {
      std::visit(
          [&](const auto& s) {
            if constexpr (!std::is_same_v<std::decay_t<decltype(s)>, CanFrame>) emit(recording::format_row(s, line));
          },
          *r);
    }
  }
  if (file) {
    if (auto e = file->close()) return failed("cat", *e, kExitCantCreate);
  } else if (std::fflush(stdout) != 0) {
    return failed("cat", ParseError{"standard output", 0, "write", std::strerror(errno)}, kExitCantCreate);
  }
  for (const ParseError& e : rec.value().errors().kept()) say("cat", e.to_string());
  return rec.value().errors().count() > 0 ? kExitDataErr : kExitOk;
}

}  // namespace

Run add_cat(CLI::App& roadload) {
  auto o = std::make_shared<CatOptions>();
  CLI::App& cmd = *roadload.add_subcommand("cat", "write one stream of a recording as text, however it is stored");
  describe(cmd, kCatHelp);
  cmd.add_option("STREAM", o->stream, "can.log, accel.csv, gnss.csv or weather.csv")->required();
  cmd.add_option("RECORDING", o->inputs, "a recording folder; several: the segments of one roadloadd run,\nread as one drive")
      ->required();
  cmd.add_option("-o,--out", o->out, "write FILE instead of standard output")->type_name("FILE");
  return [o] { return on_one_drive("cat", o->inputs, [&] { return cat(*o); }); };
}

}  // namespace roadload::cli
