#pragma once
// A command's --help: the hand-written usage lines and prose that say what it does, around the
// arguments and options CLI11 lists from the options themselves, so the list never drifts.
#include <string>

#include <CLI/CLI.hpp>

namespace roadload::cli {

struct HelpText {
  std::string usage;       // "usage: roadload analyze <recording> --out RESULTS [options]"; a line or more
  std::string prose = {};  // what the command does, before its arguments and options
  std::string notes = {};  // after them
};

// `app`'s --help prints `text` around its arguments, options and subcommands.
void describe(CLI::App& app, HelpText text);

// `app`'s --help prints `action`'s: a command whose one action is a subcommand of it
// (`roadload route build`) is described where a user first asks.
void describe_as(CLI::App& app, const CLI::App& action);

// A command of `parent` whose one action is a subcommand (`roadload route build`): both added,
// the action required and described by `text`, the command's --help the action's. Returns the
// action, for its options.
CLI::App& add_action_command(CLI::App& parent, const std::string& name, const std::string& summary, const std::string& action,
                             const std::string& action_summary, HelpText text);

}  // namespace roadload::cli
