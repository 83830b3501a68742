#pragma once
// What bash completion (tools/completion/) asks a program for, so that the scripts hold no list
// of commands or options that could drift from the programs' own.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace roadload::cli {

// The words that may follow `path` (the subcommands typed so far, e.g. {"gap", "bench"}), one a
// line with its kind: "analyze command", "--out value" (takes a value: a file, a name or a
// number), "--quiet flag". Hidden options are left out; a word of `path` that is no subcommand
// (a recording, a value) ends it.
std::string completion_words(const CLI::App& app, const std::vector<std::string>& path);

}  // namespace roadload::cli
