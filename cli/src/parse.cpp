#include "roadload/cli/parse.hpp"

#include <optional>

#include "roadload/cli/completion.hpp"

namespace roadload::cli {
namespace {

// An option's value never starts with "--": `--can --no-gnss` lacks its interface, it does not
// listen on a bus named "--no-gnss".
CLI::Validator not_an_option(const std::string& type_name) {
  return CLI::Validator(
      [type_name](std::string& text) {
        if (text.rfind("--", 0) != 0) return std::string();
        return "needs " + (type_name.empty() ? std::string("a value") : type_name) + ", not the option '" + text + "'";
      },
      "");
}

void apply_conventions(CLI::App& app, const std::string& version) {
  app.set_help_flag("-h,--help", "this text");
  app.set_version_flag("--version", version, "print the version and exit");
  // Unknown arguments are collected and named by unknown_argument(), not CLI11's "not expected".
  app.allow_extras();
  for (CLI::Option* opt : app.get_options()) {
    // A positional's name says what it is: "RECORDING", not "RECORDING TEXT". A flag takes no value.
    if (opt->get_positional()) opt->type_name("");
    if (opt->get_positional() || opt->get_expected_max() == 0) continue;
    opt->allow_extra_args(false);
    // An option of one value given twice keeps the last, as a later word overrides an earlier one.
    if (opt->get_items_expected_max() <= 1) opt->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    opt->transform(not_an_option(opt->get_type_name()));
  }
  for (CLI::App* sub : app.get_subcommands({})) apply_conventions(*sub, version);
}

// The subcommands given, outermost first, from the program itself.
std::vector<const CLI::App*> given(const CLI::App& app) {
  std::vector<const CLI::App*> chain{&app};
  while (!chain.back()->get_subcommands().empty()) chain.push_back(chain.back()->get_subcommands().front());
  return chain;
}

std::string command_of(const std::vector<const CLI::App*>& chain, std::size_t depth) {
  std::string command;
  for (std::size_t i = 1; i <= depth && i < chain.size(); ++i) command += (i > 1 ? " " : "") + chain[i]->get_name();
  return command;
}

Outcome printed(std::string text) { return {Outcome::Kind::print, std::move(text), {}, {}}; }

Outcome usage_error(std::string command, std::string field, std::string message) {
  return {Outcome::Kind::usage_error, std::move(message), std::move(command), std::move(field)};
}

// A second word for a positional that takes one: "one RECORDING at a time: 'a' and 'b' given",
// rather than replacing the first or passing for an unknown argument.
std::optional<std::string> second_positional(const CLI::App& app, const std::string& arg) {
  for (const CLI::Option* opt : app.get_options()) {
    if (!opt->get_positional() || opt->get_items_expected_max() != 1 || opt->results().empty()) continue;
    return "one " + opt->get_name(true) + " at a time: '" + opt->results().front() + "' and '" + arg + "' given";
  }
  return std::nullopt;
}

// The first argument nothing took, named as what it looks like.
std::optional<Outcome> unknown_argument(const CLI::App& app) {
  const std::vector<const CLI::App*> chain = given(app);
  for (std::size_t depth = 0; depth < chain.size(); ++depth) {
    const std::vector<std::string> left = chain[depth]->remaining(false);
    if (left.empty()) continue;
    const std::string& arg = left.front();
    const std::string command = command_of(chain, depth);
    if (arg.rfind('-', 0) == 0) return usage_error(command, arg, "unknown option");
    if (auto second = second_positional(*chain[depth], arg)) return usage_error(command, "", *second);
    return usage_error(command, arg, chain[depth]->get_subcommands({}).empty() ? "unexpected argument" : "unknown command");
  }
  return std::nullopt;
}

// "route: a command is required: build", where CLI11 says "A subcommand is required".
std::optional<std::string> missing_command(const CLI::App& app) {
  if (app.get_require_subcommand_min() == 0 || !app.get_subcommands().empty()) return std::nullopt;
  std::string names;
  for (const CLI::App* sub : app.get_subcommands({})) names += (names.empty() ? "" : ", ") + sub->get_name();
  return "a command is required: " + names;
}

// CLI11's message, "--mass: 'heavy' is not ...", split at the option it begins with.
Outcome parse_error(const CLI::App& app, const std::string& message) {
  const std::vector<const CLI::App*> chain = given(app);
  const std::string command = command_of(chain, chain.size() - 1);
  if (auto missing = missing_command(*chain.back())) return usage_error(command, "", *missing);
  const std::size_t colon = message.find(": ");
  if (message.rfind('-', 0) != 0 || colon == std::string::npos) return usage_error(command, "", message);
  return usage_error(command, message.substr(0, colon), message.substr(colon + 2));
}

}  // namespace

Outcome parse(CLI::App& app, const std::vector<std::string>& args, const std::string& version) {
  apply_conventions(app, version);
  if (!args.empty() && args.front() == "--complete") {
    return printed(completion_words(app, std::vector<std::string>(args.begin() + 1, args.end())));
  }
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last first
  try {
    app.parse(reversed);
  } catch (const CLI::CallForHelp&) {
    return printed(app.help());
  } catch (const CLI::CallForVersion& e) {
    return printed(std::string(e.what()) + "\n");
  } catch (const CLI::ParseError& e) {
    // An unknown option explains the errors that follow from it (a value it took, a requirement).
    if (auto unknown = unknown_argument(app)) return *unknown;
    return parse_error(app, e.what());
  }
  if (auto unknown = unknown_argument(app)) return *unknown;
  return {};
}

}  // namespace roadload::cli
