// `throng verify` — runs the verification suites (RiMEA, NIST TN 1822, ISO 20414; docs/verification.md)
// by handing its flags to scripts/verify.py, which runs this same binary on verification/*.json,
// measures the recordings and prints the table. Finds the script in <prefix>/share/throng/scripts
// next to an installed binary, else in the source tree the binary was built from (THRONG_SOURCE_DIR); runs it with /usr/bin/python3 (numpy and matplotlib come from Debian), else
// python3 on PATH (python_script.hpp).
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "bench_files.hpp"
#include "commands.hpp"
#include "output.hpp"
#include "python_script.hpp"

namespace throng::cli {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> scriptArguments(const VerifyOptions& o, const fs::path& exe) {
  std::vector<std::string> args{"--suite", o.suite, "--threads", std::to_string(o.threads)};
  for (const auto& t : o.tests) args.insert(args.end(), {"--test", t});
  if (!o.model.empty()) args.insert(args.end(), {"--model", o.model});
  if (!o.json.empty()) args.insert(args.end(), {"--json", o.json});
  if (!o.report.empty()) args.insert(args.end(), {"--report", o.report});
  if (!o.keep.empty()) args.insert(args.end(), {"--keep", o.keep});
  if (o.list) args.emplace_back("--list");
  args.insert(args.end(), {"--throng", o.throng.empty() ? exe.string() : o.throng});
  return args;
}

}  // namespace

CLI::App* addVerifyCommand(CLI::App& app, VerifyOptions& options) {
  CLI::App* cmd = app.add_subcommand("verify", "Run the verification tests (RiMEA, NIST TN 1822, ISO 20414)");
  cmd->footer(
      "Run the bundled verification scenarios (verification/), measure the recordings and print one row per\n"
      "test: criterion, measured, PASS / FAIL / XFAIL (expected to fail, with the reason) / XPASS (expected to\n"
      "fail but passed: update the expectation). Exit 0 when every test is PASS or XFAIL, 1 otherwise, 2 for\n"
      "bad flags. Runs scripts/verify.py with python3 (numpy and matplotlib from Debian); docs/verification.md\n"
      "has the tests, the criteria and the results. Suites: rimea (RiMEA tests 1-16), nist (NIST TN 1822 tests\n"
      "1.1-5.2), iso (the ISO 20414:2020 tests that differ from both: 7, 12, 13, 17, 21; verification/iso/README.md\n"
      "maps the other 16 to the RiMEA and NIST tests that run them). The whole suite: throng verify --suite all\n"
      "(about half a minute on 2 cores; with --model orca,avm,cfsm about a minute and a half)");
  cmd->add_option("--suite", options.suite, "Which tests: rimea, nist, iso (ISO 20414 beyond RiMEA and NIST) or all")
      ->check(CLI::IsMember({"rimea", "nist", "iso", "all"}))
      ->default_str("all");
  cmd->add_option("--test", options.tests, "Only these tests (repeatable, or a comma list: rimea-1,nist-2.1)")
      ->type_name("ID[,ID]");
  cmd->add_option("--model", options.model, "Run every test with each of these operational models side by side "
                                             "(orca, avm, cfsm, or all); default: the engine default")
      ->type_name("NAME[,NAME]");
  cmd->add_option("--threads", options.threads, "Simulations at a time, one thread each (results do not depend on it)")
      ->check(CLI::Range(1, 1024))
      ->default_str("2");
  cmd->add_option("--json", options.json, "Write the results as JSON to FILE ('-' = stdout; the table then goes to stderr)")->type_name("FILE");
  cmd->add_option("--report", options.report, "Write DIR/verification.md, its PNG plots and DIR/verification.json")->type_name("DIR");
  cmd->add_option("--keep", options.keep, "Keep the scenarios and recordings in DIR")->type_name("DIR");
  cmd->add_flag("--list", options.list, "List the tests and their expectations; run nothing");
  cmd->add_option("--throng", options.throng, "The throng binary the tests run (default: this one)")->type_name("PATH");
  return cmd;
}

int runVerify(const VerifyOptions& options) {
  const fs::path exe = currentExecutable();
  const fs::path script = findBundledScript(exe, "verify.py", fs::path(THRONG_SOURCE_DIR) / "scripts");
  if (script.empty()) {
    printLine(stderr, fmt::format("throng verify: error: scripts/verify.py not found (looked in "
                                  "<prefix>/share/throng/scripts and {}/scripts); run it from a source checkout",
                                  THRONG_SOURCE_DIR));
    return kExitFailure;
  }
  const std::string python = findPython();
  if (python.empty()) {
    printLine(stderr, "throng verify: error: python3 not found (install python3, python3-numpy and python3-matplotlib)");
    return kExitFailure;
  }
  std::vector<std::string> argv{python, script.string()};
  const auto rest = scriptArguments(options, exe);
  argv.insert(argv.end(), rest.begin(), rest.end());
  return runScriptAndWait(argv, "verify");
}

}  // namespace throng::cli
