#pragma once
// Reading a command line with the conventions both programs keep: -h/--help and --version on the
// program and every subcommand, each printed on standard output; one value per occurrence of an
// option (repeat it for more); a value that is another option ("--can --no-gnss") refused; an
// unknown option or a stray argument named. `--complete [COMMAND...]`, not in --help, prints the
// words bash completion offers (completion.hpp).
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace roadload::cli {

struct Outcome {
  enum class Kind { run, print, usage_error };
  Kind kind = Kind::run;
  std::string text;     // print: help, version or completion words; usage_error: what is wrong
  std::string command;  // usage_error: the subcommand read ("analyze", "gap bench"); empty for the program
  std::string field;    // usage_error: the option or argument at fault, when there is one

  // A usage error as one line: "--mass: 'heavy' is not a finite number in 1000..200000".
  std::string message() const { return field.empty() ? text : field + ": " + text; }
};

// `version` is what --version prints: "roadload 0.1.0". On Kind::run the options are bound and
// the subcommands given report parsed().
Outcome parse(CLI::App& app, const std::vector<std::string>& args, const std::string& version);

}  // namespace roadload::cli
