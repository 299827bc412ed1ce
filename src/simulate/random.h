// Random deviates that are the same for a seed on every machine: the
// distributions of <random> differ between standard libraries, so the
// deviates are made by hand from the (standardised) mt19937_64 output.
// Shared by the static-session and walk simulators.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

#include <Eigen/Core>

namespace mpcal::internal {

/// SplitMix64 (Steele, Lea & Flood 2014): a good mixer to derive seeds.
inline std::uint64_t SplitMix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

class PortableRandom {
 public:
  explicit PortableRandom(std::uint64_t seed) : engine_(seed) {}

  /// Uniform in [0, 1).
  double Uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }

  /// Standard normal (Box-Muller, both deviates used).
  double Normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u1 = Uniform();
    while (u1 <= 0.0) u1 = Uniform();
    const double u2 = Uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * std::numbers::pi * u2);
    has_spare_ = true;
    return r * std::cos(2.0 * std::numbers::pi * u2);
  }
  Eigen::Vector3d Normal3() {
    const double x = Normal();
    const double y = Normal();
    const double z = Normal();
    return {x, y, z};
  }
  /// Uniform on the unit sphere.
  Eigen::Vector3d UnitVector() {
    for (;;) {
      const Eigen::Vector3d v = Normal3();
      const double n = v.norm();
      if (n > 1e-6) return v / n;
    }
  }

 private:
  std::mt19937_64 engine_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

}  // namespace mpcal::internal
