#include "roadload/firmware/command_line.hpp"

#include <optional>

#include <CLI/CLI.hpp>

#include "roadload/cli/help.hpp"
#include "roadload/cli/parse.hpp"
#include "roadload/cli/values.hpp"

namespace roadload::firmware {
namespace {

// What the options set, laid over the configuration file once it is read: an option overrides
// the file wherever it stands, before --config or after it.
struct Overrides {
  std::string config_file;
  std::vector<std::string> can;  // replaces the configured buses
  std::optional<std::string> data_dir, status, status_json, vehicle, route, results, replay, replay_origin;
  std::optional<double> replay_rate;
  bool no_record = false, no_gnss = false, replay_can = false;
};

const cli::HelpText kHelp{"usage: roadloadd [--config FILE] [options]",
                          "Records J1939 CAN traffic, accelerometers and GNSS on one capture clock, estimates the\n"
                          "coefficient of rolling resistance live, and writes a status line per second.\n"
                          "Without --config the built-in defaults apply (config/roadloadd.toml documents them).",
                          "Signals: SIGTERM/SIGINT flush and exit; SIGHUP reopens the status files (logrotate) without\n"
                          "cutting the recording; SIGUSR1 ends the recording segment and starts a new one."};

void add_options(CLI::App& app, Overrides& o, CommandLine& cl) {
  cli::describe(app, kHelp);
  app.add_option("--config", o.config_file, "settings in TOML")->type_name("FILE");
  app.add_option("--can", o.can, "listen on IFACE; repeatable; replaces the configured buses")->type_name("IFACE");
  app.add_option("--data-dir", o.data_dir, "record into DIR (recording.data_dir)")->type_name("DIR");
  app.add_flag("--no-record", o.no_record, "record nothing (status and estimate only)");
  app.add_option("--status", o.status, "status text, one line per interval (status.text_file)")->type_name("FILE");
  app.add_option("--status-json", o.status_json, "status as JSON lines; '' for none (status.json_file)")->type_name("FILE");
  app.add_option("--vehicle", o.vehicle, "vehicle file or built-in name: the truck recorded and\nmodelled (vehicle.file)")
      ->type_name("V");
  app.add_option("--route", o.route, "route file or built-in route name: cells for the live CRR")->type_name("R");
  app.add_option("--results", o.results, "at exit, DIR/cells.csv and DIR/trip.json from the live filter")->type_name("DIR");
  app.add_flag("--no-gnss", o.no_gnss, "do not connect to gpsd");
  app.add_option("--replay", o.replay,
                 "accelerometer, GNSS and weather streams from recording folder\nREC (a can.log alone, with --replay-can)")
      ->type_name("REC");
  app.add_option("--replay-rate", o.replay_rate, "their pace: 1 real time, N times faster, 0 as fast as read")
      ->type_name("R")
      ->check(cli::finite());
  app.add_flag("--replay-can", o.replay_can, "CAN from the recording too, instead of the buses");
  app.add_option("--replay-origin", o.replay_origin, "wait for `roadload replay --origin FILE` and replay in step\nwith its CAN")
      ->type_name("FILE");
  app.add_flag("--exit-when-done", cl.exit_when_done, "exit once every replayed stream has ended");
  app.add_flag("--print-config", cl.print_config, "print the effective settings as TOML and exit");
}

void apply(const Overrides& o, DaemonConfig& c) {
  if (!o.can.empty()) {
    c.can.clear();
    for (const std::string& iface : o.can) {
      CanBusConfig bus;
      bus.interface = iface;
      c.can.push_back(bus);
    }
  }
  if (o.no_record) c.recording.enabled = false;
  if (o.no_gnss) c.gnss.enabled = false;
  if (o.replay_can) c.replay.can = true;
  for (const auto& [value, into] : {std::pair{&o.data_dir, &c.recording.data_dir}, std::pair{&o.status, &c.status.text_file},
                                    std::pair{&o.status_json, &c.status.json_file}, std::pair{&o.vehicle, &c.vehicle.file},
                                    std::pair{&o.route, &c.estimator.route}, std::pair{&o.results, &c.estimator.results_dir},
                                    std::pair{&o.replay, &c.replay.recording}, std::pair{&o.replay_origin, &c.replay.origin_file}}) {
    if (*value) *into = **value;
  }
  if (o.replay_rate) c.replay.rate = *o.replay_rate;
}

}  // namespace

Parsed<CommandLine> parse_command_line(const std::vector<std::string>& args) {
  CommandLine cl;
  Overrides o;
  CLI::App app("", "roadloadd");
  add_options(app, o, cl);
  const cli::Outcome read = cli::parse(app, args, std::string("roadloadd ") + ROADLOAD_VERSION);
  if (read.kind == cli::Outcome::Kind::usage_error) return ParseError{kCommandLineSource, 0, read.field, read.text + " (see --help)"};
  if (read.kind == cli::Outcome::Kind::print) {
    cl.print = read.text;
    return cl;
  }
  if (!o.config_file.empty()) {
    auto c = load_config(o.config_file);
    if (!c) return c.error();
    cl.config = std::move(c.value());
  }
  apply(o, cl.config);
  if (auto e = validate(cl.config)) return *e;
  return cl;
}

}  // namespace roadload::firmware
