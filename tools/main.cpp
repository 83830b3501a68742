// roadload: one CLI11 command line for every subcommand (cli/ keeps the conventions roadloadd
// shares), then the subcommand that was given runs.
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "command.hpp"
#include "roadload/cli/help.hpp"
#include "roadload/cli/parse.hpp"

// Inside roadload::cli like every command's file: the commands compile together (unity build), and
// a using-directive at file scope would carry their anonymous namespaces' names into the files after.
namespace roadload::cli {
namespace {

// In the order `roadload --help` lists them.
constexpr Run (*kCommands[])(CLI::App&) = {add_decode,  add_analyze, add_batch,   add_calibrate, add_cat,
                                           add_collect, add_gap,     add_network, add_grade,     add_psd,
                                           add_replay,  add_report,  add_route,   add_simulate,  add_vehicle};

const HelpText kRoadloadHelp{"usage: roadload <command> [options]",
                             "Measures what a heavy truck spends on rolling resistance, pavement by pavement.",
                             "'roadload <command> --help' describes a command; every command takes --version."};

int roadload_main(int argc, char** argv) {
  CLI::App app("", "roadload");
  describe(app, kRoadloadHelp);
  app.require_subcommand(1);
  std::vector<std::pair<const CLI::App*, Run>> commands;
  for (const auto add : kCommands) {
    Run run = add(app);
    commands.emplace_back(app.get_subcommands({}).back(), std::move(run));
  }
  if (argc < 2) {
    std::fputs(app.help().c_str(), stderr);
    return kExitUsage;
  }
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.front() == "help") args.front() = "--help";
  const Outcome read = parse(app, args, "roadload " ROADLOAD_VERSION);
  if (read.kind == Outcome::Kind::print) {
    std::fputs(read.text.c_str(), stdout);
    return kExitOk;
  }
  if (read.kind == Outcome::Kind::usage_error) return usage_error(read.command, read.message());
  for (const auto& [command, run] : commands) {
    if (command->parsed()) return run();
  }
  return usage_error("", "no command given");  // require_subcommand(1) makes this unreachable
}

}  // namespace
}  // namespace roadload::cli

int main(int argc, char** argv) { return roadload::cli::roadload_main(argc, argv); }
