// roadload vehicle identify: a vehicle file filled in from the truck's own recordings. What the bus
// and the GNSS tell replaces the prior's value, each with its sigma and source noted above it;
// everything else stays the prior's, and what could not be identified is said, with why.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command.hpp"
#include "files.hpp"
#include "roadload/cli/help.hpp"
#include "roadload/recording/reader.hpp"
#include "roadload/vehicle_file.hpp"
#include "roadload/vehicle_identification.hpp"

namespace roadload::cli {
namespace {

const HelpText kVehicleHelp{"usage: roadload vehicle identify RECORDING... --out FILE [--vehicle PRIOR] [options]",
                            "Writes a vehicle file for the truck the recordings were made with. It starts from a prior (the\n"
                            "nearest vehicle file: --vehicle, else the one the first recording's meta.toml carries) and\n"
                            "replaces what the drives tell, each value with its standard error and its source as a comment:\n"
                            "  vin                  VI (PGN 65260)\n"
                            "  reference torque     EC1 SPN 544\n"
                            "  gear ratios          ETC2's actual ratio per current gear, else engine over wheel speed\n"
                            "  drive tires' radius  GNSS speed against the wheels' turning rate in steady driving\n"
                            "  mass                 CVW's gross combination weight (PGN 65136), where the truck sends it\n"
                            "What the drives cannot tell (CdA, efficiency, a mass the bus does not send) keeps the prior's\n"
                            "value and sigma; standard error lists each with the reason."};

struct VehicleOptions {
  std::vector<std::string> recordings, dbcs;
  std::string out, vehicle, name;
};

void add_options(CLI::App& cmd, VehicleOptions& o) {
  cmd.add_option("RECORDING", o.recordings, "recording folders of the truck")->required();
  cmd.add_option("-o,--out", o.out, "the vehicle file to write (TOML, docs/vehicle-file.md)")->type_name("FILE")->required();
  cmd.add_option("--vehicle", o.vehicle, "the prior: a vehicle file or a built-in name (config/vehicles)")->type_name("V");
  cmd.add_option("--name", o.name, "the written vehicle's name (default: FILE's stem)")->type_name("TEXT");
  cmd.add_option("--dbc", o.dbcs, "load FILE after the built-in definitions; repeatable")->type_name("FILE");
}

std::string figure(double v, double sigma) {
  char text[96];
  // The sigma to one significant digit, the value to the same decimal.
  const int digits = sigma > 0 ? std::max(0, -static_cast<int>(std::floor(std::log10(sigma)))) : 3;
  std::snprintf(text, sizeof text, "%.*f +- %.*f", digits, v, digits, sigma);
  return text;
}

// The value to a tenth of its sigma's leading digit: more digits would claim what was not measured.
double rounded(const IdentifiedValue& v) {
  if (!(v.sigma > 0)) return v.value;
  const double step = std::pow(10.0, std::floor(std::log10(v.sigma)) - 1);
  return std::round(v.value / step) * step;
}

std::string note(const IdentifiedValue& v, double prior, const std::string& unit) {
  char p[48];
  std::snprintf(p, sizeof p, "%.6g", prior);
  return "identified: " + figure(v.value, v.sigma) + unit + " from " + v.source + ", " + std::to_string(v.samples) +
         " samples; the prior was " + p + unit;
}

// The prior with what the drives told put in, and a note above each value it replaced.
Vehicle fill(const Vehicle& prior, const VehicleIdentification& id, const std::string& name, VehicleNotes& notes) {
  Vehicle v = prior;
  v.name = name;
  v.description = "identified by roadload vehicle identify from " + prior.name;
  if (!id.vin.empty()) {
    v.vin = id.vin;
    notes["vin"] = "identified: from VI (PGN 65260)";
  }
  if (id.reference_torque_nm) {
    v.engine.reference_torque_nm = rounded(*id.reference_torque_nm);
    notes["engine.reference_torque_nm"] = note(*id.reference_torque_nm, prior.engine.reference_torque_nm, " N m");
  }
  std::string gears;
  for (std::size_t g = 0; g < id.gear_ratios.size(); ++g) {
    if (!id.gear_ratios[g]) continue;
    v.driveline.gear_ratios[g] = rounded(*id.gear_ratios[g]);
    gears += (gears.empty() ? "" : "\n") + ("gear " + std::to_string(g + 1) + ": ") +
             figure(id.gear_ratios[g]->value, id.gear_ratios[g]->sigma) + " (" + id.gear_ratios[g]->source + ")";
  }
  if (!gears.empty()) notes["driveline.gear_ratios"] = "identified, the rest the prior's:\n" + gears;
  if (id.drive_tire_radius_m) {
    for (std::size_t i = 0; i < v.axles.size(); ++i) {
      if (!v.axles[i].driven) continue;
      notes["axle[" + std::to_string(i) + "].tire_radius_m"] = note(*id.drive_tire_radius_m, v.axles[i].tire_radius_m, " m");
      v.axles[i].tire_radius_m = rounded(*id.drive_tire_radius_m);
    }
  }
  if (id.mass_kg && prior.mass_kg() > 0) {
    // The axles keep their shares of the load; the combination's weight sets the total.
    const double k = rounded(*id.mass_kg) / prior.mass_kg();
    for (VehicleAxle& a : v.axles) a.load_kg *= k;
    v.mass_sigma_kg = id.mass_kg->sigma;
    notes["body.mass_sigma_kg"] = note(*id.mass_kg, prior.mass_kg(), " kg") + " (the axle loads scaled to it)";
  }
  return v;
}

void print(const Vehicle& prior, const VehicleIdentification& id) {
  std::printf("%-28s %-14s %-24s %s\n", "value", "prior", "identified", "source");
  const auto row = [](const std::string& what, double p, const std::optional<IdentifiedValue>& v) {
    std::printf("%-28s %-14.6g %-24s %s\n", what.c_str(), p, v ? figure(v->value, v->sigma).c_str() : "-",
                v ? v->source.c_str() : "");
  };
  std::printf("%-28s %-14s %-24s %s\n", "vin", prior.vin.empty() ? "-" : prior.vin.c_str(), id.vin.empty() ? "-" : id.vin.c_str(),
              id.vin.empty() ? "" : "VI PGN 65260");
  row("reference_torque_nm", prior.engine.reference_torque_nm, id.reference_torque_nm);
  for (std::size_t g = 0; g < id.gear_ratios.size(); ++g)
    row("gear " + std::to_string(g + 1), prior.driveline.gear_ratios[g], id.gear_ratios[g]);
  const VehicleAxle* drive = prior.drive_axle();
  row("drive tire_radius_m", drive ? drive->tire_radius_m : 0.0, id.drive_tire_radius_m);
  row("mass_kg", prior.mass_kg(), id.mass_kg);
  row("wheel speed scale", 1.0, id.wheel_speed_scale);
  for (const std::string& why : id.not_identified) std::fprintf(stderr, "vehicle: not identified: %s\n", why.c_str());
}

int identify(VehicleOptions& o) {
  if (o.name.empty()) o.name = std::filesystem::path(o.out).stem().string();
  j1939::Database db;
  if (auto rc = load_definitions("vehicle", o.dbcs, db)) return *rc;
  std::optional<Vehicle> prior;
  if (!o.vehicle.empty()) {
    auto v = load_vehicle("vehicle", o.vehicle);
    if (const int* rc = std::get_if<int>(&v)) return *rc;
    prior = std::move(std::get<Vehicle>(v));
  }
  std::optional<VehicleIdentifier> identifier;
  std::uint64_t malformed = 0;
  for (const std::string& path : o.recordings) {
    auto reader = recording::RecordingReader::open(path, recording::kCanStream | recording::kGnssStream);
    if (!reader) {
      std::fprintf(stderr, "roadload vehicle: %s\n", reader.error().to_string().c_str());
      return exit_for(reader.error());
    }
    if (!prior && reader.value().metadata().vehicle_file) prior = *reader.value().metadata().vehicle_file;
    if (!prior) {
      std::fprintf(stderr,
                   "roadload vehicle: %s: meta.toml describes no vehicle: give the nearest vehicle file as the prior (--vehicle)\n",
                   path.c_str());
      return kExitUsage;
    }
    if (!identifier) identifier.emplace(db, *prior);
    while (const recording::Record* r = reader.value().next()) {
      if (const auto* f = std::get_if<CanFrame>(r)) identifier->push(*f);
      if (const auto* g = std::get_if<GnssFix>(r)) identifier->push(*g);
    }
    for (const ParseError& e : reader.value().errors().kept()) std::fprintf(stderr, "roadload vehicle: %s\n", e.to_string().c_str());
    malformed += reader.value().errors().count();
  }
  const VehicleIdentification id = identifier->result();
  VehicleNotes notes;
  const Vehicle v = fill(*prior, id, o.name, notes);
  const std::string header = "# Written by roadload vehicle identify from " + std::to_string(o.recordings.size()) +
                             " recording(s); every value not noted as\n# identified is the prior's (" +
                             (prior->source.empty() ? prior->name : prior->source) + ").\n";
  if (auto rc = write_text_file("vehicle", o.out, header + format_vehicle(v, notes))) return *rc;
  print(*prior, id);
  return malformed > 0 ? kExitDataErr : kExitOk;
}

}  // namespace

Run add_vehicle(CLI::App& roadload) {
  auto o = std::make_shared<VehicleOptions>();
  CLI::App& identify_cmd = add_action_command(
      roadload, "vehicle", "identify a truck's vehicle file from its recordings: VIN, torque, gear ratios, tire radius, mass",
      "identify", "write a vehicle file for the truck the recordings were made with", kVehicleHelp);
  add_options(identify_cmd, *o);
  return [o] { return identify(*o); };
}

}  // namespace roadload::cli
