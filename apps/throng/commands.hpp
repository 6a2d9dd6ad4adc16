// throng CLI subcommands — each subcommand registers its flags on a CLI::App and runs from a plain
// options struct (one file per subcommand: cmd_run.cpp, cmd_check.cpp, cmd_info.cpp,
// cmd_bench.cpp, cmd_script.cpp, cmd_metrics.cpp, cmd_serve.cpp, cmd_loadgen.cpp, cmd_link.cpp, cmd_verify.cpp, cmd_plot.cpp, cmd_import.cpp, cmd_edit.cpp; the hidden describe-cli in cmd_describe.cpp). Exit codes: 0 success, 1 bad input or failure, 2 bad flags (CLI11), 130
// interrupted by SIGINT/SIGTERM.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace throng::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitUsage = 2;
inline constexpr int kExitInterrupted = 130;

struct RunOptions {
  std::string scenario;                 ///< scenario JSON path
  std::optional<std::uint64_t> seed;    ///< overrides the scenario's seed
  std::optional<double> duration;       ///< overrides the scenario's duration [s]
  int threads = 0;                      ///< 0 = all hardware threads
  std::string out;                      ///< recording path; empty = <scenario stem>.sqlite
  bool force = false;                   ///< overwrite an existing recording
  double fps = 10.0;                    ///< recorded frames per second [Hz]
  bool quiet = false;                   ///< only errors
  bool json = false;                    ///< summary as one JSON object
  std::optional<bool> commonGround;     ///< overrides the scenario's "social"/"commonGround"
  bool phaseTimes = false;              ///< time every phase of the tick and print the totals
};

struct CheckOptions {
  std::string scenario;
  bool json = false;
};

struct InfoOptions {
  std::string recording;
  bool json = false;
};

struct ScriptOptions {
  std::string recording;
  std::uint32_t agent = 0;                  ///< stable agent id
  std::optional<std::uint32_t> coordination;  ///< only this coordination
  bool json = false;                        ///< one JSON object: coordinations, entries, trajectory
};

struct MetricsCmdOptions {
  std::string recording;
  double radius = 2.0;  ///< congestion disc around key points [m]
  double bin = 60.0;    ///< arrival-rate bin [s]
  bool json = false;
};

struct BenchOptions {
  std::vector<std::size_t> agents;      ///< agent counts (in-memory scenarios); empty = 1000,10000,100000
  std::vector<int> threads;             ///< thread counts; empty = 1,2
  std::string scenario = "random";      ///< "random", "navmesh", "musse", "mall" or a scenario file path
  int ticks = 0;                        ///< timed ticks per configuration; 0 = about 3 s each (file: to the end)
  int warmup = 20;                      ///< untimed ticks before timing (in-memory scenarios)
  std::uint64_t seed = 1;               ///< in-memory scenarios' seed (a file keeps its own)
  std::optional<double> duration;       ///< caps a scenario file's simulated time [s]
  bool record = false;                  ///< also time each configuration while recording
  double fps = 10.0;                    ///< recorded frames per second with `record` [Hz]
  bool json = false;                    ///< one JSON object per line
  bool noBaseline = false;              ///< skip DetourCrowd
  std::size_t baselineMax = 20000;      ///< largest agent count DetourCrowd runs at
  bool phaseTimes = false;              ///< also time every phase of the timed ticks
  std::string model;                    ///< every population walks with this model (its defaults); empty = as given
  std::string rowOrder = "auto";        ///< "auto", "id" or "spatial" (sim::RowOrder)
};

struct ServeOptions {
  std::string scenario;
  int port = 8080;                      ///< HTTP + WebSocket; 0 = any free port
  int udpPort = 8081;                   ///< 0 = any free port
  int udpFragment = 1200;               ///< largest datagram to UDP clients [bytes]; larger messages go as Fragments
  std::string bind = "127.0.0.1";
  std::optional<double> tick;           ///< ticks per second; default 1/dt
  int maxClients = 100;
  int threads = 0;
  std::optional<std::uint64_t> seed;
  std::optional<double> duration;       ///< wall-clock seconds; default until Ctrl-C
  std::string web;                      ///< viewer files; default web/dist of the source tree
  double budgetKbit = 500.0;            ///< per-client bandwidth target [kbit/s]
  std::string recordings;               ///< --recordings DIR: recordings a viewer may list, open, upload; empty = none
  int maxUploadMiB = 256;               ///< largest recording a viewer may upload [MiB]
  bool quiet = false;
  bool json = false;
};

struct EditOptions {
  std::string file;                     ///< scenario to edit; empty = none (download only)
  int port = 8080;                      ///< HTTP; 0 = any free port
  std::string host = "127.0.0.1";
  bool open = false;                    ///< open the default browser
  std::string web;                      ///< built pages; default web/dist of the source tree
};

struct LoadgenOptions {
  std::string url = "ws://127.0.0.1:8080/ws";
  int clients = 10;
  double duration = 10.0;               ///< [s]
  bool udp = false;                     ///< native clients over UDP instead of WebSocket
  int udpPort = 8081;                   ///< the server's UDP port (the URL gives the host)
  double guideShare = 0.5;              ///< share of the clients that guide a group
  std::vector<double> at;               ///< --at X,Y: every avatar's loop centre [m]; empty = random in the world
  double loopRadius = 0.0;              ///< --loop-radius [m]; 0 = random in [2, 5] m
  bool json = false;
  bool quiet = false;
};

struct LinkOptions {
  std::string scenario;
  std::string shm;                      ///< segment name ("/throng-1"); default with --socket: /throng-<pid>
  std::string socket;                   ///< UNIX socket path for the name handshake; empty = none
  std::optional<double> tick;           ///< ticks per second; default 1/dt
  std::optional<double> duration;       ///< wall-clock seconds; default until Ctrl-C or the host leaves
  int maxAgents = 10000;                ///< agent records per frame
  int maxDetailed = 16;                 ///< agents with joint angles per frame
  int maxAvatars = 16;
  int maxGuides = 16;
  double hostTimeout = 2.0;             ///< host heartbeat silence that means it is gone [s]
  bool keepAlive = false;               ///< wait for the next host instead of exiting when it leaves
  bool lockstep = false;                ///< step only after the host posts input_written
  bool force = false;                   ///< replace an existing segment / socket file
  int threads = 0;
  std::optional<std::uint64_t> seed;
  bool quiet = false;
};

struct VerifyOptions {
  std::string suite = "all";            ///< rimea, nist, iso or all
  std::vector<std::string> tests;       ///< test ids (each may be a comma list); empty = the whole suite
  std::string model;                    ///< NAME[,NAME]: run every test with each; empty = engine default
  int threads = 2;                      ///< simulations at a time
  std::string json;                     ///< results as JSON to this file ("-" = stdout)
  std::string report;                   ///< Markdown and PNG report directory
  std::string keep;                     ///< keep scenarios and recordings here
  bool list = false;                    ///< list the tests, run nothing
  std::string throng;                   ///< the binary the tests run; empty = this one
};

struct PlotOptions {
  std::string recording;                ///< recording path
  std::string out;                      ///< PNG directory; empty = <recording stem>-plots
  std::vector<std::string> what;        ///< figures; empty = all
  std::vector<double> line;             ///< x0, y0, x1, y1 [m]; empty = one in front of each exit
  std::vector<double> area;             ///< rectangle corners x0, y0, x1, y1 [m]; empty = behind the first exit's line
  double cell = 0.5;                    ///< heatmap cell size [m]
  std::string density = "classic";      ///< the density heatmap's definition: classic or voronoi
  std::string speed = "classic";        ///< the speed heatmap's definition: classic or voronoi
  bool json = false;                    ///< files and numbers as one JSON object
};

struct ImportOptions {
  std::string plan;                     ///< DXF or WKT floor plan
  std::string out;                      ///< scenario path; empty = <plan stem>.json; "-" = stdout
  double scale = 1.0;                   ///< multiplies coordinates after the file's units
  std::vector<std::string> layers;      ///< NAME=ROLE (walkable, obstacle, wall, ignore)
  double wallThickness = 0.2;           ///< [m]
  bool force = false;                   ///< overwrite an existing scenario file
  bool json = false;                    ///< result as one JSON object
};

/// Each registers its subcommand (flags bound to `options`, which must outlive parsing) and returns it.
CLI::App* addRunCommand(CLI::App& app, RunOptions& options);
CLI::App* addCheckCommand(CLI::App& app, CheckOptions& options);
CLI::App* addInfoCommand(CLI::App& app, InfoOptions& options);
CLI::App* addBenchCommand(CLI::App& app, BenchOptions& options);
CLI::App* addScriptCommand(CLI::App& app, ScriptOptions& options);
CLI::App* addMetricsCommand(CLI::App& app, MetricsCmdOptions& options);
CLI::App* addServeCommand(CLI::App& app, ServeOptions& options);
CLI::App* addLoadgenCommand(CLI::App& app, LoadgenOptions& options);
CLI::App* addLinkCommand(CLI::App& app, LinkOptions& options);
CLI::App* addVerifyCommand(CLI::App& app, VerifyOptions& options);
CLI::App* addPlotCommand(CLI::App& app, PlotOptions& options);
CLI::App* addImportCommand(CLI::App& app, ImportOptions& options);
CLI::App* addEditCommand(CLI::App& app, EditOptions& options);

int runRun(const RunOptions& options);
int runCheck(const CheckOptions& options);
int runInfo(const InfoOptions& options);
int runBench(const BenchOptions& options);
int runScript(const ScriptOptions& options);
int runMetrics(const MetricsCmdOptions& options);
int runServe(const ServeOptions& options);
int runLoadgen(const LoadgenOptions& options);
int runLink(const LinkOptions& options);
int runVerify(const VerifyOptions& options);
int runPlot(const PlotOptions& options);
int runImport(const ImportOptions& options);
int runEdit(const EditOptions& options);

/// The hidden `describe-cli` (cmd_describe.cpp): prints `app`'s subcommands and options as JSON.
CLI::App* addDescribeCommand(CLI::App& app);
int runDescribe(const CLI::App& app, const char* version);

}  // namespace throng::cli
