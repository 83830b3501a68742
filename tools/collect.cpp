// roadload collect: analysed drives into the fleet database (docs/fleet.md).
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command.hpp"
#include "progress.hpp"
#include "roadload/cli/help.hpp"
#include "roadload/db/database.hpp"
#include "roadload/fleet/collect.hpp"

namespace roadload::cli {
namespace {

const HelpText kCollectHelp{"usage: roadload collect RESULTS... --db URL [options]",
                            "Ingests analysed drives (the folders `roadload analyze` and roadloadd write: trip.json,\n"
                            "cells.csv) into a fleet database: vehicles, routes, sections with their geometry, drives\n"
                            "with their provenance, and each drive's result per section (docs/fleet.md, \"Schema\").\n\n"
                            "URL is a file path or sqlite:///PATH (SQLite, created when missing) or postgresql://...\n"
                            "(PostgreSQL with PostGIS; libpq's URI, so PGPASSWORD and ~/.pgpass work). A drive is keyed\n"
                            "by its logger run's recording_id: collecting it again changes nothing, and its results\n"
                            "analysed again replace its rows. Each drive is one transaction; the first that cannot be\n"
                            "read or written stops the run, naming its file and field, with the drives before it kept."};

struct CollectOptions {
  std::vector<std::string> results;
  std::string db;
  bool quiet = false;
};

int collect(const CollectOptions& o) {
  Progress progress("collect", o.quiet || o.results.size() < 2, 2.0);
  try {
    const fleet::CollectSummary s = fleet::collect(o.results, o.db, [&](std::size_t done) {
      progress.update(static_cast<double>(done) / static_cast<double>(o.results.size()));
    });
    progress.finish();
    std::printf("collect: %d drives added, %d unchanged, %d replaced; %d sections new, %d section results written%s\n",
                s.drives_added, s.drives_unchanged, s.drives_replaced, s.sections_added, s.section_results,
                s.schema_from == 0 ? " (new database)" : "");
    return kExitOk;
  } catch (const db::DatabaseError& e) {
    std::fprintf(stderr, "roadload collect: %s\n", e.what());
    return kExitCantCreate;
  } catch (const fleet::ResultsError& e) {
    std::fprintf(stderr, "roadload collect: %s\n", e.what());
    return exit_for(e.error);
  }
}

}  // namespace

Run add_collect(CLI::App& roadload) {
  auto o = std::make_shared<CollectOptions>();
  CLI::App& cmd = *roadload.add_subcommand("collect", "ingest analysed drives into a fleet database (SQLite or PostgreSQL)");
  describe(cmd, kCollectHelp);
  cmd.add_option("RESULTS", o->results, "results folders of analysed drives")->required();
  cmd.add_option("--db", o->db, "database: a file path, sqlite:///PATH or postgresql://...")->type_name("URL")->required();
  cmd.add_flag("-q,--quiet", o->quiet, "no progress on standard error");
  return [o] { return collect(*o); };
}

}  // namespace roadload::cli
