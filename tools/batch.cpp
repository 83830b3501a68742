// roadload batch: the analysis of many recordings on Dask distributed, each drive's results into
// the fleet database. The runner is Python's (tools/python/roadload/batch.py: Dask is a Python
// engine); this command reads the same command line, so that --help, completion and the manual
// page are the program's, and runs it from the package beside the program.
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command.hpp"
#include "roadload/cli/help.hpp"
#include "roadload/cli/values.hpp"

namespace roadload::cli {
namespace {

namespace fs = std::filesystem;

const HelpText kBatchHelp{"usage: roadload batch MANIFEST --db URL [--scheduler ADDRESS | --workers N] [-o DIR]",
                          "Analyses every drive of MANIFEST on Dask distributed, each task running `roadload analyze` in-process\n"
                          "into DIR/<drive>/ and adding the results to the fleet database (`roadload collect`). MANIFEST is a CSV\n"
                          "with the header recording,vehicle,route: one drive a row, its segments joined by '+', an empty\n"
                          "vehicle or route for the recording's meta.toml or the road its GNSS traces; an optional column name\n"
                          "names the drive's folder, and a column named after an option of analyze (mass, cda, engine_losses, ...)\n"
                          "gives it per drive. Relative paths are the manifest's folder's. Every worker must read the recordings\n"
                          "and write DIR at the same paths (a shared file system on a cluster).",
                          "Progress (drives done, failed, time left) and each failure with its error go to standard error. Exit\n"
                          "status: 0 when every drive was analysed and collected; 1 when one failed (the others are done);\n"
                          "65 when some input was malformed; 69 when the scheduler cannot be reached. docs/python.md tells how\n"
                          "to start a scheduler and workers on several machines."};

struct BatchOptions {
  std::string manifest, db, scheduler, out = "batch-results";
  int workers = 0;
};

// The package's folder beside the program: the build tree's BUILD/python, or the installed one.
std::string package_dir(const fs::path& program) {
  for (const fs::path& dir : {program.parent_path() / ".." / "python", program.parent_path() / ROADLOAD_BIN_TO_PYTHONDIR}) {
    std::error_code ec;
    if (fs::is_regular_file(dir / "roadload" / "batch.py", ec)) return dir.lexically_normal().string();
  }
  return {};
}

int run_batch(const BatchOptions& o) {
  std::error_code ec;
  const fs::path program = fs::read_symlink("/proc/self/exe", ec);
  const std::string package = ec ? std::string() : package_dir(program);
  if (package.empty()) {
    say("batch", "no Python package roadload beside " + program.string() +
                     " (this roadload was built without it: ROADLOAD_PYTHON=OFF, or pybind11-dev was missing)");
    return kExitNoInput;
  }
  const char* path = std::getenv("PYTHONPATH");
  const std::string python_path = package + (path != nullptr && *path != '\0' ? ":" + std::string(path) : "");
  setenv("PYTHONPATH", python_path.c_str(), 1);
  // The tasks' `roadload collect` is this program, wherever the workers started from.
  setenv("ROADLOAD_PROGRAM", program.c_str(), 0);
  std::vector<std::string> args{ROADLOAD_PYTHON_EXECUTABLE, "-m", "roadload.batch", o.manifest, "--db", o.db, "-o", o.out};
  if (!o.scheduler.empty()) args.insert(args.end(), {"--scheduler", o.scheduler});
  if (o.workers > 0) args.insert(args.end(), {"--workers", std::to_string(o.workers)});
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  execv(argv[0], argv.data());
  say("batch", std::string(ROADLOAD_PYTHON_EXECUTABLE) + ": " + std::strerror(errno));
  return kExitNoInput;
}

}  // namespace

Run add_batch(CLI::App& roadload) {
  auto o = std::make_shared<BatchOptions>();
  CLI::App& cmd = *roadload.add_subcommand("batch", "analyse many recordings on Dask distributed into the fleet database");
  describe(cmd, kBatchHelp);
  cmd.add_option("MANIFEST", o->manifest, "CSV: recording,vehicle,route[,name][,option...]")->required();
  cmd.add_option("--db", o->db, "the fleet database: an SQLite file, sqlite:///path or postgresql://...")
      ->type_name("URL")
      ->required();
  CLI::Option* scheduler = cmd.add_option("--scheduler", o->scheduler,
                                          "a running Dask scheduler (tcp://host:8786), its workers started apart")
                               ->type_name("ADDRESS");
  cmd.add_option("--workers", o->workers,
                 "start a local cluster of N worker processes, one thread each\n(default: one per core, without --scheduler)")
      ->type_name("N")
      ->transform(whole_in(1, 1024))
      ->excludes(scheduler);
  cmd.add_option("-o,--out", o->out, "the drives' results folders, DIR/<drive>/ (default batch-results)")->type_name("DIR");
  return [o] { return run_batch(*o); };
}

}  // namespace roadload::cli
