#include "roadload/contact_forces.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <utility>

namespace roadload {
namespace {

struct Found {
  std::int64_t id = -1;
  bool left = true;
};

// The accelerometer at "<base>-left", else "<base>-right"; the lowest id wins a shared position.
Found find_sensor(std::span<const SensorPlacement> sensors, std::string_view base) {
  Found best;
  for (const bool left : {true, false}) {
    for (const SensorPlacement& s : sensors) {
      if (!s.kind.empty() && s.kind != "accelerometer") continue;
      const std::string_view side = left ? "-left" : "-right";
      if (s.position.size() != base.size() + side.size() || !s.position.starts_with(base) || !s.position.ends_with(side)) {
        continue;
      }
      if (best.id < 0 || s.id < best.id) best = {s.id, left};
    }
    if (best.id >= 0) return best;
  }
  return best;
}

// An axle's own frame sensor first; else the unit's nearest, same side first.
struct Frame {
  Found sensor;
  std::size_t axle = 0;
};
Frame find_frame(std::span<const SensorPlacement> sensors, const Vehicle& v, std::size_t i, bool left) {
  Frame best{{}, i};
  double best_score = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < v.axles.size(); ++j) {
    if (v.axles[j].unit != v.axles[i].unit) continue;
    const Found f = find_sensor(sensors, v.axles[j].frame_mount);
    if (f.id < 0) continue;
    const double score = std::abs(v.axles[j].position_m - v.axles[i].position_m) + (j == i ? -1e6 : 0.0) +
                         (f.left == left ? 0.0 : 1e3);
    if (score < best_score) {
      best_score = score;
      best = {f, j};
    }
  }
  return best;
}

}  // namespace

Parsed<AxleLayout> build_axle_layout(std::span<const SensorPlacement> sensors, const Vehicle& vehicle, std::string_view source,
                                     LayoutOptions options) {
  auto fail = [&](std::string field, std::string message) {
    return ParseError{std::string(source), 0, std::move(field), std::move(message)};
  };
  AxleLayout layout;
  if (vehicle.axles.empty()) return fail("vehicle", "the vehicle has no axles");
  for (std::size_t i = 0; i < vehicle.axles.size(); ++i) {
    const VehicleAxle& d = vehicle.axles[i];
    if (!(d.load_kg > 0) || !std::isfinite(d.load_kg))
      return fail("vehicle." + d.name + "_load_kg", "axle load must be a positive number");
    if (!(d.unsprung_kg > 0) || !(d.unsprung_kg < d.load_kg)) {
      return fail("vehicle." + d.name + "_unsprung_kg", "unsprung mass " + std::to_string(d.unsprung_kg) +
                                                            " kg must be above 0 and below the axle load " +
                                                            std::to_string(d.load_kg) + " kg");
    }
    auto skip_or_fail = [&](std::string field, std::string message) -> std::optional<ParseError> {
      if (!options.skip_axles_without_sensors) return fail(std::move(field), std::move(message));
      layout.skipped.push_back(d.name + ": " + message);
      return std::nullopt;
    };
    const Found axle = find_sensor(sensors, d.axle_mount);
    if (axle.id < 0) {
      if (auto e = skip_or_fail("[[sensor]] position",
                                "no accelerometer at '" + d.axle_mount + "-left' (or -right) for axle " + d.name)) {
        return *e;
      }
      continue;
    }
    const Frame frame = find_frame(sensors, vehicle, i, axle.left);
    if (frame.sensor.id < 0) {
      if (auto e = skip_or_fail("[[sensor]] position", "no frame accelerometer on the " + d.unit + " for axle " + d.name +
                                                           " (looked for '" + d.frame_mount +
                                                           "-left' and the unit's other frame positions)")) {
        return *e;
      }
      continue;
    }
    if (axle.id > 255 || frame.sensor.id > 255) {
      return fail("[[sensor]] id", "accelerometer id above 255 for axle " + d.name + " (accel.csv sensor is 0-255)");
    }
    if (layout.axles.size() == kMaxContactAxles) break;
    AxleContact a;
    a.name = d.name;
    a.load_kg = d.load_kg;
    a.unsprung_kg = d.unsprung_kg;
    a.sprung_kg = d.load_kg - d.unsprung_kg;
    a.position_m = d.position_m;
    a.axle_sensor = static_cast<std::uint8_t>(axle.id);
    a.frame_sensor = static_cast<std::uint8_t>(frame.sensor.id);
    a.frame_of = vehicle.axles[frame.axle].name;
    a.frame_ahead_m = d.position_m - vehicle.axles[frame.axle].position_m;
    a.suspension = d.suspension;
    layout.axles.push_back(std::move(a));
  }
  if (layout.axles.empty()) {
    return fail("[[sensor]] position", "no axle has both an axle and a frame accelerometer (" +
                                           (layout.skipped.empty() ? std::string() : layout.skipped.front()) + ")");
  }
  return layout;
}

ForceStats rolling_resistance(const ForceStats& fz, double crr) { return {fz.count, crr * fz.mean_n, std::abs(crr) * fz.std_n}; }

ForceStats ContactForces::stats(const RunningStats& r) { return {r.n, r.mean, r.std()}; }

ContactForces::ContactForces(AxleLayout layout, std::size_t cell_count, ContactConfig config)
    : layout_(std::move(layout)),
      cell_count_(cell_count),
      config_(config),
      alpha_tau_s_(1.0 / (2.0 * std::numbers::pi * config.highpass_hz)) {
  if (layout_.axles.size() > kMaxContactAxles) layout_.axles.resize(kMaxContactAxles);
  for (std::size_t i = 0; i < layout_.axles.size(); ++i) {
    const AxleContact& a = layout_.axles[i];
    roles_[a.axle_sensor].axle = static_cast<std::int16_t>(i);
    roles_[a.axle_sensor].used = true;
    roles_[a.frame_sensor].frame = true;
    roles_[a.frame_sensor].used = true;
  }
  if (config_.delay_borrowed_frames) {
    for (const AxleContact& a : layout_.axles) {
      SensorRole& r = roles_[a.frame_sensor];
      if (a.frame_ahead_m > 0 && r.history == kNone) {
        r.history = static_cast<std::int16_t>(histories_.size());
        histories_.emplace_back();
      }
    }
  }
  cell_.fill(-1);
  cells_.resize(cell_count_ * layout_.axles.size());
}

void ContactForces::History::add(CaptureTime t, double d) {
  t_ns[next] = to_ns(t);
  deviation[next] = d;
  next = (next + 1) % kFrameHistory;
  size = std::min(size + 1, kFrameHistory);
}

ContactForces::History::Found ContactForces::History::at(CaptureTime t, Seconds max_gap, double& out) const {
  if (size == 0) return Found::stale;
  const std::int64_t want = to_ns(t);
  const auto max_gap_ns = std::chrono::duration_cast<Nanoseconds>(max_gap).count();
  auto index = [&](std::size_t k) { return (next + kFrameHistory - size + k) % kFrameHistory; };  // k = 0: oldest
  const std::size_t newest = index(size - 1);
  if (want >= t_ns[newest]) {
    if (want - t_ns[newest] > max_gap_ns) return Found::stale;
    out = deviation[newest];
    return Found::ok;
  }
  if (want < t_ns[index(0)]) return Found::not_kept;
  // First kept sample after `want`: stamps are non-decreasing in push order.
  std::size_t lo = 0, hi = size - 1;
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (t_ns[index(mid)] > want) {
      hi = mid;
    } else {
      lo = mid + 1;
    }
  }
  const std::size_t b = index(lo), a = index(lo - 1);
  const std::int64_t span = t_ns[b] - t_ns[a];
  if (span > 2 * max_gap_ns) {
    // A gap in the frame's samples: the nearer edge if it is close enough, as for an own frame.
    if (want - t_ns[a] <= max_gap_ns) {
      out = deviation[a];
    } else if (t_ns[b] - want <= max_gap_ns) {
      out = deviation[b];
    } else {
      return Found::stale;
    }
    return Found::ok;
  }
  const double w = span > 0 ? static_cast<double>(want - t_ns[a]) / static_cast<double>(span) : 1.0;
  out = deviation[a] + w * (deviation[b] - deviation[a]);
  return Found::ok;
}

void ContactForces::set_cell(CaptureTime t, int cell, double grade_rad, double speed_mps) {
  for (std::size_t i = 0; i < layout_.axles.size(); ++i) cell_[i] = cell;
  position_t_ = t;
  position_set_ = true;
  cos_grade_ = std::cos(grade_rad);
  speed_mps_ = speed_mps;
}

void ContactForces::set_axle_cells(CaptureTime t, std::span<const int> cells, double grade_rad, double speed_mps) {
  for (std::size_t i = 0; i < layout_.axles.size(); ++i) cell_[i] = i < cells.size() ? cells[i] : -1;
  position_t_ = t;
  position_set_ = true;
  cos_grade_ = std::cos(grade_rad);
  speed_mps_ = speed_mps;
}

bool ContactForces::update_sensor(SensorState& st, const AccelSample& s) {
  const double z = s.z_mps2;
  if (st.started && to_seconds(s.t - st.last) > config_.gap_reset.count()) {
    st.started = false;
    ++restarts_;
  }
  if (!st.started) {
    st = SensorState{};
    st.started = true;
    st.first = s.t;
    st.last = s.t;
  }
  // First-order low-pass for the static reading; the expanding average until it weighs less.
  const double dt = std::max(0.0, to_seconds(s.t - st.last));
  ++st.n;
  const double alpha = std::max(1.0 / static_cast<double>(st.n), dt / (alpha_tau_s_ + dt));
  st.mean += alpha * (z - st.mean);
  st.deviation = z - st.mean;
  st.last = s.t;
  return to_seconds(s.t - st.first) >= config_.warmup.count();
}

void ContactForces::push(const AccelSample& s) {
  const SensorRole role = roles_[s.sensor];
  if (!role.used) {
    ++unknown_;
    return;
  }
  SensorState& st = sensors_[s.sensor];
  const bool warm = update_sensor(st, s);
  if (role.history != kNone) histories_[static_cast<std::size_t>(role.history)].add(s.t, st.deviation);
  if (role.axle == kNone) return;  // a frame sensor: its latest deviation waits for the axle samples
  const auto axle = static_cast<std::size_t>(role.axle);
  ContactCounters& c = counters_[axle];
  if (!warm) {
    ++c.warming_up;
    return;
  }
  const SensorState& frame = sensors_[layout_.axles[axle].frame_sensor];
  if (!frame.started || to_seconds(frame.last - frame.first) < config_.warmup.count()) {
    ++c.no_frame;
    return;
  }
  const AxleContact& a = layout_.axles[axle];
  const SensorRole& frame_role = roles_[a.frame_sensor];
  if (frame_role.history != kNone && a.frame_ahead_m > 0) {
    // A borrowed frame ahead of this axle: its body motion frame_ahead_m / speed ago.
    const bool placed = position_set_ && to_seconds(s.t - position_t_) <= config_.max_position_age.count();
    if (placed && speed_mps_ >= config_.min_delay_speed_mps) {  // false for NaN
      const auto delay = Nanoseconds{std::llround(a.frame_ahead_m / speed_mps_ * 1e9)};
      double a_c = 0;
      switch (histories_[static_cast<std::size_t>(frame_role.history)].at(s.t - delay, config_.max_pair_age, a_c)) {
        case History::Found::ok:
          ++c.paired;
          add_force(axle, s.t, st.deviation, a_c);
          return;
        case History::Found::stale: ++c.stale_frame; return;
        case History::Found::not_kept: break;
      }
    }
    ++c.undelayed;
  } else if (a.frame_ahead_m < 0 && config_.delay_borrowed_frames) {
    ++c.undelayed;  // the frame sensor is behind this axle: its motion then is still to come
  }
  const auto age = s.t >= frame.last ? s.t - frame.last : frame.last - s.t;
  if (to_seconds(age) > config_.max_pair_age.count()) {
    ++c.stale_frame;
    return;
  }
  ++c.paired;
  add_force(axle, s.t, st.deviation, frame.deviation);
}

void ContactForces::add_force(std::size_t axle, CaptureTime t, double a_w, double a_c) {
  const AxleContact& a = layout_.axles[axle];
  const double dynamic = a.unsprung_kg * a_w + a.sprung_kg * a_c;
  const double fz = (a.unsprung_kg + a.sprung_kg) * config_.gravity_mps2 * cos_grade_ + dynamic;
  latest_[axle] = {t, fz, dynamic, true};
  trip_[axle].fz.add(fz);
  trip_[axle].dynamic.add(dynamic);
  const int cell = cell_[axle];
  const bool placed = position_set_ && to_seconds(t - position_t_) <= config_.max_position_age.count();
  if (!placed || cell < 0 || static_cast<std::size_t>(cell) >= cell_count_) {
    ++counters_[axle].no_cell;
    return;
  }
  Acc& acc = cells_[static_cast<std::size_t>(cell) * layout_.axles.size() + axle];
  acc.fz.add(fz);
  acc.dynamic.add(dynamic);
}

AxleForceStats ContactForces::cell(std::size_t cell, std::size_t axle) const {
  const Acc& acc = cells_[cell * layout_.axles.size() + axle];
  return {stats(acc.fz), stats(acc.dynamic)};
}

AxleForceStats ContactForces::trip(std::size_t axle) const { return {stats(trip_[axle].fz), stats(trip_[axle].dynamic)}; }

}  // namespace roadload
