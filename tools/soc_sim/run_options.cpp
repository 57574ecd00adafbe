#include "run_options.h"
#include "transaction_writer.h"

#include <strings.h>

#include <filesystem>
#include <iostream>
#include <optional>
#include <string_view>
#include <utility>

#include <CLI/CLI.hpp>

#include "apps/apps.h"
#include "build_info.h"
#include "cluster/cluster.h"
#include "renderers/backend_parameters.h"
#include "renderers/backends.h"
#include "soc/soc.h"

namespace fs = std::filesystem;

namespace tessera {

namespace {

// soc_sim's own parameters (sim.*): what to run and how the run is watched.
ParamGroup runner_parameters() {
  return {"soc_sim",
          {
              param::text("sim.app", "teapot", "application to run: a built-in name or a path to a shared library"),
              param::integer("sim.frames", 3, 1, 100000, "frames",
                             "frames the application draws before the simulation ends"),
              param::integer("sim.time_limit_ms", 0, 0, 3600000, "ms",
                             "simulated-time limit; a run that reaches it stops with an error (0: automatic, " +
                                 TimeLimit::automatic_rule() + ")"),
              param::integer("sim.stall_limit_s", 60, 0, 86400, "s",
                             "wall-clock time the simulation may go without simulated time advancing (an application "
                             "stuck in its own code) before the run stops with an error (0: no limit)"),
              param::integer("sim.wall_limit_s", 0, 0, 604800, "s",
                             "wall-clock limit of the simulation; a run that reaches it stops with an error and writes "
                             "what is complete (0: no limit)"),
              param::choice("sim.log_level", "warning", {"quiet", "error", "warning", "info", "debug"},
                            "lowest severity of the log lines printed on stderr"),
          },
          {}};
}

// soc_sim's options, bound to `opt`.
void add_options(CLI::App& cli, Options& opt) {
  cli.add_option("--config", opt.config_files, "JSON configuration file(s), applied in order")
      ->check(CLI::ExistingFile);
  cli.add_option("--set", opt.overrides, "override one parameter: key=value (repeatable)");
  cli.add_option("--platform", opt.platform, "soc (the default) or cluster (sim.platform)");
  cli.add_option("--app,--scene", opt.app, "application: a built-in name (see --list-apps)");
  cli.add_option("--backend", opt.backend,
                 "renderer back end (driver.backend): " + backends::backend_names(", ", " or "));
  cli.add_option("--frames", opt.frames, "frames to draw (sim.frames)")->check(CLI::Range(1, 100000));
  cli.add_option("--out", opt.out_dir, "folder for frames and statistics")->capture_default_str();
  cli.add_option("--stats", opt.stats, "write statistics as JSON to FILE (default: <out>/stats.json)");
  cli.add_option("--stats-schema", opt.stats_schema,
                 "write the unit and description of every number of the run's statistics to FILE (JSON; "
                 "docs/statistics.md)");
  cli.add_option("--vcd", opt.vcd, "write a VCD trace to FILE");
  cli.add_option("--fst", opt.fst,
                 "write the same trace as FST (GTKWave's compressed format) to FILE, which must end in .fst; with "
                 "--vcd too, both are written");
  cli.add_option("--report", opt.report,
                 "after the run, write a one-page HTML report of it (frames, frame times, energy, where the time "
                 "went) to FILE, which must end in .html; needs the Python of tessera-sweep (scripts/setup.sh)");
  CLI::Option* timeline =
      cli.add_option("--timeline", opt.timeline,
                     "write a timeline of every block's activity to FILE (Chrome trace-event JSON, for Perfetto)");
  cli.add_option("--timeline-detail", opt.timeline_detail,
                 "with --timeline: frames (frames, vblanks, power and bus counters), blocks (and every block's "
                 "runs: the default) or all (and array stages, single CIU accesses, the host's stalls apart)")
      ->check(CLI::IsMember({"frames", "blocks", "all"}))
      ->needs(timeline);
  cli.add_option("--trace-transactions", opt.trace_transactions,
                 "write every bus transaction matching FILTER to FILE as CSV (FILE[:FILTER], FILTER: key=value,... "
                 "with initiator, target, command=read|write, addr=LO-HI, time=A-B, e.g. tx.csv:initiator=dma,"
                 "time=1ms-2ms)")
      ->check([](const std::string& text) {
        try {
          parse_transaction_trace(text);
          return std::string();
        } catch (const std::invalid_argument& e) {
          return std::string(e.what());
        }
      });
  cli.add_flag("--force", opt.force,
               "remove the outputs of an earlier run (frames, statistics, traces) from the output folder first");
  cli.add_flag("--no-frames", opt.no_frames, "write no PNG frames (they are still counted in the statistics)");
  cli.add_flag("--wall-clock", opt.wall_clock,
               "add each frame's wall-clock and CPU time (wall_ns, cpu_ns) to stats.json, for benchmarks; the file "
               "then differs from run to run");
  CLI::Option* gdb = cli.add_option("--gdb", opt.gdb_port,
                                    "serve GDB's remote protocol on 127.0.0.1:PORT (0: any free port) for the program "
                                    "on the ISS (host.model=iss), which waits for GDB before its first instruction")
                         ->check(CLI::Range(0, 65535));
  cli.add_option("--gdb-port-file", opt.gdb_port_file, "with --gdb: write the port to FILE once listening")->needs(gdb);
  cli.add_flag("--iss-profile", opt.iss_profile,
               "profile the program on the ISS (host.model=iss) per function: stats.json's host.iss.profile (the "
               "40 functions with the most cycles); off, the run is faster and every other figure the same");
  cli.add_flag("--quiet,-q", opt.quiet, "print nothing but errors");
  cli.add_option("--log-level", opt.log_level, "quiet, error, warning, info or debug (sim.log_level)");
  cli.add_flag("--print-config", opt.print_config, "print the effective configuration as JSON and exit");
  cli.add_flag("--config-reference", opt.config_reference, "print the configuration reference (Markdown) and exit");
  cli.add_flag("--list-apps", opt.list_apps, "list the built-in applications and exit");
  // Left-over arguments are rejected below, with advice for a stray word:
  // "soc_sim cubes" means "--app cubes" more often than not.
  cli.allow_extras();
  cli.set_version_flag("--version",
                       std::string("soc_sim (tessera) ") + build_info::version() + ", commit " + build_info::commit(),
                       "print the version and the git commit soc_sim was built from, and exit");
  const uint64_t default_frames = Config(all_parameters()).get_uint("sim.frames");
  cli.footer(
      "Arguments after -- go to the application, e.g. soc_sim --app obj_viewer -- model.obj\n"
      "(AppEnvironment::args); soc_sim itself takes no positional arguments.\n\n"
      "Simulated-time limit (sim.time_limit_ms): the value a --config file or --set gives;\n"
      "0 (the default): automatic, " +
      TimeLimit::automatic_rule() + " (" + std::to_string(choose_time_limit(default_frames, 0).ms / 1000) +
      " s for the default " + std::to_string(default_frames) +
      " frames).\nThe summary and stats.json show the limit in effect; reaching it is an error (status 1).\n\n"
      "A run that cannot finish ends by itself: sim.stall_limit_s (wall-clock seconds without\n"
      "simulated progress, default 60) and sim.wall_limit_s (wall-clock limit, default none)\n"
      "stop it with status 1. SIGINT or SIGTERM stops it at the next safe point with status\n"
      "128 + signal; a crash is reported with the frame reached. stats.json says how the run\n"
      "ended (run_status), and every output is whole or absent.");
}

// What the parser left that it should not have: an option given an empty
// value, or a word before "--". Prints why and returns EXIT_USAGE; nothing
// if all is well.
std::optional<int> reject_leftovers(const CLI::App& cli, const Options& opt) {
  // An option given with an empty value is a mistake (an unset shell
  // variable, say), not a request for the default.
  const std::pair<const char*, const std::string*> valued_options[] = {{"--app", &opt.app},
                                                                       {"--backend", &opt.backend},
                                                                       {"--log-level", &opt.log_level},
                                                                       {"--fst", &opt.fst},
                                                                       {"--report", &opt.report}};
  for (const auto& [option, value] : valued_options)
    if (cli.count(option) > 0 && value->empty()) {
      std::cerr << "soc_sim: " << option << " was given an empty value: give one (soc_sim --help"
                << (std::string_view(option) == "--app" ? ", soc_sim --list-apps" : "")
                << "), or leave the option out for the default\n";
      return EXIT_USAGE;
    }
  if (cli.remaining().empty()) return std::nullopt;
  const std::string word = cli.remaining().front();
  if (word.size() > 1 && word[0] == '-') {
    std::cerr << "soc_sim: unknown option '" << word << "' (soc_sim --help lists the options)\n";
    return EXIT_USAGE;
  }
  std::cerr << "soc_sim: unexpected argument '" << word << "' before '--': ";
  if (builtin_apps().count(word))
    std::cerr << "to run the application '" << word << "', use --app " << word;
  else
    std::cerr << "choose the application with --app NAME (soc_sim --list-apps)";
  std::cerr << "; arguments for the application go after '--', e.g. soc_sim --app obj_viewer -- model.obj\n";
  return EXIT_USAGE;
}

bool has_extension(const std::string& path, std::string_view extension) {
  const std::string given = fs::path(path).extension().string();
  return given.size() == extension.size() && strcasecmp(given.c_str(), extension.data()) == 0;
}

// The trace's format is the option's, never guessed from the name; a name
// whose extension says the other format (or none the report's) is a
// mistake, told before the run. Prints why and returns EXIT_USAGE.
std::optional<int> check_output_names(const Options& opt) {
  std::string problem;
  if (!opt.vcd.empty() && has_extension(opt.vcd, ".fst"))
    problem = "--vcd writes a VCD, but '" + opt.vcd + "' is named as an FST: use --fst " + opt.vcd + " for FST";
  else if (!opt.fst.empty() && !has_extension(opt.fst, ".fst"))
    problem = "--fst writes an FST, and its file must end in .fst (got '" + opt.fst + "')" +
              (has_extension(opt.fst, ".vcd") ? ": use --vcd " + opt.fst + " for a VCD" : "");
  else if (!opt.fst.empty() && !opt.vcd.empty() && fs::path(opt.fst) == fs::path(opt.vcd))
    problem = "--vcd and --fst name the same file '" + opt.fst + "'";
  else if (!opt.report.empty() && !has_extension(opt.report, ".html"))
    problem = "--report writes an HTML page, and its file must end in .html (got '" + opt.report + "')";
  if (problem.empty()) return std::nullopt;
  std::cerr << "soc_sim: " << problem << "\n";
  return EXIT_USAGE;
}

// On the cluster platform every node runs the sort-middle program
// (cluster_node); a scene named with --scene (sim.app) is the program's
// cluster.scene. Throws ConfigError for anything else.
void choose_cluster_program(Config& config) {
  constexpr const char* PROGRAM = "cluster_node";
  if (config.is_set("sim.app") && config.get_string("sim.app") != PROGRAM) {
    const std::string scene = config.get_string("sim.app");
    try {
      config.set("cluster.scene", scene, "--scene");
    } catch (const ConfigError&) {
      throw ConfigError("sim.platform=cluster draws the scenes of cluster.scene (random_triangles or teapot), not '" +
                        scene + "'");
    }
  }
  config.set("sim.app", PROGRAM, "sim.platform=cluster");
}

// The configuration files, the overrides and the options that set a
// parameter, applied in that order, then validated. Throws ConfigError.
Config effective_configuration(const Options& opt) {
  Config config(all_parameters());
  for (const auto& file : opt.config_files) config.load_file(file);
  for (const auto& assignment : opt.overrides) config.apply_override(assignment);
  if (!opt.platform.empty()) config.set("sim.platform", opt.platform, "--platform");
  if (!opt.app.empty()) config.set("sim.app", opt.app, "--app");
  if (opt.frames > 0) config.set("sim.frames", opt.frames, "--frames");
  if (!opt.backend.empty()) config.set("driver.backend", opt.backend, "--backend");
  if (!opt.log_level.empty()) config.set("sim.log_level", opt.log_level, "--log-level");
  if (opt.quiet) config.set("sim.log_level", "error", "--quiet");
  if (config.get_string("sim.platform") == "cluster") choose_cluster_program(config);
  // An ARM executable runs on the ISS: host.model follows the application
  // unless the user chose it.
  if (is_elf_app(config.get_string("sim.app"))) {
    if (!config.is_set("host.model"))
      config.set("host.model", "iss", "--app " + config.get_string("sim.app"));
    else if (config.get_string("host.model") != "iss")
      throw ConfigError(
          "configuration: impossible combination: sim.app=" + config.get_string("sim.app") +
          " is an ARM executable, which runs on the ISS, and host.model=" + config.get_string("host.model"));
  }
  // The chosen back end fills in what it needs that the user left unset.
  if (const backends::Backend* chosen = backends::find_backend(config.get_string("driver.backend")))
    chosen->adjust_configuration(config);
  config.validate();
  return config;
}

// --iss-profile and --gdb are for a program on the ISS. Prints why and
// returns EXIT_USAGE when the host is host-compiled; nothing otherwise.
std::optional<int> check_iss_options(const Options& opt, const Config& config) {
  const std::string& model = config.get_string("host.model");
  if (opt.iss_profile && model != "iss") {
    std::cerr << "soc_sim: impossible combination: --iss-profile profiles a program on the ISS, and host.model="
              << model
              << " runs the application host-compiled (set host.model=iss, or run an ARM executable with --app "
                 "program.elf)\n";
    return EXIT_USAGE;
  }
  if (opt.gdb_port >= 0 && config.get_string("sim.platform") == "cluster") {
    std::cerr << "soc_sim: impossible combination: --gdb debugs the SoC's one program, and sim.platform=cluster runs "
                 "cluster.nodes of them\n";
    return EXIT_USAGE;
  }
  if (!opt.stats_schema.empty() && config.get_string("sim.platform") == "cluster") {
    std::cerr << "soc_sim: impossible combination: --stats-schema describes the SoC platform's statistics, and "
                 "sim.platform=cluster's are not described yet (docs/statistics.md)\n";
    return EXIT_USAGE;
  }
  if (opt.gdb_port >= 0 && model != "iss") {
    std::cerr << "soc_sim: impossible combination: --gdb debugs a program on the ISS, and host.model=" << model
              << " runs the application host-compiled (set host.model=iss, or run an ARM executable with --app "
                 "program.elf)\n";
    return EXIT_USAGE;
  }
  return std::nullopt;
}

}  // namespace

std::vector<ParamGroup> soc_parameters() {
  std::vector<ParamGroup> groups = {runner_parameters()};
  for (ParamGroup& group : driver_parameter_groups()) groups.push_back(std::move(group));
  for (ParamGroup& group : Soc::parameter_groups()) groups.push_back(std::move(group));
  return groups;
}

std::vector<ParamGroup> all_parameters() {
  std::vector<ParamGroup> groups = soc_parameters();
  groups.push_back({"platform",
                    {param::choice("sim.platform", "soc", {"soc", "cluster"},
                                   "what is simulated: the SoC, or the cluster platform of cluster.nodes ARM922T "
                                   "nodes and a network running the sort-middle renderer (docs/cluster.md)")},
                    {}});
  for (ParamGroup& group : Cluster::parameter_groups()) groups.push_back(std::move(group));
  return groups;
}

Config soc_view(const Config& config) {
  Config view(soc_parameters());
  for (const ParamSpec& spec : view.specs())
    if (config.is_set(spec.key)) view.set(spec.key, config.get_json(spec.key), "the run's configuration");
  return view;
}

std::variant<RunPlan, int> read_command_line(int argc, char* argv[]) {
  Options opt;
  CLI::App cli{"tessera soc_sim: run an application on the virtual mobile graphics SoC"};
  add_options(cli, opt);
  // CLI11 sees only what comes before the first "--": the rest belongs to
  // the application, so a word before it is an error, not an argument.
  int own_argc = argc;
  for (int i = 1; i < argc; ++i)
    if (std::string_view(argv[i]) == "--") {
      own_argc = i;
      opt.app_args.assign(argv + i + 1, argv + argc);
      break;
    }
  try {
    cli.parse(own_argc, argv);
  } catch (const CLI::ParseError& e) {
    return cli.exit(e) == 0 ? 0 : EXIT_USAGE;
  }
  if (const std::optional<int> status = reject_leftovers(cli, opt)) return *status;
  if (const std::optional<int> status = check_output_names(opt)) return *status;

  if (opt.config_reference) {
    std::cout << Config(all_parameters()).reference_markdown();
    return 0;
  }
  if (opt.list_apps) {
    for (const auto& [name, info] : builtin_apps()) std::cout << name << "  " << info.description << "\n";
    return 0;
  }

  std::optional<Config> config;
  try {
    config.emplace(effective_configuration(opt));
  } catch (const ConfigError& e) {
    std::cerr << "soc_sim: " << e.what() << "\n";
    return EXIT_USAGE;
  }
  const TimeLimit time_limit = choose_time_limit(config->get_uint("sim.frames"), config->get_uint("sim.time_limit_ms"));
  if (opt.print_config) {
    std::cout << config->to_json().dump(2) << "\n";
    return 0;
  }
  if (const std::optional<int> status = check_iss_options(opt, *config)) return *status;

  LaunchableApp app;
  try {
    const bool on_iss = config->get_string("host.model") == "iss";
    app = config->get_string("sim.platform") == "cluster" ? cluster_node_program(on_iss)
                                                          : find_app(config->get_string("sim.app"), on_iss);
  } catch (const std::invalid_argument& e) {
    std::cerr << "soc_sim: " << e.what() << "\n";
    return EXIT_USAGE;
  }
  return RunPlan{std::move(opt), std::move(*config), time_limit, std::move(app),
                 std::vector<std::string>(argv, argv + argc)};
}

}  // namespace tessera
