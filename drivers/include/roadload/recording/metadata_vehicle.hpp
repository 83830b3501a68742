#pragma once
// The vehicle a recording was made with: a vehicle description (a vehicle file) with what the
// recording's meta.toml states over it. A recording that names axle loads carries those axles only,
// at its loads and positions (a drive's cargo, a trailer swapped); the antenna and VIN likewise.
#include "roadload/recording/metadata.hpp"
#include "roadload/vehicle.hpp"

namespace roadload::recording {

Vehicle vehicle_from_metadata(const Vehicle& base, const Metadata& meta);

}  // namespace roadload::recording
