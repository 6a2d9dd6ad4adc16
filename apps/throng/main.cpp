// throng — command-line front end: run, check, info, bench, script, metrics, serve, loadgen, link, verify, plot, import and edit subcommands (CLI11),
// and the hidden describe-cli (the command line as JSON, for the man pages and completions).
// Parses flags, dispatches to the subcommand and turns every failure into a message and an exit
// code: 0 success, 1 bad input or failure, 2 bad flags or unknown subcommand, 130 interrupted.
#include <cstdio>
#include <exception>
#include <initializer_list>
#include <new>
#include <string>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "commands.hpp"
#include "throng/core/diagnostic.hpp"
#include "throng/core/simd.hpp"

namespace {

/// CLI11 reports an unknown command as "A subcommand is required"; this names it instead (with the
/// closest command) on stderr. True when argv[1] is a word that names none of `commands`.
bool reportUnknownCommand(int argc, char** argv, std::initializer_list<const CLI::App*> commands) {
  if (argc <= 1 || argv[1][0] == '-') return false;
  for (const CLI::App* sub : commands) {
    if (sub->check_name(argv[1])) return false;
  }
  const std::string hint = throng::core::closestMatch(argv[1], {"run", "check", "info", "bench", "script", "metrics", "serve", "loadgen", "link", "verify", "plot", "import", "edit"});
  std::fputs(fmt::format("throng: unknown command '{}'; expected run, check, info, bench, script, metrics, serve, loadgen, link, verify, plot, import or edit{}\n"
                         "Run 'throng --help' for more information.\n",
                         argv[1], hint.empty() ? "" : fmt::format(" (did you mean '{}'?)", hint))
                 .c_str(),
             stderr);
  return true;
}

int dispatch(int argc, char** argv) {
  using namespace throng::cli;
  CLI::App app{"throng — a crowd engine for shared virtual worlds.\n"
               "Simulates crowds described by a scenario JSON file and records their trajectories.",
               "throng"};
  app.set_version_flag("--version", THRONG_VERSION, "Print the version and exit");
  app.require_subcommand(1);
  app.footer("Run 'throng COMMAND --help' for the flags of a command.\n"
             "Exit codes: 0 ok, 1 bad input or failure, 2 bad flags, 130 interrupted.\n"
             "Environment: THRONG_SIMD=auto|portable|avx2 picks the vector path of the hot loops (default auto: the\n"
             "widest this CPU runs); every path gives the same trajectories.");

  RunOptions runOptions;
  CheckOptions checkOptions;
  InfoOptions infoOptions;
  BenchOptions benchOptions;
  ScriptOptions scriptOptions;
  MetricsCmdOptions metricsOptions;
  ServeOptions serveOptions;
  LoadgenOptions loadgenOptions;
  LinkOptions linkOptions;
  VerifyOptions verifyOptions;
  PlotOptions plotOptions;
  ImportOptions importOptions;
  EditOptions editOptions;
  CLI::App* run = addRunCommand(app, runOptions);
  CLI::App* check = addCheckCommand(app, checkOptions);
  CLI::App* info = addInfoCommand(app, infoOptions);
  CLI::App* bench = addBenchCommand(app, benchOptions);
  CLI::App* script = addScriptCommand(app, scriptOptions);
  CLI::App* metrics = addMetricsCommand(app, metricsOptions);
  CLI::App* serve = addServeCommand(app, serveOptions);
  CLI::App* loadgen = addLoadgenCommand(app, loadgenOptions);
  CLI::App* link = addLinkCommand(app, linkOptions);
  CLI::App* verify = addVerifyCommand(app, verifyOptions);
  CLI::App* plot = addPlotCommand(app, plotOptions);
  CLI::App* importCmd = addImportCommand(app, importOptions);
  CLI::App* edit = addEditCommand(app, editOptions);
  CLI::App* describe = addDescribeCommand(app);  // hidden: the man pages and completions read it

  if (reportUnknownCommand(argc, argv, {run, check, info, bench, script, metrics, serve, loadgen, link, verify, plot, importCmd, edit, describe})) {
    return kExitUsage;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" with exit code 0; every real parse error exits 2.
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitUsage;
  }
  if (const std::string problem = throng::core::simdRequestProblem(); !problem.empty()) {
    std::fputs(fmt::format("throng: warning: {}\n", problem).c_str(), stderr);
  }

  if (run->parsed()) return runRun(runOptions);
  if (check->parsed()) return runCheck(checkOptions);
  if (info->parsed()) return runInfo(infoOptions);
  if (bench->parsed()) return runBench(benchOptions);
  if (script->parsed()) return runScript(scriptOptions);
  if (metrics->parsed()) return runMetrics(metricsOptions);
  if (serve->parsed()) return runServe(serveOptions);
  if (loadgen->parsed()) return runLoadgen(loadgenOptions);
  if (link->parsed()) return runLink(linkOptions);
  if (verify->parsed()) return runVerify(verifyOptions);
  if (plot->parsed()) return runPlot(plotOptions);
  if (importCmd->parsed()) return runImport(importOptions);
  if (edit->parsed()) return runEdit(editOptions);
  if (describe->parsed()) return runDescribe(app, THRONG_VERSION);
  std::fputs("throng: no command given; run 'throng --help'\n", stderr);
  return kExitUsage;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return dispatch(argc, argv);
  } catch (const std::bad_alloc&) {
    std::fputs("throng: error: out of memory\n", stderr);
  } catch (const std::exception& e) {
    std::fputs(fmt::format("throng: error: {}\n", e.what()).c_str(), stderr);
  } catch (...) {
    std::fputs("throng: error: unknown failure\n", stderr);
  }
  return throng::cli::kExitFailure;
}
