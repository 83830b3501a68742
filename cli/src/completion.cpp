#include "roadload/cli/completion.hpp"

namespace roadload::cli {
namespace {

const CLI::App* subcommand(const CLI::App& app, const std::string& name) {
  for (const CLI::App* sub : app.get_subcommands({})) {
    if (sub->get_name() == name) return sub;
  }
  return nullptr;
}

}  // namespace

std::string completion_words(const CLI::App& app, const std::vector<std::string>& path) {
  const CLI::App* at = &app;
  for (const std::string& word : path) {
    const CLI::App* next = subcommand(*at, word);
    if (next == nullptr) break;
    at = next;
  }
  std::string words;
  for (const CLI::App* sub : at->get_subcommands({})) {
    if (!sub->get_group().empty()) words += sub->get_name() + " command\n";
  }
  for (const CLI::Option* opt : at->get_options()) {
    if (opt->get_positional() || opt->get_group().empty()) continue;
    const std::string kind = opt->get_expected_max() == 0 ? " flag\n" : " value\n";
    for (const std::string& s : opt->get_snames()) words += "-" + s + kind;
    for (const std::string& l : opt->get_lnames()) words += "--" + l + kind;
  }
  return words;
}

}  // namespace roadload::cli
