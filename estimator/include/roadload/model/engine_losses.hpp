#pragma once
// The engine's own losses against engine speed: friction plus the accessories it drives, in N m at
// the crankshaft. J1939 states them in EEC3 in whole percent of reference torque (SPN 514, 2978);
// at one cruise speed that rounding is one constant flywheel torque error of up to 1 % of the
// reference torque (24 N m on the MnROAD engine, 0.0005 in CRR in 8th gear). A calibration at
// standstill measures them to EEC1's 1/8 % instead (engine_loss_calibration.hpp).
#include <array>
#include <cstddef>
#include <limits>
#include <optional>

namespace roadload::model {

struct EngineLossPoint {
  double rpm = 0;
  double loss_nm = 0;   // friction + accessories at this engine speed
  double sigma_nm = 0;  // its standard error
  // The engine's friction alone: the loss less the accessories split_losses smoothed against EEC3's
  // friction curve; NaN where the calibration could not separate them, and the accessories keep
  // EEC3's parasitic share.
  double friction_nm = std::numeric_limits<double>::quiet_NaN();
};

// Fixed capacity, no heap: it is part of the truck model the live filter copies.
class EngineLossMap {
 public:
  static constexpr std::size_t kCapacity = 64;

  // Points must come in increasing engine speed; false (nothing added) when one does not, or the
  // map is full.
  bool add(const EngineLossPoint& p);
  // Linear between the two nearest points; nothing outside the calibrated range: an engine
  // speed the calibration never held is not guessed at.
  std::optional<double> loss_nm(double rpm) const;
  // The friction part of that loss, likewise; nothing where a neighbouring point has none.
  std::optional<double> friction_nm(double rpm) const;
  // The error the map leaves in the flywheel torque at an engine speed anywhere in its range: RMS
  // over the range of the interpolated error's sigma, the points' errors independent.
  double sigma_nm() const;
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const EngineLossPoint& operator[](std::size_t i) const { return points_[i]; }
  // The same engine speeds with every loss moved by `offset_nm` and every sigma set to
  // `sigma_nm`: the table held as exact, or nudged, to see what depends on it.
  EngineLossMap shifted(double offset_nm, double sigma_nm) const;

 private:
  template <typename Field>
  std::optional<double> interpolate(double rpm, Field field) const;

  std::array<EngineLossPoint, kCapacity> points_{};
  std::size_t size_ = 0;
};

}  // namespace roadload::model
