#include "roadload/cli/help.hpp"

#include <cctype>
#include <memory>
#include <utility>

#include <CLI/CLI.hpp>

namespace roadload::cli {
namespace {

// Names up to this wide share a line with their description; longer ones put it on the next.
constexpr std::size_t kNameColumn = 26;

class HelpFormatter : public CLI::Formatter {
 public:
  explicit HelpFormatter(HelpText text) : text_(std::move(text)) {
    column_width(kNameColumn);
    label("Positionals", "arguments");
    label("REQUIRED", "(required)");
  }

  std::string make_help(const CLI::App* app, std::string, CLI::AppFormatMode mode) const override {
    if (mode == CLI::AppFormatMode::Sub) return make_expanded(app);
    std::string out = text_.usage + "\n";
    if (!text_.prose.empty()) out += "\n" + text_.prose + "\n";
    out += make_positionals(app) + make_groups(app, mode) + make_subcommands(app, mode);
    if (!text_.notes.empty()) out += "\n" + text_.notes + "\n";
    return out;
  }

  // Group headings in the lower case of the rest of the text: "options:", not "Options:".
  std::string make_group(std::string group, bool is_positional, std::vector<const CLI::Option*> opts) const override {
    for (char& c : group) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return CLI::Formatter::make_group(std::move(group), is_positional, std::move(opts));
  }

 private:
  HelpText text_;
};

class SameHelpAs : public CLI::Formatter {
 public:
  explicit SameHelpAs(const CLI::App& action) : action_(action) {}
  std::string make_help(const CLI::App*, std::string name, CLI::AppFormatMode mode) const override {
    return action_.help(name, mode);
  }

 private:
  const CLI::App& action_;
};

}  // namespace

void describe(CLI::App& app, HelpText text) {
  app.formatter(std::make_shared<HelpFormatter>(std::move(text)));
  // Subcommands are listed under "commands:", whatever their parent is.
  app.group("commands");
}

void describe_as(CLI::App& app, const CLI::App& action) {
  app.formatter(std::make_shared<SameHelpAs>(action));
  app.group("commands");
}

CLI::App& add_action_command(CLI::App& parent, const std::string& name, const std::string& summary, const std::string& action,
                             const std::string& action_summary, HelpText text) {
  CLI::App& cmd = *parent.add_subcommand(name, summary);
  CLI::App& act = *cmd.add_subcommand(action, action_summary);
  cmd.require_subcommand(1);
  describe_as(cmd, act);
  describe(act, std::move(text));
  return act;
}

}  // namespace roadload::cli
