#pragma once
// What a truck's own drives tell of it, for a vehicle file (`roadload vehicle identify`): each
// value with its standard error and its source; what they cannot tell is left to the prior, with
// the reason. Push API over the bus's frames and the GNSS fixes in time order; no I/O.
//
// - VIN: VI (PGN 65260), ASCII up to its "*".
// - Reference torque: EC1 SPN 544, as sent (1 N m resolution).
// - Gear ratios, per ETC2 current gear (SPN 523): ETC2's actual ratio (SPN 526) where sent, else
//   engine speed over wheel speed through the prior's drive-tire radius and final drive. Only in
//   gear, the driveline engaged, no shift and no clutch, above a walking pace.
// - The drive tires' dynamic radius: GNSS speed over the wheels' turning rate, the engine's speed
//   through the gear's ratio and the final drive, in steady driving (GNSS speed changing by less
//   than 0.3 m/s per fix interval).
// - Mass: CVW's gross combination weight (PGN 65136 SPN 1760) where sent.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "roadload/can_frame.hpp"
#include "roadload/drive_signals.hpp"
#include "roadload/samples.hpp"
#include "roadload/vehicle.hpp"

namespace roadload {

struct IdentifiedValue {
  double value = 0;
  double sigma = 0;  // standard error
  std::size_t samples = 0;
  std::string source;
};

struct VehicleIdentification {
  std::string vin;
  std::optional<IdentifiedValue> reference_torque_nm;
  std::vector<std::optional<IdentifiedValue>> gear_ratios;  // first gear first, as the prior lists them
  std::optional<IdentifiedValue> drive_tire_radius_m;
  std::optional<IdentifiedValue> mass_kg;
  std::optional<IdentifiedValue> wheel_speed_scale;  // GNSS speed over CCVS1's: the ECU's tire setting
  std::vector<std::string> not_identified;           // "field: why"
};

class VehicleIdentifier {
 public:
  VehicleIdentifier(const j1939::Database& db, const Vehicle& prior);
  void push(const CanFrame& frame);
  void push(const GnssFix& fix);
  VehicleIdentification result() const;

  // A gear's samples a ratio needs; at 10 Hz, two seconds in that gear.
  static constexpr std::size_t kMinSamples = 20;
  // GCVW's standard error: the axles' air-suspension pressures give a few percent of the mass.
  static constexpr double kCombinationWeightSigma = 0.03;

 private:
  void on_message(const j1939::Message& m);
  bool steady_in_gear(CaptureTime t) const;
  double gear_ratio_now(int gear, CaptureTime t) const;

  const Vehicle& prior_;
  SignalFeed feed_;
  const j1939::SignalDef* gcvw_ = nullptr;
  j1939::Pgn gcvw_pgn_ = 0;
  std::string vin_;
  std::vector<std::vector<double>> etc2_ratios_, speed_ratios_;  // per gear
  std::vector<double> radii_m_, wheel_scales_, weights_kg_;
  std::optional<GnssFix> last_fix_;
};

}  // namespace roadload
