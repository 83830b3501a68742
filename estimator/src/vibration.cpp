#include "roadload/vibration.hpp"

#include <algorithm>
#include <string_view>

namespace roadload {
namespace {

std::vector<spectra::GridSensor> grid_sensors(std::span<const VibrationSensor> sensors) {
  std::vector<spectra::GridSensor> out;
  for (const auto& s : sensors) out.push_back({s.id, s.rate_hz});
  return out;
}

int slot_of(std::span<const VibrationSensor> sensors, std::uint8_t id) {
  for (std::size_t i = 0; i < sensors.size(); ++i)
    if (sensors[i].id == id) return static_cast<int>(i);
  return -1;
}

std::vector<spectra::SuspensionAxle> suspension_axles(const AxleLayout& layout, std::span<const VibrationSensor> sensors) {
  std::vector<spectra::SuspensionAxle> out;
  for (const AxleContact& a : layout.axles) {
    spectra::SuspensionAxle s;
    s.name = a.name;
    s.axle_slot = slot_of(sensors, a.axle_sensor);
    s.frame_slot = slot_of(sensors, a.frame_sensor);
    s.frame_ahead_m = a.frame_ahead_m;
    s.unsprung_kg = a.unsprung_kg;
    s.sprung_kg = a.sprung_kg;
    s.damper_nspm = a.suspension.damper_nspm;
    s.tire_damping_nspm = a.suspension.tire_damping_nspm;
    s.tire_stiffness_npm = a.suspension.tire_stiffness_npm;
    out.push_back(std::move(s));
  }
  return out;
}

std::vector<spectra::ModeSensor> mode_sensors(const AxleLayout& layout, std::span<const VibrationSensor> sensors) {
  std::vector<spectra::ModeSensor> out;
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    std::size_t axle = 0;
    for (std::size_t a = 0; a < layout.axles.size(); ++a) {
      const AxleContact& c = layout.axles[a];
      if (c.axle_sensor == sensors[i].id || (c.frame_sensor == sensors[i].id && c.frame_of == c.name)) axle = a;
    }
    out.push_back({sensors[i].name, static_cast<int>(i), axle});
  }
  return out;
}

}  // namespace

VibrationAnalysis::VibrationAnalysis(const AxleLayout& layout, std::span<const VibrationSensor> sensors, std::size_t cell_count,
                                     std::vector<int> cell_group, std::size_t group_count, VibrationConfig config)
    : layout_(layout),
      cell_group_(cell_group),
      grid_(grid_sensors(sensors), config.grid),
      history_(config.placement_history),
      suspension_(suspension_axles(layout, sensors), cell_count, grid_, config.suspension),
      modes_(mode_sensors(layout, sensors), std::move(cell_group), group_count, grid_.rate_hz(), config.modes) {}

namespace {

DynamicPower sum_axles(const spectra::SuspensionSpectra& s, const auto& power_of) {
  DynamicPower d;
  d.segments = s.axle_count() > 0 ? 1e300 : 0.0;
  for (std::size_t a = 0; a < s.axle_count(); ++a) {
    const spectra::AxlePower p = power_of(a);
    d.damper_w += p.damper_w;
    d.damper_accel_w += p.damper_accel_w;
    d.tire_w += p.tire_deflection_w;
    d.tire_eq27_w += p.tire_eq27_w;
    d.segments = std::min(d.segments, p.segments);
  }
  return d;
}

}  // namespace

DynamicPower VibrationAnalysis::cell_power(std::size_t cell) const {
  return sum_axles(suspension_, [&](std::size_t a) { return suspension_.cell_power(cell, a); });
}

DynamicPower VibrationAnalysis::trip_power() const {
  return sum_axles(suspension_, [&](std::size_t a) { return suspension_.trip_power(a); });
}

DynamicPower VibrationAnalysis::window_power() const {
  return sum_axles(suspension_, [&](std::size_t a) { return suspension_.window_power(a); });
}

DynamicPower VibrationAnalysis::group_power(std::size_t group) const {
  DynamicPower g;
  for (std::size_t c = 0; c < cell_group_.size(); ++c) {
    if (cell_group_[c] != static_cast<int>(group)) continue;
    const DynamicPower p = cell_power(c);
    g.damper_w += p.segments * p.damper_w;
    g.damper_accel_w += p.segments * p.damper_accel_w;
    g.tire_w += p.segments * p.tire_w;
    g.tire_eq27_w += p.segments * p.tire_eq27_w;
    g.segments += p.segments;
  }
  if (g.segments > 0) {
    g.damper_w /= g.segments;
    g.damper_accel_w /= g.segments;
    g.tire_w /= g.segments;
    g.tire_eq27_w /= g.segments;
  }
  return g;
}

void VibrationAnalysis::set_axle_cells(CaptureTime t, std::span<const int> cells, double speed_mps, double s_front_m) {
  history_.add(t, cells, speed_mps, s_front_m);
}

void VibrationAnalysis::push(const AccelSample& s) {
  grid_.push(s);
  suspension_.update(grid_, history_);
  modes_.update(grid_, history_);
}

}  // namespace roadload
