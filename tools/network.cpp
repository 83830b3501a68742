// roadload network: per-section CRR across a fleet's drives, from the database collect fills.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

#include "command.hpp"
#include "roadload/cli/help.hpp"
#include "roadload/cli/values.hpp"
#include "roadload/db/database.hpp"
#include "roadload/fleet/network.hpp"

namespace roadload::cli {
namespace {

const HelpText kNetworkHelp{"usage: roadload network --db URL -o DIR [options]",
                            "Estimates each section's CRR from every drive in the fleet database, with a 90 % interval,\n"
                            "through one model: a drive's CRR of a section is the section's CRR plus what the drive shares\n"
                            "over all its sections (its truck's tires, its truck's drag error growing with speed squared,\n"
                            "the drive's own torque and weather errors) plus the cell's own error (docs/fleet.md).\n"
                            "A cell the analysis withheld for its width is weighed; one withheld because the model did\n"
                            "not fit the drive is not evidence, and is counted by its reason.\n\n"
                            "Writes into DIR: network.csv (per section: CRR and interval, drives and trucks behind it,\n"
                            "dynamic rolling resistance, fuel per pass and per year), network-bands.csv (per section and\n"
                            "speed band), trucks.csv (each truck's own CRR offset), network.geojson, network.json (the\n"
                            "model's spreads with intervals) and network.html, a self-contained map."};

struct NetworkOptions {
  std::string db, out;
  fleet::NetworkOptions network;
  double band_kmh = 25;
};

int network(NetworkOptions o) {
  o.network.speed_band_mps = o.band_kmh / 3.6;
  try {
    const fleet::NetworkView view = fleet::network_view(o.db, o.network);
    std::filesystem::create_directories(o.out);
    for (const auto& [name, text] : fleet::network_files(view)) {
      std::ofstream f(o.out + "/" + name, std::ios::binary);
      if (!(f << text) || !f.flush()) {
        std::fprintf(stderr, "roadload network: %s/%s: cannot write\n", o.out.c_str(), name.c_str());
        return kExitCantCreate;
      }
    }
    std::printf("network: %d drives, %zu trucks, %zu sections; %d cells used, %d excluded; truck spread %.5f [%.5f, %.5f]%s\n",
                view.drives, view.trucks.size(), view.sections.size(), view.cells_used, view.cells_excluded, view.fit.truck.sd,
                view.fit.truck.sd_lo, view.fit.truck.sd_hi, view.fit.fitted ? "" : " (the model did not converge)");
    return view.cells_used > 0 && view.fit.fitted ? kExitOk : kExitDataErr;
  } catch (const db::DatabaseError& e) {
    std::fprintf(stderr, "roadload network: %s\n", e.what());
    return kExitNoInput;
  } catch (const std::filesystem::filesystem_error& e) {
    std::fprintf(stderr, "roadload network: %s\n", e.what());
    return kExitCantCreate;
  }
}

}  // namespace

Run add_network(CLI::App& roadload) {
  auto o = std::make_shared<NetworkOptions>();
  CLI::App& cmd = *roadload.add_subcommand("network", "estimate every section's CRR across a fleet's drives (map, CSV, GeoJSON)");
  describe(cmd, kNetworkHelp);
  cmd.add_option("--db", o->db, "database: a file path, sqlite:///PATH or postgresql://...")->type_name("URL")->required();
  cmd.add_option("-o,--out", o->out, "folder to write the outputs into")->type_name("DIR")->required();
  cmd.add_option("--trucks-per-day", o->network.trucks_per_day,
                 "heavy trucks a day over each section and direction, for the\nyearly fuel (default 1000)")
      ->type_name("N")
      ->check(real_in(0, 1e6));
  cmd.add_option("--band", o->band_kmh, "width of the speed bands (default 25)")->type_name("KMH")->check(real_in(1, 200));
  cmd.add_option("--fuel-price", o->network.fuel_price_per_l, "price of a litre of diesel: adds a yearly cost (default: none)")
      ->type_name("PER_L")
      ->check(real_in(0, 1000));
  return [o] { return network(*o); };
}

}  // namespace roadload::cli
