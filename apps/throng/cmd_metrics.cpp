// `throng metrics FILE.sqlite [--json] [--radius R] [--bin S]` — the social-model evaluation of a
// recording (docs/social-metrics.md): arrival rate at destinations over time, congestion at key
// points, group cohesion and Common Ground coordination statistics. Reads the file once (a
// progress bar on a terminal while trajectory_data is read); --json prints one JSON object.
#include <cmath>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "output.hpp"
#include "progress.hpp"
#include "throng/recording/recording_social.hpp"
#include "validators.hpp"

namespace throng::cli {
namespace {

using nlohmann::json;

json densityJson(const recording::DensityStats& d) {
  json j{{"category", d.category}, {"samples", d.samples}, {"mean", d.mean}, {"p95", d.p95}, {"max", d.max}};
  if (d.point.empty()) {
    j["points"] = d.points;
  } else {
    j["point"] = d.point;
    j["index"] = d.pointIndex;
  }
  return j;
}

json toJson(const recording::SocialMetrics& m) {
  json bins = json::array();
  for (const recording::ArrivalBin& b : m.arrivals) {
    bins.push_back({{"start", b.start}, {"visits", b.visits}, {"by_category", b.byCategory}, {"exits", b.exits}});
  }
  json congestion = json::array(), worst = json::array();
  for (const auto& d : m.congestion) congestion.push_back(densityJson(d));
  for (const auto& d : m.worstPoints) worst.push_back(densityJson(d));
  const recording::CoordinationStats& c = m.coordinations;
  return {{"recording", m.path},
          {"common_ground", m.commonGround.empty() ? json(nullptr) : json(m.commonGround)},
          {"fps", m.fps},
          {"frames", m.frames},
          {"duration_s", m.duration},
          {"options", {{"radius_m", m.radius}, {"bin_s", m.bin}, {"cohesion_radius_m", m.cohesionRadius}}},
          {"arrivals",
           {{"categories", m.categories},
            {"visits", m.visits},
            {"exits", m.exits},
            {"visits_by_category", m.visitsByCategory},
            {"visits_per_minute", m.visitsPerMinute},
            {"exits_per_minute", m.exitsPerMinute},
            {"bins", bins}}},
          {"congestion", {{"unit", "agents/m^2"}, {"by_category", congestion}, {"worst_points", worst}}},
          {"cohesion",
           {{"group_frames", m.cohesion.groupFrames},
            {"groups", m.cohesion.groups},
            {"mean_distance_m", m.cohesion.meanDistance},
            {"share_together", m.cohesion.shareTogether}}},
          {"coordinations",
           {{"total", c.total},
            {"by_plan", c.byPlan},
            {"by_outcome", c.byOutcome},
            {"by_relation", c.byRelation},
            {"by_trigger", c.byTrigger},
            {"micro_behaviours", c.microBehaviours},
            {"grounding_samples", c.groundingSamples},
            {"grounding_mean_s", c.meanGrounding},
            {"grounding_max_s", c.maxGrounding},
            {"divide_samples", c.divideSamples},
            {"divide_mean_s", c.meanDivide},
            {"reunited", c.reunited},
            {"goals_generated", c.goalsGenerated}}}};
}

std::string countsText(const std::map<std::string, std::uint64_t>& counts) {
  std::string out;
  for (const auto& [name, n] : counts) out += fmt::format("{}{} {}", out.empty() ? "" : ", ", name.empty() ? "(none)" : name, n);
  return out.empty() ? "none" : out;
}

void printReport(const recording::SocialMetrics& m) {
  printLine(stdout, fmt::format("recording      {}", m.path));
  printLine(stdout, fmt::format("common ground  {}", m.commonGround.empty() ? "no social section" : m.commonGround));
  printLine(stdout, fmt::format("frames         {} at {:g} fps ({})", m.frames, m.fps, formatSeconds(m.duration)));
  printLine(stdout, "");

  printLine(stdout, fmt::format("Arrivals at destinations (visit starts), bins of {:g} s", m.bin));
  printLine(stdout, fmt::format("  {} visits ({:.2f}/min), {} exits ({:.2f}/min); by category: {}", m.visits,
                                m.visitsPerMinute, m.exits, m.exitsPerMinute, countsText(m.visitsByCategory)));
  std::vector<std::string> columns = m.categories;
  for (const auto& [category, n] : m.visitsByCategory) {
    if (std::find(columns.begin(), columns.end(), category) == columns.end()) columns.push_back(category);
  }
  // Each category column as wide as its name (at least 10), so no header is cut.
  std::vector<std::size_t> widths;
  for (const auto& col : columns) widths.push_back(std::max<std::size_t>(10, col.empty() ? 6 : col.size()));
  std::string header = fmt::format("  {:>13} {:>7}", "from [s]", "visits");
  for (std::size_t c = 0; c < columns.size(); ++c) {
    header += fmt::format(" {:>{}}", columns[c].empty() ? "(none)" : columns[c], widths[c]);
  }
  header += fmt::format(" {:>7}", "exits");
  printLine(stdout, header);
  for (const recording::ArrivalBin& b : m.arrivals) {
    std::string row = fmt::format("  {:>13g} {:>7}", b.start, b.visits);
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const auto it = b.byCategory.find(columns[c]);
      row += fmt::format(" {:>{}}", it == b.byCategory.end() ? 0 : it->second, widths[c]);
    }
    row += fmt::format(" {:>7}", b.exits);
    printLine(stdout, row);
  }
  printLine(stdout, "");

  printLine(stdout, fmt::format("Congestion at key points (agents within {:g} m, per m^2, per frame)", m.radius));
  if (m.congestion.empty()) printLine(stdout, "  no points with a category");
  else printLine(stdout, fmt::format("  {:<16} {:>6} {:>8} {:>8} {:>8}", "category", "points", "mean", "p95", "max"));
  for (const auto& d : m.congestion) {
    printLine(stdout, fmt::format("  {:<16} {:>6} {:>8.3f} {:>8.3f} {:>8.3f}", d.category, d.points, d.mean, d.p95, d.max));
  }
  if (!m.worstPoints.empty()) {
    printLine(stdout, "  most congested points (by mean density):");
    for (const auto& d : m.worstPoints) {
      printLine(stdout, fmt::format("    {:<16} {:<12} mean {:.3f}  p95 {:.3f}  max {:.3f}", d.point, d.category, d.mean,
                                    d.p95, d.max));
    }
  }
  printLine(stdout, "");

  printLine(stdout, "Group cohesion (members' distance to their group's centroid)");
  printLine(stdout, fmt::format("  {} group-frames of {} groups; mean distance {:.2f} m; all within {:g} m in {:.1f}%",
                                m.cohesion.groupFrames, m.cohesion.groups, m.cohesion.meanDistance, m.cohesionRadius,
                                m.cohesion.shareTogether * 100.0));
  printLine(stdout, "");

  const recording::CoordinationStats& c = m.coordinations;
  printLine(stdout, fmt::format("Coordinations: {} ({} goals generated)", c.total, c.goalsGenerated));
  printLine(stdout, fmt::format("  by outcome       {}", countsText(c.byOutcome)));
  printLine(stdout, fmt::format("  by plan          {}", countsText(c.byPlan)));
  printLine(stdout, fmt::format("  by relation      {}", countsText(c.byRelation)));
  printLine(stdout, fmt::format("  by trigger       {}", countsText(c.byTrigger)));
  printLine(stdout, fmt::format("  micro-behaviours {}", countsText(c.microBehaviours)));
  printLine(stdout, fmt::format("  grounding        mean {:.2f} s, max {:.2f} s over {} coordinations", c.meanGrounding,
                                c.maxGrounding, c.groundingSamples));
  printLine(stdout, fmt::format("  divided          mean {:.2f} s over {} divide plans; {} reunions", c.meanDivide,
                                c.divideSamples, c.reunited));
}

}  // namespace

CLI::App* addMetricsCommand(CLI::App& app, MetricsCmdOptions& options) {
  CLI::App* cmd = app.add_subcommand("metrics", "Measure arrivals, congestion, cohesion and coordinations");
  cmd->footer(
      "Evaluate a Common Ground recording (docs/social-metrics.md): visits started per time bin by\n"
      "destination category and exits; density around every point with a category (mean, 95th\n"
      "percentile, max, the five most congested points); group cohesion; coordination counts by plan,\n"
      "outcome, relation and trigger, micro-behaviours, grounding and divide durations, reunions.");
  cmd->add_option("recording", options.recording, "Recording written by 'throng run'")
      ->required()
      ->type_name("FILE.sqlite");
  cmd->add_option("--radius", options.radius, "Congestion radius around key points [m]")
      ->capture_default_str()
      ->check(positiveNumber("m"));
  cmd->add_option("--bin", options.bin, "Width of the arrival-rate bins [s]")
      ->capture_default_str()
      ->check(positiveNumber("s"));
  cmd->add_flag("--json", options.json, "Print the metrics as one JSON object");
  return cmd;
}

int runMetrics(const MetricsCmdOptions& options) {
  if (auto missing = checkInputFile(options.recording, "recording"); !missing.empty()) {
    printDiagnostics(missing);
    return kExitFailure;
  }
  recording::MetricsOptions mo;
  mo.radius = options.radius;
  mo.bin = options.bin;
  ProgressLine progress(stderr, true);  // draws only on a terminal
  if (progress.enabled()) {
    mo.progress = [&progress](double fraction) {
      if (!progress.due()) return;
      progress.draw(fmt::format("reading trajectories {} {:3.0f}%", formatBar(fraction, 30), fraction * 100.0));
    };
  }
  auto metrics = recording::computeMetrics(options.recording, mo);
  progress.clear();
  if (!metrics) {
    printDiagnostics(metrics.errors());
    return kExitFailure;
  }
  if (options.json) {
    printLine(stdout, toJson(*metrics).dump());
  } else {
    printReport(*metrics);
  }
  return kExitOk;
}

}  // namespace throng::cli
