#pragma once
// The subcommands of `roadload gap` beyond the diagnosis itself.
#include "options.hpp"

namespace roadload::cli {

int run_gap_bench(OptionParser& opt);
int run_gap_tables(OptionParser& opt);
unsigned default_jobs();

}  // namespace roadload::cli
