#include "roadload/firmware/command_line.hpp"

#include <charconv>

namespace roadload::firmware {

const char* const kUsage =
    "usage: roadloadd [--config FILE] [options]\n"
    "\n"
    "Records J1939 CAN traffic, accelerometers and GNSS on one capture clock, estimates the\n"
    "coefficient of rolling resistance live, and writes a status line per second.\n"
    "Without --config the built-in defaults apply (config/roadloadd.toml documents them).\n"
    "\n"
    "  --config FILE        settings in TOML\n"
    "  --can IFACE          listen on IFACE; repeatable; replaces the configured buses\n"
    "  --data-dir DIR       record into DIR (recording.data_dir)\n"
    "  --no-record          record nothing (status and estimate only)\n"
    "  --status FILE        status text, one line per interval (status.text_file)\n"
    "  --status-json FILE   status as JSON lines; '' for none (status.json_file)\n"
    "  --vehicle V          vehicle file or built-in name: the truck recorded and modelled (vehicle.file)\n"
    "  --route R            route file or built-in route name: cells for the live CRR\n"
    "  --results DIR        at exit, DIR/cells.csv and DIR/trip.json from the live filter\n"
    "  --no-gnss            do not connect to gpsd\n"
    "  --replay REC         accelerometer, GNSS and weather streams from recording folder REC\n"
    "                       (a can.log alone, with --replay-can)\n"
    "  --replay-rate R      their pace: 1 real time, N times faster, 0 as fast as read\n"
    "  --replay-can         CAN from the recording too, instead of the buses\n"
    "  --replay-origin FILE wait for `roadload replay --origin FILE` and replay in step with its CAN\n"
    "  --exit-when-done     exit once every replayed stream has ended\n"
    "  --print-config       print the effective settings as TOML and exit\n"
    "  --version            print the version and exit\n"
    "  -h, --help           this text\n"
    "\n"
    "Signals: SIGTERM/SIGINT flush and exit; SIGHUP reopens the status files (logrotate) without\n"
    "cutting the recording; SIGUSR1 ends the recording segment and starts a new one.\n";

namespace {

ParseError arg_error(const std::string& field, const std::string& message) { return ParseError{"command line", 0, field, message}; }

}  // namespace

Parsed<CommandLine> parse_command_line(const std::vector<std::string>& args) {
  CommandLine cl;
  // --config first, wherever it is, so the other options override it.
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] != "--config") continue;
    if (i + 1 >= args.size()) return arg_error("--config", "needs a file");
    auto c = load_config(args[i + 1]);
    if (!c) return c.error();
    cl.config = std::move(c.value());
  }
  bool can_given = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    // An option's value, never the next option: `--can --no-gnss` lacks its interface.
    auto value = [&](std::string& out) -> bool {
      if (i + 1 >= args.size() || args[i + 1].starts_with("--")) return false;
      out = args[++i];
      return true;
    };
    std::string v;
    if (a == "-h" || a == "--help") {
      cl.help = true;
    } else if (a == "--version") {
      cl.version = true;
    } else if (a == "--print-config") {
      cl.print_config = true;
    } else if (a == "--exit-when-done") {
      cl.exit_when_done = true;
    } else if (a == "--no-record") {
      cl.config.recording.enabled = false;
    } else if (a == "--replay-origin") {
      if (!value(cl.config.replay.origin_file)) return arg_error(a, "needs a file");
    } else if (a == "--replay-can") {
      cl.config.replay.can = true;
    } else if (a == "--no-gnss") {
      cl.config.gnss.enabled = false;
    } else if (a == "--config") {
      ++i;
    } else if (a == "--can") {
      if (!value(v)) return arg_error(a, "needs an interface name");
      if (!can_given) cl.config.can.clear();
      can_given = true;
      CanBusConfig b;
      b.interface = v;
      cl.config.can.push_back(b);
    } else if (a == "--data-dir") {
      if (!value(cl.config.recording.data_dir)) return arg_error(a, "needs a directory");
    } else if (a == "--status") {
      if (!value(cl.config.status.text_file)) return arg_error(a, "needs a file");
    } else if (a == "--status-json") {
      if (!value(cl.config.status.json_file)) return arg_error(a, "needs a file ('' for none)");
    } else if (a == "--vehicle") {
      if (!value(cl.config.vehicle.file)) return arg_error(a, "needs a vehicle file or name");
    } else if (a == "--route") {
      if (!value(cl.config.estimator.route)) return arg_error(a, "needs a route file or name");
    } else if (a == "--results") {
      if (!value(cl.config.estimator.results_dir)) return arg_error(a, "needs a directory");
    } else if (a == "--replay") {
      if (!value(cl.config.replay.recording)) return arg_error(a, "needs a recording folder");
    } else if (a == "--replay-rate") {
      if (!value(v)) return arg_error(a, "needs a number");
      double rate = 0;
      const auto r = std::from_chars(v.data(), v.data() + v.size(), rate);
      if (r.ec != std::errc{} || r.ptr != v.data() + v.size()) return arg_error(a, "'" + v + "' is not a number");
      cl.config.replay.rate = rate;
    } else {
      return arg_error(a, "unknown option (see --help)");
    }
  }
  if (auto e = validate(cl.config)) return *e;
  return cl;
}

}  // namespace roadload::firmware
