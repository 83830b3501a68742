#pragma once
// Each subcommand of `roadload` adds itself to the program's command line, its options bound to
// settings of its own, and returns what runs it once the command line has been read (main.cpp).
#include <functional>

#include "status.hpp"

namespace CLI {
class App;
}

namespace roadload::cli {

using Run = std::function<int()>;

Run add_decode(CLI::App& roadload);
Run add_analyze(CLI::App& roadload);
Run add_cat(CLI::App& roadload);
Run add_batch(CLI::App& roadload);
Run add_calibrate(CLI::App& roadload);
Run add_collect(CLI::App& roadload);
Run add_gap(CLI::App& roadload);
Run add_grade(CLI::App& roadload);
Run add_network(CLI::App& roadload);
Run add_psd(CLI::App& roadload);
Run add_replay(CLI::App& roadload);
Run add_report(CLI::App& roadload);
Run add_route(CLI::App& roadload);
Run add_simulate(CLI::App& roadload);
Run add_vehicle(CLI::App& roadload);

}  // namespace roadload::cli
