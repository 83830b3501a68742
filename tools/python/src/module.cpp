// roadload._core: the C++ analysis and decoder for the Python package (tools/python/roadload),
// which turns what they return into pandas frames and exceptions. Each call releases Python's
// lock while the C++ runs, so threads (a Dask worker's, a notebook's) analyse drives at once.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "decode_columns.hpp"
#include "roadload/analysis/analyze.hpp"
#include "roadload/cli/parse.hpp"
#include "roadload/db/database.hpp"
#include "roadload/fleet/collect.hpp"
#include "status.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace roadload::python {
namespace {

const std::string kVersion = "roadload " ROADLOAD_VERSION;

// `roadload analyze ARGS...`'s command line, read as the command reads it: the Python keywords are
// its options, so their names, ranges and messages cannot drift from the command's.
int run_analyze(const std::vector<std::string>& args, bool progress) {
  CLI::App app("", "roadload");
  analysis::AnalyzeOptions o;
  analysis::add_options(*app.add_subcommand("analyze", ""), o);
  std::vector<std::string> argv{"analyze"};
  argv.insert(argv.end(), args.begin(), args.end());
  const cli::Outcome read = cli::parse(app, argv, kVersion);
  if (read.kind == cli::Outcome::Kind::usage_error) return cli::usage_error(read.command, read.message());
  if (read.kind == cli::Outcome::Kind::print) return cli::usage_error("analyze", "--help and --version are the command's");
  o.report = false;
  o.progress = progress;
  return analysis::analyze(std::move(o));
}

// Runs `work` (which returns an exit status) without Python's lock, its messages captured: the
// C++ touches no Python object, and other threads run meanwhile.
template <typename Work>
std::pair<int, std::vector<std::string>> unlocked(Work&& work) {
  py::gil_scoped_release released;
  cli::MessageCapture capture;
  const int status = work();
  return {status, capture.lines()};
}

py::tuple analyze(const std::vector<std::string>& args, bool progress) {
  auto [status, messages] = unlocked([&] { return run_analyze(args, progress); });
  return py::make_tuple(status, messages);
}

// The long names of `roadload analyze`'s options ("route", "cda-sigma", ...), each with whether it
// is a flag, for roadload.analyze's keywords.
std::vector<std::pair<std::string, bool>> analyze_options() {
  CLI::App app("", "roadload");
  analysis::AnalyzeOptions o;
  analysis::add_options(app, o);
  std::vector<std::pair<std::string, bool>> names;
  for (const CLI::Option* opt : app.get_options()) {
    for (const std::string& n : opt->get_lnames()) names.emplace_back(n, opt->get_expected_max() == 0);
  }
  return names;
}

template <typename T>
py::array_t<T> array(std::vector<T>&& v) {
  return py::array_t<T>(static_cast<py::ssize_t>(v.size()), v.data());
}

py::tuple decode(const std::vector<std::string>& inputs, const std::vector<std::string>& dbcs,
                 const std::vector<std::uint32_t>& pgns) {
  DecodedColumns c;
  auto [status, messages] = unlocked([&] { return decode_columns(inputs, dbcs, pgns, c); });
  py::dict columns("t_ns"_a = array(std::move(c.t_ns)), "iface"_a = array(std::move(c.iface)), "sa"_a = array(std::move(c.sa)),
                   "pgn"_a = array(std::move(c.pgn)), "message"_a = array(std::move(c.message)),
                   "signal"_a = array(std::move(c.signal)), "value"_a = array(std::move(c.value)),
                   "state"_a = array(std::move(c.state)));
  py::dict names("iface"_a = c.iface_names, "message"_a = c.message_names, "signal"_a = c.signal_names, "unit"_a = c.signal_units,
                 "state"_a = c.state_names);
  return py::make_tuple(status, messages, columns, names);
}

// `roadload collect DIRS... --db URL` in-process: the database's failure is the command's 73, a
// results folder it cannot read its 65, each with the C++'s message.
py::tuple collect(const std::vector<std::string>& dirs, const std::string& db_url) {
  fleet::CollectSummary s;
  auto [status, messages] = unlocked([&] {
    try {
      s = fleet::collect(dirs, db_url);
      return cli::kExitOk;
    } catch (const db::DatabaseError& e) {
      cli::say("collect", e.what());
      return cli::kExitCantCreate;
    } catch (const std::runtime_error& e) {
      cli::say("collect", e.what());
      return cli::kExitDataErr;
    }
  });
  py::dict summary("drives_added"_a = s.drives_added, "drives_unchanged"_a = s.drives_unchanged,
                   "drives_replaced"_a = s.drives_replaced, "sections_added"_a = s.sections_added,
                   "section_results"_a = s.section_results, "schema_from"_a = s.schema_from);
  return py::make_tuple(status, messages, summary);
}

}  // namespace
}  // namespace roadload::python

PYBIND11_MODULE(_core, m) {
  using namespace roadload::python;
  m.doc() = "roadload's C++ analysis and J1939 decoder; use the package roadload, which wraps them in pandas";
  m.attr("version") = ROADLOAD_VERSION;
  m.def("analyze", &analyze, py::arg("args"), py::arg("progress") = false,
        "Runs `roadload analyze ARGS...` in-process without its tables; returns (exit status, messages).");
  m.def("analyze_options", &analyze_options, "The long option names of `roadload analyze`, each with whether it is a flag.");
  m.def("collect", &collect, py::arg("dirs"), py::arg("db"),
        "Adds results folders to the fleet database; returns (exit status, messages, summary).");
  m.def("decode", &decode, py::arg("inputs"), py::arg("dbcs"), py::arg("pgns"),
        "Decodes a recording's J1939 signals; returns (exit status, messages, columns, names).");
}
