#pragma once
// Whether each accelerometer's z holds gravity, up as mounted, as the recording format says it
// does (docs/recording-format.md): a mean z far from +g is a sensor mounted upside down or on its
// side, or a logger that took gravity out. Contact forces (Eq. 2.1) difference an axle's sensor and
// its frame's: a sign or axis wrong there gives wrong forces without any other symptom.
#include <array>
#include <cstdint>
#include <vector>

#include "roadload/samples.hpp"

namespace roadload {

class GravityCheck {
 public:
  void push(const AccelSample& s) {
    Sum& sum = sums_[s.sensor];
    sum.z += s.z_mps2;
    sum.n += 1;
  }

  struct Finding {
    std::uint8_t sensor = 0;
    double mean_z_mps2 = 0;
    std::uint64_t samples = 0;
  };
  // Sensors with enough samples whose mean z lies more than `tolerance` from +g (a truck on a 10 %
  // grade still sees 0.995 g along a vertical sensor; 2.5 m/s^2 is a tilt of about 40 degrees).
  std::vector<Finding> implausible(std::uint64_t min_samples = 1000, double tolerance_mps2 = 2.5) const;

 private:
  struct Sum {
    double z = 0;
    std::uint64_t n = 0;
  };
  std::array<Sum, 256> sums_{};
};

}  // namespace roadload
