// A still record from mpcal's noise simulator, as a Recording, for the noise
// tests.
#pragma once

#include "mpcal/recording.h"
#include "mpcal/simulate_noise.h"

namespace mpcal {

inline Recording SimulatedStill(const NoiseSimulationOptions& o) {
  NoiseGenerator gen(o);
  Recording rec;
  rec.source = "<simulated>";
  double t = 0.0;
  Eigen::Vector3d a, g;
  while (gen.Next(&t, &a, &g)) {
    rec.time_s.push_back(t);
    rec.accel.push_back(a);
    rec.gyro_radps.push_back(g);
  }
  return rec;
}

}  // namespace mpcal
