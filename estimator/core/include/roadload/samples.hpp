#pragma once
// Sensor samples as the estimator receives them. Each starts with its capture-clock stamp and
// names its unit in every field.
#include <cstdint>

#include "roadload/time.hpp"

namespace roadload {

struct AccelSample {
  CaptureTime t;
  std::uint8_t sensor = 0;  // index into the recording's sensor table
  double x_mps2 = 0.0;      // sensor frame; z up when mounted as documented
  double y_mps2 = 0.0;
  double z_mps2 = 0.0;
};

enum class GnssFixMode : std::uint8_t { none = 0, fix_2d = 2, fix_3d = 3, dgps = 4, rtk = 5 };

struct GnssFix {
  CaptureTime t;
  std::int64_t utc_ns = 0;  // UTC of the fix per the receiver, ns since 1970; 0 if unknown
  double lat_deg = 0.0;
  double lon_deg = 0.0;
  double alt_m = 0.0;       // height above the WGS84 ellipsoid
  double speed_mps = 0.0;   // over ground
  double course_deg = 0.0;  // true, clockwise from north
  GnssFixMode mode = GnssFixMode::none;
  double hdop = 0.0;
};

// A field the station does not measure is NaN (an empty field in weather.csv).
struct WeatherSample {
  CaptureTime t;
  std::uint8_t station = 0;
  double air_temp_c = 0.0;
  double pressure_pa = 0.0;
  double wind_speed_mps = 0.0;
  double wind_from_deg = 0.0;  // meteorological: direction the wind blows from, clockwise from north
};

}  // namespace roadload
