// roadload grade: a route's grade profile per distance bin with its standard error, from the
// route's survey or from the GNSS heights of several recorded passes (seed report, Chapter 5),
// written as a CSV the force balance can take its grade and grade uncertainty from.
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command.hpp"
#include "files.hpp"
#include "gnss_tracks.hpp"
#include "roadload/cli/help.hpp"
#include "roadload/cli/values.hpp"
#include "roadload/definitions.hpp"
#include "roadload/grade_file.hpp"
#include "roadload/grade_profile.hpp"
#include "roadload/recording/reader.hpp"
#include "roadload/recording/writer.hpp"

namespace roadload::cli {
namespace {

constexpr double kDefaultSurveySigma_m = 0.02;  // a levelled or RTK survey: about 2 cm in height

const HelpText kGradeHelp{"usage: roadload grade --route ROUTE [RECORDING...] --out FILE [options]",
                          "Builds the route's grade profile per distance bin, with its standard error. Grade is the force\n"
                          "balance's largest error: 0.1 % of grade is 356 N on the 36 t truck, 0.001 in CRR.\n\n"
                          "Without recordings: from the route's survey elevations, a central difference over +-BASE, with\n"
                          "the survey's height error (--survey-sigma) at both ends.\n"
                          "With recordings: from their GNSS heights (seed report, Chapter 5). Each fix is placed on the\n"
                          "route; fixes off it, beyond its ends or without a 3-D fix are counted and dropped. A recording\n"
                          "is cut into passes where the travel along the route reverses. Each pass is averaged per bin,\n"
                          "then the passes; grade is the least-squares slope over +-BASE and its standard error the\n"
                          "scatter of the passes' slopes over sqrt(passes). A bin with fewer than --min-passes passes has\n"
                          "no grade (an empty field), never a guess. At 30 mph a code-DGPS pass gives about 0.25 % per bin:\n"
                          "six to ten passes, in both directions, reach 0.1 %. Each bin is compared with the survey on\n"
                          "standard output, and summarised on standard error."};

struct GradeOptions {
  std::string route_name, out;
  TrackOptions track;
  std::vector<std::string> recordings;
  GradeConfig cfg;
  double survey_sigma_m = kDefaultSurveySigma_m;
  bool quiet = false;
};

void add_options(CLI::App& cmd, GradeOptions& o) {
  cmd.add_option("RECORDING", o.recordings, "recording folders whose GNSS heights give the grade (none: the survey)");
  cmd.add_option("--route", o.route_name, "route file or built-in route name (config/routes): polyline and\nsurvey")
      ->type_name("R")
      ->required();
  cmd.add_option("-o,--out", o.out,
                 "write FILE: s_m,elevation_m,elevation_sigma_m,grade_pct,\n"
                 "grade_sigma_pct,passes, one line per bin; passes is 0 for the survey")
      ->type_name("FILE")
      ->required();
  cmd.add_option("--bin", o.cfg.bin_m, "bin length along the route (default 10)")->type_name("M")->check(real_in(0.5, 1000));
  cmd.add_option("--base", o.cfg.base_m, "slope over +-M, at least one bin (default 30, as analyze's survey\ngrade)")
      ->type_name("M")
      ->check(real_in(0.5, 5000));
  cmd.add_option("--min-passes", o.cfg.min_passes, "passes a bin needs for a grade (default 2: one pass has no scatter)")
      ->type_name("N")
      ->transform(whole_in(1, 1000));
  cmd.add_option("--survey-sigma", o.survey_sigma_m, "the survey's height standard error (default 0.02)")
      ->type_name("M")
      ->check(real_in(0, 10));
  cmd.add_option("--max-offset", o.cfg.max_offset_m, "fixes farther than M from the route are on another road (default 15)")
      ->type_name("M")
      ->check(real_in(0.1, 1000));
  cmd.add_option("--antenna-height", o.track.antenna_height_m,
                 "GNSS antenna above the road (default: the vehicle's, as --vehicle or\n"
                 "each recording's meta.toml gives it, else 0: heights are then the\n"
                 "antenna's)")
      ->type_name("M")
      ->check(real_in(-10, 20));
  cmd.add_option("--vehicle", o.track.vehicle, "vehicle file or built-in name whose antenna height the recordings\nshare")
      ->type_name("V");
  cmd.add_flag("-q,--quiet", o.quiet, "no per-bin comparison on standard output");
}

std::optional<int> write_csv(const std::string& path, const GradeProfile& g) {
  if (auto e = write_grade_file(path, g)) {
    std::fprintf(stderr, "roadload grade: %s\n", e->to_string().c_str());
    return kExitCantCreate;
  }
  return std::nullopt;
}

double pct(double rad) { return 100 * std::tan(rad); }

// A line per bin on standard output, and the summary on standard error.
void compare(const GradeProfile& gnss, const GradeProfile& survey, bool quiet) {
  if (!quiet) std::printf("%8s %9s %9s %9s %9s %6s\n", "s_m", "gnss_%", "sigma_%", "survey_%", "diff_%", "passes");
  double diff2 = 0, sigma = 0;
  std::size_t n = 0, with_sigma = 0;
  for (std::size_t k = 0; k < gnss.bins().size(); ++k) {
    const GradeBin& b = gnss.bins()[k];
    const double survey_pct = pct(survey.bins()[k].grade_rad);
    if (!std::isfinite(b.grade_rad)) {
      if (!quiet) std::printf("%8.1f %9s %9s %9.4f %9s %6zu\n", b.s_m, "-", "-", survey_pct, "-", b.passes);
      continue;
    }
    const double diff = pct(b.grade_rad) - survey_pct;
    if (!quiet) {
      std::printf("%8.1f %9.4f %9.4f %9.4f %9.4f %6zu\n", b.s_m, pct(b.grade_rad), 100 * b.grade_sigma_rad, survey_pct, diff,
                  b.passes);
    }
    diff2 += diff * diff;
    ++n;
    if (!std::isfinite(b.grade_sigma_rad)) continue;  // --min-passes 1: a lone pass has no scatter
    sigma += 100 * b.grade_sigma_rad;
    ++with_sigma;
  }
  const GnssFixCounts& f = gnss.fixes();
  std::fprintf(stderr,
               "grade: passes %zu; GNSS fixes: %zu used, %zu off the route, %zu beyond its ends, %zu without a 3-D "
               "fix, %zu with poor hdop\n",
               gnss.passes(), f.used, f.off_route, f.beyond_ends, f.no_3d_fix, f.poor_hdop);
  std::fprintf(stderr, "grade: %zu of %zu bins with a grade (--min-passes %zu)\n", n, gnss.bins().size(), gnss.config().min_passes);
  if (n == 0) return;
  const double rms_pct = std::sqrt(diff2 / static_cast<double>(n));
  std::fprintf(stderr, "grade: against the survey: RMS difference %.4f %% of grade; ", rms_pct);
  if (with_sigma == 0) {
    std::fprintf(stderr, "no grade sigma (one pass has no scatter)\n");
  } else {
    std::fprintf(stderr, "mean grade sigma %.4f %%\n", sigma / static_cast<double>(with_sigma));
  }
}

int grade(const GradeOptions& o) {
  if (o.cfg.base_m < o.cfg.bin_m) return usage_error("grade", "--base must be at least --bin: a slope needs three bins");
  const auto loaded = load_route("grade", o.route_name);
  if (const int* rc = std::get_if<int>(&loaded)) return *rc;
  const LoadedRoute& route = std::get<LoadedRoute>(loaded);
  const GradeProfile survey = GradeProfile::from_survey(route.geometry, o.survey_sigma_m, o.cfg);
  if (o.recordings.empty()) {
    if (auto code = write_csv(o.out, survey)) return *code;
    std::fprintf(stderr, "grade: survey profile of %s: %zu bins of %.1f m, grade sigma %.4f %% (survey sigma %.3f m)\n",
                 route.file.source_file.c_str(), survey.bins().size(), o.cfg.bin_m,
                 100 * std::sqrt(2.0) * o.survey_sigma_m / (2 * o.cfg.base_m), o.survey_sigma_m);
    return kExitOk;
  }

  j1939::Database db;
  if (auto rc = load_definitions("grade", {}, db)) return *rc;
  std::vector<RecordedTrack> tracks(o.recordings.size());
  std::uint64_t malformed = 0;
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    if (auto code = read_recorded_track("grade", {o.recordings[i]}, o.track, db, tracks[i], malformed)) return *code;
    if (tracks[i].fixes.empty())
      std::fprintf(stderr, "roadload grade: %s: no GNSS fixes (gnss.csv, J1939 VP1)\n", tracks[i].path.c_str());
  }
  std::vector<GnssTrack> gnss_tracks;
  for (const RecordedTrack& t : tracks) gnss_tracks.push_back({t.fixes, t.antenna_height_m});
  const GradeProfile gnss = GradeProfile::from_gnss(route.geometry, gnss_tracks, o.cfg);
  if (auto code = write_csv(o.out, gnss)) return *code;
  compare(gnss, survey, o.quiet);
  if (gnss.bins_with_grade() == 0) {
    std::fprintf(stderr,
                 "roadload grade: no bin has a grade: passes %zu, recordings %zu, --min-passes %zu (drive the "
                 "route again, in either direction)\n",
                 gnss.passes(), tracks.size(), o.cfg.min_passes);
    return kExitDataErr;
  }
  return malformed > 0 ? kExitDataErr : kExitOk;
}

}  // namespace

Run add_grade(CLI::App& roadload) {
  auto o = std::make_shared<GradeOptions>();
  CLI::App& cmd = *roadload.add_subcommand("grade",
                                           "build a route's grade profile with its uncertainty from its survey or GNSS passes");
  describe(cmd, kGradeHelp);
  add_options(cmd, *o);
  return [o] { return grade(*o); };
}

}  // namespace roadload::cli
