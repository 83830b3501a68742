#pragma once
// The nominal truck: the parameters every model of a real truck has slightly wrong (its mass, drag
// area, engine friction and driveline efficiency), each with the prior spread its vehicle file
// states. The diagnosis fits them before any effect, so that "this is another truck" is not
// mistaken for an unmodelled effect.
#include <optional>
#include <random>
#include <string_view>
#include <vector>

#include "roadload/sim/scenario.hpp"

namespace roadload::gap {

enum class Nominal { mass, cda, engine_friction, driveline_efficiency, tire_radius };

// One parameter as the model has it: its value and one sigma of how far a real truck may be off.
struct NominalPrior {
  Nominal id;
  double value = 0;
  double sigma = 0;
};

std::string_view nominal_name(Nominal p);

// The nominal parameter an effect is indistinguishable from, when there is one: a wrong declared
// mass is another truck's mass, and air a constant share denser drags as a larger CdA does.
std::optional<Nominal> stands_for(sim::Effect e);
std::string_view nominal_unit(Nominal p);

// The parameters the model scenario lets a fit move: those whose vehicle file states a spread
// (a sigma of 0 holds the parameter at its value).
std::vector<NominalPrior> nominal_priors(const sim::Scenario& model);

// The model with the parameter set to `value` (the recorded mass replaced, the drag area,
// friction or efficiency of its truck changed).
void set_nominal(sim::Scenario& model, Nominal p, double value);

// A drive of a truck whose parameter is `value` while everything recorded about it stays: for
// the mass, the truck is that heavy while its recording still declares the old mass.
void set_true_nominal(sim::Scenario& drive, const NominalPrior& prior, double value);

// One truck drawn from the priors: each parameter's offset in its prior sigmas (normal, cut at
// 2.5), the same truck for every run of a day.
std::vector<double> draw_truck(std::size_t parameters, std::mt19937_64& rng);

// A run of the drawn truck: each parameter at its prior's value plus its offset in sigmas.
void drive_truck(sim::Scenario& drive, const std::vector<NominalPrior>& priors, const std::vector<double>& offsets);

}  // namespace roadload::gap
