// roadload psd: Welch power spectral density of a recording's accelerometers or of a CSV column,
// the same numbers as scipy.signal.welch with the same settings (a check anyone can repeat).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command.hpp"
#include "files.hpp"
#include "roadload/cli/help.hpp"
#include "roadload/cli/values.hpp"
#include "roadload/recording/csv.hpp"
#include "roadload/recording/reader.hpp"
#include "roadload/spectra/welch.hpp"

namespace roadload::cli {
namespace {

const HelpText kPsdHelp{"usage: roadload psd <recording | file.csv> [options]",
                        "Welch power spectral density, one-sided, per Hz: Hann window (periodic), segments of N samples\n"
                        "every N - M samples, each segment's mean removed, averaged. The numbers are those of\n"
                        "scipy.signal.welch(x, fs, window='hann', nperseg=N, noverlap=M) (equal to 1e-9, tested).\n"
                        "A recording gives one column per accelerometer and axis, in (m/s^2)^2/Hz, each at the sensor's\n"
                        "rate from meta.toml; a CSV file gives the PSD of one column."};

struct Channel {
  std::string name;
  std::int64_t sensor = -1;  // accel.csv sensor id; -1 for a CSV column
  std::size_t axis = 2;      // 0 x, 1 y, 2 z
  double fs_hz = 0;
  std::unique_ptr<spectra::WelchPsd> psd;
  std::uint64_t samples = 0;
};

struct PsdOptions {
  std::vector<std::string> inputs;  // a CSV file, a recording, or one drive's segments
  std::string out, column, axis = "z";
  std::vector<std::string> sensors;
  std::size_t nperseg = 4096;
  std::optional<std::size_t> noverlap;
  std::optional<double> fs_hz;
};

bool wanted(const PsdOptions& o, const recording::SensorInfo& s) {
  if (s.kind != "accelerometer") return false;
  if (o.sensors.empty()) return true;
  for (const std::string& w : o.sensors)
    if (w == s.name || w == std::to_string(s.id)) return true;
  return false;
}

// Feeds every row of `path` to the channels; the first malformed row ends it with its error.
int feed(const std::string& path, std::span<const std::string_view> columns, std::vector<Channel>& channels) {
  auto csv = recording::CsvReader::open(path, columns);
  if (!csv) return failed("psd", csv.error());
  std::span<const std::string_view> row;
  for (;;) {
    const auto status = csv.value().next(row);
    if (status == recording::CsvReader::Status::end) {
      if (csv.value().error()) return failed("psd", *csv.value().error());
      return kExitOk;
    }
    if (status == recording::CsvReader::Status::bad_row) return failed("psd", *csv.value().error());
    if (columns.size() == 1) {
      const auto x = recording::parse_f64(row[0]);
      if (!x) return failed("psd", csv.value().field_error(0, "not a number"));
      channels[0].psd->push(*x);
      ++channels[0].samples;
      continue;
    }
    const auto sensor = recording::parse_i64(row[1]);
    if (!sensor) return failed("psd", csv.value().field_error(1, "not an integer"));
    for (Channel& c : channels) {
      if (c.sensor != *sensor) continue;
      const auto x = recording::parse_f64(row[2 + c.axis]);
      if (!x) return failed("psd", csv.value().field_error(2 + c.axis, "not a number"));
      c.psd->push(*x);
      ++c.samples;
    }
  }
}

int write(const PsdOptions& o, const std::vector<Channel>& channels, const spectra::WelchConfig& first) {
  std::FILE* f = o.out.empty() ? stdout : std::fopen(o.out.c_str(), "w");
  if (!f) {
    std::fprintf(stderr, "roadload psd: %s: cannot create\n", o.out.c_str());
    return kExitCantCreate;
  }
  std::vector<std::vector<double>> d;
  for (const Channel& c : channels) {
    d.emplace_back(c.psd->bins());
    c.psd->density(d.back());
  }
  std::fputs("freq_hz", f);
  for (const Channel& c : channels) std::fprintf(f, ",%s", c.name.c_str());
  std::fputc('\n', f);
  for (std::size_t k = 0; k < spectra::bin_count(first); ++k) {
    std::fprintf(f, "%.17g", static_cast<double>(k) * spectra::bin_hz(first));
    for (const auto& col : d) std::fprintf(f, ",%.17g", col[k]);
    std::fputc('\n', f);
  }
  const bool ok = std::fflush(f) == 0 && !std::ferror(f);
  if (f != stdout) std::fclose(f);
  if (!ok) {
    std::fprintf(stderr, "roadload psd: %s: write failed\n", o.out.empty() ? "stdout" : o.out.c_str());
    return kExitCantCreate;
  }
  return kExitOk;
}

void add_options(CLI::App& cmd, PsdOptions& o) {
  cmd.add_option("RECORDING", o.inputs,
                 "a recording folder or a CSV file; several: the segments of one\nroadloadd run, read as one drive")
      ->required();
  cmd.add_option("--nperseg", o.nperseg, "segment length, even (default 4096)")->type_name("N")->transform(whole_in(2, 1 << 22));
  cmd.add_option("--noverlap", o.noverlap, "overlap in samples (default N/2)")->type_name("M")->transform(whole_in(0, 1 << 22));
  cmd.add_option("--fs", o.fs_hz, "sampling rate (required for a CSV file; overrides meta.toml for a\nrecording)")
      ->type_name("HZ")
      ->check(real_in(1e-6, 1e9));
  cmd.add_option("--sensor", o.sensors, "only this accelerometer (name or id); repeatable (default: all)")->type_name("NAME");
  cmd.add_option("--axis", o.axis, "x, y, z or all (default z)")->type_name("A")->check(one_of({"x", "y", "z", "all"}));
  cmd.add_option("--column", o.column, "the CSV file's column")->type_name("NAME");
  cmd.add_option("-o,--out", o.out, "write FILE instead of standard output: freq_hz,<sensor>_<axis>,...")->type_name("FILE");
}

int psd(const PsdOptions& o) {
  const auto config = [&](double fs) { return spectra::WelchConfig{fs, o.nperseg, o.noverlap.value_or(o.nperseg / 2)}; };
  if (auto why = spectra::check(config(o.fs_hz.value_or(1.0)))) return usage_error("psd", *why);

  std::vector<Channel> channels;
  int rc = kExitOk;
  const std::string& input = o.inputs.front();
  if (!std::filesystem::is_directory(input)) {
    if (o.column.empty()) return usage_error("psd", "--column is required for a CSV file");
    if (!o.fs_hz) return usage_error("psd", "--fs is required for a CSV file");
    channels.push_back({o.column, -1, 0, *o.fs_hz, std::make_unique<spectra::WelchPsd>(config(*o.fs_hz)), 0});
    const std::string_view cols[] = {o.column};
    rc = feed(input, cols, channels);
  } else {
    auto reader = recording::RecordingReader::open(input);
    if (!reader) return failed("psd", reader.error());
    for (const auto& s : reader.value().metadata().sensors) {
      if (!wanted(o, s)) continue;
      const double fs = o.fs_hz.value_or(s.rate_hz);
      if (!(fs > 0)) return usage_error("psd", "sensor " + s.name + " has no rate_hz in meta.toml: give --fs");
      for (std::size_t axis = 0; axis < 3; ++axis) {
        if (o.axis != "all" && o.axis[0] != "xyz"[axis]) continue;
        channels.push_back({s.name + "_" + "xyz"[axis], s.id, axis, fs, std::make_unique<spectra::WelchPsd>(config(fs)), 0});
      }
    }
    if (channels.empty()) return usage_error("psd", "no accelerometer in " + input + "/meta.toml matches");
    for (const Channel& c : channels)
      if (c.fs_hz != channels[0].fs_hz) return usage_error("psd", "sensors at different rates: give --fs or one --sensor");
    // A drive's segments continue one another; accel.csv or the sensors' FLAC files alike.
    auto drive = recording::RecordingReader::open_drive(o.inputs, recording::kAccelStream);
    if (!drive) return failed("psd", drive.error());
    while (const recording::Record* r = drive.value().next()) {
      const auto& s = std::get<AccelSample>(*r);
      const std::array<double, 3> xyz{s.x_mps2, s.y_mps2, s.z_mps2};
      for (Channel& c : channels) {
        if (c.sensor != s.sensor) continue;
        c.psd->push(xyz[c.axis]);
        ++c.samples;
      }
    }
    if (drive.value().errors().count() > 0) return failed("psd", drive.value().errors().kept().front());
  }
  if (rc != kExitOk) return rc;
  for (const Channel& c : channels) {
    if (c.psd->segments() < 1) {
      std::fprintf(stderr, "roadload psd: %s: %llu samples, fewer than one segment of %zu\n", c.name.c_str(),
                   static_cast<unsigned long long>(c.samples), o.nperseg);
      return kExitDataErr;
    }
  }
  return write(o, channels, config(channels[0].fs_hz));
}

}  // namespace

Run add_psd(CLI::App& roadload) {
  auto o = std::make_shared<PsdOptions>();
  CLI::App& cmd = *roadload.add_subcommand(
      "psd", "Welch power spectral density of accelerometer channels, as scipy.signal.welch computes it");
  describe(cmd, kPsdHelp);
  add_options(cmd, *o);
  return [o] { return on_one_drive("psd", o->inputs, [&] { return psd(*o); }); };
}

}  // namespace roadload::cli
