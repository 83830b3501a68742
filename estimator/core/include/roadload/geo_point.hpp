#pragma once
// A surveyed point of a road.
namespace roadload {

struct GeoPoint {
  double lat_deg = 0;
  double lon_deg = 0;
  double elev_m = 0;  // height above the WGS84 ellipsoid
};

}  // namespace roadload
