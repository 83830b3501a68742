#pragma once
// The subcommands of `roadload gap` beyond the diagnosis itself, added under it.
#include "command.hpp"

namespace roadload::cli {

Run add_gap_bench(CLI::App& gap);
Run add_gap_tables(CLI::App& gap);
unsigned default_jobs();

}  // namespace roadload::cli
