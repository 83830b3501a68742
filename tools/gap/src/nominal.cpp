#include "roadload/gap/nominal.hpp"

#include <algorithm>

namespace roadload::gap {

std::string_view nominal_name(Nominal p) {
  switch (p) {
    case Nominal::mass: return "mass";
    case Nominal::cda: return "CdA";
    case Nominal::engine_friction: return "engine friction";
    case Nominal::driveline_efficiency: return "driveline efficiency";
    case Nominal::tire_radius: return "tire radius";
  }
  return "?";
}

std::optional<Nominal> stands_for(sim::Effect e) {
  switch (e) {
    case sim::Effect::mass_error: return Nominal::mass;
    case sim::Effect::air_density_error: return Nominal::cda;
    default: return std::nullopt;
  }
}

std::string_view nominal_unit(Nominal p) {
  switch (p) {
    case Nominal::mass: return "kg";
    case Nominal::cda: return "m2";
    case Nominal::engine_friction: return "x curve";
    case Nominal::driveline_efficiency: return "";
    case Nominal::tire_radius: return "m";
  }
  return "";
}

namespace {

// The driven tires' radius as the vehicle file gives it (the plant's engine speed and the ECUs'
// speed both turn on it); 0 without a driven axle, which leaves the parameter out.
double drive_radius_m(const Vehicle& v) {
  const VehicleAxle* a = v.drive_axle();
  return a != nullptr ? a->tire_radius_m : 0.0;
}

}  // namespace

std::vector<NominalPrior> nominal_priors(const sim::Scenario& model) {
  const Vehicle& v = model.vehicle;
  const NominalPrior all[] = {
      {Nominal::mass, v.mass_kg() * model.load_scale, v.mass_sigma_kg * model.load_scale},
      {Nominal::cda, v.cda_m2 * model.cda_scale, v.cda_sigma_m2 * model.cda_scale},
      {Nominal::engine_friction, model.engine_friction_scale, v.engine.friction_sigma * model.engine_friction_scale},
      {Nominal::driveline_efficiency, v.driveline.efficiency, v.driveline.efficiency_sigma},
      {Nominal::tire_radius, drive_radius_m(v) * model.tire_radius_scale, v.tire_radius_sigma_m * model.tire_radius_scale},
  };
  std::vector<NominalPrior> out;
  for (const NominalPrior& p : all) {
    if (p.sigma > 0 && p.value > 0) out.push_back(p);
  }
  return out;
}

void set_nominal(sim::Scenario& model, Nominal p, double value) {
  switch (p) {
    case Nominal::mass: model.load_scale = value / model.vehicle.mass_kg(); return;
    case Nominal::cda: model.cda_scale = value / model.vehicle.cda_m2; return;
    case Nominal::engine_friction: model.engine_friction_scale = value; return;
    case Nominal::driveline_efficiency: model.vehicle.driveline.efficiency = std::clamp(value, 0.5, 0.999); return;
    case Nominal::tire_radius: model.tire_radius_scale = value / drive_radius_m(model.vehicle); return;
  }
}

void set_true_nominal(sim::Scenario& drive, const NominalPrior& prior, double value) {
  if (prior.id != Nominal::mass) {
    set_nominal(drive, prior.id, value);
    return;
  }
  // The simulator records (1 + e) times the true mass: keep what it records, change what is true.
  const double declared = (1.0 + drive.effects.magnitude(sim::Effect::mass_error)) * drive.load_scale;
  drive.load_scale *= value / prior.value;
  drive.effects.set(sim::Effect::mass_error, declared / drive.load_scale - 1.0);
}

std::vector<double> draw_truck(std::size_t parameters, std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> out;
  for (std::size_t i = 0; i < parameters; ++i) out.push_back(std::clamp(normal(rng), -2.5, 2.5));
  return out;
}

void drive_truck(sim::Scenario& drive, const std::vector<NominalPrior>& priors, const std::vector<double>& offsets) {
  for (std::size_t i = 0; i < priors.size() && i < offsets.size(); ++i) {
    set_true_nominal(drive, priors[i], priors[i].value + offsets[i] * priors[i].sigma);
  }
}

}  // namespace roadload::gap
