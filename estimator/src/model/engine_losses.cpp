#include "roadload/model/engine_losses.hpp"

#include <algorithm>
#include <cmath>

namespace roadload::model {

bool EngineLossMap::add(const EngineLossPoint& p) {
  if (size_ == kCapacity || (size_ > 0 && p.rpm <= points_[size_ - 1].rpm)) return false;
  points_[size_++] = p;
  return true;
}

template <typename Field>
std::optional<double> EngineLossMap::interpolate(double rpm, Field field) const {
  if (size_ == 0 || rpm < points_[0].rpm || rpm > points_[size_ - 1].rpm) return std::nullopt;
  double v = field(points_[0]);
  if (size_ > 1) {
    const auto* end = points_.begin() + static_cast<std::ptrdiff_t>(size_);
    const auto* hi = std::lower_bound(points_.begin() + 1, end - 1, rpm,
                                      [](const EngineLossPoint& p, double r) { return p.rpm < r; });
    const auto* lo = hi - 1;
    const double w = (rpm - lo->rpm) / (hi->rpm - lo->rpm);
    v = field(*lo) + w * (field(*hi) - field(*lo));
  }
  if (std::isnan(v)) return std::nullopt;
  return v;
}

std::optional<double> EngineLossMap::loss_nm(double rpm) const {
  return interpolate(rpm, [](const EngineLossPoint& p) { return p.loss_nm; });
}

std::optional<double> EngineLossMap::friction_nm(double rpm) const {
  return interpolate(rpm, [](const EngineLossPoint& p) { return p.friction_nm; });
}

EngineLossMap EngineLossMap::shifted(double offset_nm, double sigma_nm) const {
  EngineLossMap m;
  for (std::size_t i = 0; i < size_; ++i) m.add({points_[i].rpm, points_[i].loss_nm + offset_nm, sigma_nm, points_[i].friction_nm});
  return m;
}

double EngineLossMap::sigma_nm() const {
  if (size_ < 2) return size_ == 0 ? 0.0 : points_[0].sigma_nm;
  // Between two points the map's error is (1 - w) e_lo + w e_hi, the points' errors independent
  // (each is its own hold's rounding): its variance averages (s_lo^2 + s_hi^2) / 3 over w.
  double sum = 0;
  for (std::size_t i = 1; i < size_; ++i) {
    const double lo = points_[i - 1].sigma_nm, hi = points_[i].sigma_nm;
    sum += (points_[i].rpm - points_[i - 1].rpm) * (lo * lo + hi * hi) / 3.0;
  }
  return std::sqrt(sum / (points_[size_ - 1].rpm - points_[0].rpm));
}

}  // namespace roadload::model
