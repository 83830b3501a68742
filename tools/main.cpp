#include <cstdio>
#include <cstring>

#include "command.hpp"

namespace {

using roadload::cli::Command;

constexpr Command kCommands[] = {
    {"decode", "print decoded J1939 signals, transport messages or per-PGN statistics of a recording", roadload::cli::run_decode},
    {"analyze", "estimate CRR along a recorded drive and per pavement cell (cells.csv, trip.json)", roadload::cli::run_analyze},
    {"calibrate", "measure the engine's losses by engine speed standing in neutral (replaces EEC3's whole percent)",
     roadload::cli::run_calibrate},
    {"gap", "diagnose the sim-to-real gap: where it lies, which unmodelled effect causes it, how far it shrinks",
     roadload::cli::run_gap},
    {"grade", "build a route's grade profile with its uncertainty from its survey or GNSS passes", roadload::cli::run_grade},
    {"psd", "Welch power spectral density of accelerometer channels, as scipy.signal.welch computes it", roadload::cli::run_psd},
    {"replay", "play a recording's CAN frames onto a (virtual) CAN interface, in real time or faster", roadload::cli::run_replay},
    {"report", "draw a drive's results as one self-contained HTML page (figures and tables)", roadload::cli::run_report},
    {"route", "build a route file from the recordings' own GNSS passes, with cells or a GIS file's sections",
     roadload::cli::run_route},
    {"simulate", "drive the simulated truck over a simulated road; write a recording and its ground truth",
     roadload::cli::run_simulate},
    {"vehicle", "identify a truck's vehicle file from its recordings: VIN, torque, gear ratios, tire radius, mass",
     roadload::cli::run_vehicle},
};

void usage(std::FILE* out) {
  std::fprintf(out,
               "usage: roadload <command> [options]\n\n"
               "Measures what a heavy truck spends on rolling resistance, pavement by pavement.\n\n"
               "commands:\n");
  for (const Command& c : kCommands)
    std::fprintf(out, "  %-10.*s %.*s\n", static_cast<int>(c.name.size()), c.name.data(), static_cast<int>(c.summary.size()),
                 c.summary.data());
  std::fprintf(out, "\n'roadload <command> --help' describes a command.\n");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    usage(stderr);
    return roadload::cli::kExitUsage;
  }
  const std::string_view name = argv[1];
  if (name == "--help" || name == "-h" || name == "help") {
    usage(stdout);
    return 0;
  }
  if (name == "--version") {
    std::puts("roadload " ROADLOAD_VERSION);
    return 0;
  }
  for (const Command& c : kCommands) {
    if (c.name == name) return c.run(roadload::cli::Args(argv + 2, static_cast<std::size_t>(argc - 2)));
  }
  std::fprintf(stderr, "roadload: unknown command '%s'\n\n", argv[1]);
  usage(stderr);
  return roadload::cli::kExitUsage;
}
