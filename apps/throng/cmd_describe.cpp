// `throng describe-cli` (hidden: not in --help) — the command line itself as JSON on stdout: every
// subcommand with its description and footer, every option and positional with its names, value
// label, choices and description. scripts/cli_docs.py turns it into the man pages and the bash and
// zsh completions at build time (docs/install.md), so they follow every flag the program has.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>

#include "commands.hpp"

namespace throng::cli {
namespace {

/// One option or positional: its names, whether it takes a value, the value's label as --help
/// shows it (with its checks, e.g. "N:0..1024"), its default and description.
nlohmann::json describeOption(const CLI::Option& option) {
  nlohmann::json names = nlohmann::json::array();
  for (const auto& s : option.get_snames()) names.push_back("-" + s);
  for (const auto& l : option.get_lnames()) names.push_back("--" + l);
  return {{"names", names},
          {"positional", !option.nonpositional()},
          {"name", option.get_name(true, false)},
          {"takes_value", option.get_items_expected_max() > 0 || !option.nonpositional()},
          {"type", option.get_type_name()},
          {"default", option.get_default_str()},
          {"required", option.get_required()},
          {"description", option.get_description()}};
}

nlohmann::json describeApp(const CLI::App& app) {
  nlohmann::json options = nlohmann::json::array();
  for (const CLI::Option* option : app.get_options()) options.push_back(describeOption(*option));
  nlohmann::json commands = nlohmann::json::array();
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App* s) { return !s->get_group().empty(); })) {
    commands.push_back(describeApp(*sub));
  }
  return {{"name", app.get_name()},
          {"description", app.get_description()},
          {"footer", app.get_footer()},
          {"options", options},
          {"commands", commands}};
}

}  // namespace

CLI::App* addDescribeCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("describe-cli", "The command line as JSON (for man pages and completions)");
  cmd->group("");  // hidden
  return cmd;
}

int runDescribe(const CLI::App& app, const char* version) {
  nlohmann::json out = describeApp(app);
  out["version"] = version;
  std::fputs((out.dump(2) + "\n").c_str(), stdout);
  return kExitOk;
}

}  // namespace throng::cli
