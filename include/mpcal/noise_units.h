/// \file noise_units.h
/// \brief The datasheet units of noise terms, from and to SI: the one place
/// where they are converted.
///
/// SI (what mpcal computes and writes): white noise N in m/s²/√Hz or
/// rad/s/√Hz, bias instability B in m/s² or rad/s, random walk K in
/// m/s³/√Hz or rad/s²/√Hz. Datasheets: µg/√Hz and m/s/√h (velocity random
/// walk), µg, °/√h (angle random walk), °/h, and for the random walks µg/√h
/// and °/h/√h. √h = 60 √s.
#pragma once

#include <numbers>

#include "mpcal/noise.h"
#include "mpcal/units.h"

namespace mpcal::noise_units {

inline constexpr double kMicroG = kStandardGravityMps2 * 1e-6;  ///< m/s² per µg
inline constexpr double kDegPerRad = 180.0 / std::numbers::pi;
inline constexpr double kRootSecondsPerRootHour = 60.0;  ///< √3600
inline constexpr double kSecondsPerHour = 3600.0;

// Accelerometer.
constexpr double MicroGPerRtHz(double n_mps2_per_rthz) {
  return n_mps2_per_rthz / kMicroG;
}
constexpr double MpsPerRtHour(double n_mps2_per_rthz) {
  return n_mps2_per_rthz * kRootSecondsPerRootHour;
}
constexpr double MicroG(double b_mps2) { return b_mps2 / kMicroG; }
constexpr double MicroGPerRtHour(double k_mps3_per_rthz) {
  return k_mps3_per_rthz * kRootSecondsPerRootHour / kMicroG;
}

// Gyroscope.
constexpr double DegPerRtHour(double n_radps_per_rthz) {
  return n_radps_per_rthz * kDegPerRad * kRootSecondsPerRootHour;
}
constexpr double DegPerSecondPerRtHz(double n_radps_per_rthz) {
  return n_radps_per_rthz * kDegPerRad;
}
constexpr double DegPerHour(double b_radps) {
  return b_radps * kDegPerRad * kSecondsPerHour;
}
constexpr double DegPerHourPerRtHour(double k_radps2_per_rthz) {
  return k_radps2_per_rthz * kDegPerRad * kSecondsPerHour * kRootSecondsPerRootHour;
}

/// A term's value in its datasheet unit, and that unit's name ("µg/√Hz",
/// "°/h"); for a sensor `gyroscope` or not. Quantisation and rate ramp have
/// none (their SI value is returned, unit "").
struct DatasheetValue {
  double value;
  const char* unit;
};
inline DatasheetValue ToDatasheet(NoiseTerm term, bool gyroscope, double si) {
  switch (term) {
    case NoiseTerm::kWhiteNoise:
      return gyroscope ? DatasheetValue{DegPerRtHour(si), "°/√h"}
                       : DatasheetValue{MicroGPerRtHz(si), "µg/√Hz"};
    case NoiseTerm::kBiasInstability:
      return gyroscope ? DatasheetValue{DegPerHour(si), "°/h"}
                       : DatasheetValue{MicroG(si), "µg"};
    case NoiseTerm::kRandomWalk:
      return gyroscope ? DatasheetValue{DegPerHourPerRtHour(si), "°/h/√h"}
                       : DatasheetValue{MicroGPerRtHour(si), "µg/√h"};
    default:
      return {si, ""};
  }
}

/// The SI unit of a term for a sensor, e.g. "m/s²/√Hz", "rad/s²/√Hz".
inline const char* SiUnit(NoiseTerm term, bool gyroscope) {
  switch (term) {
    case NoiseTerm::kQuantisation:
      return gyroscope ? "rad" : "m/s";
    case NoiseTerm::kWhiteNoise:
      return gyroscope ? "rad/s/√Hz" : "m/s²/√Hz";
    case NoiseTerm::kBiasInstability:
      return gyroscope ? "rad/s" : "m/s²";
    case NoiseTerm::kRandomWalk:
      return gyroscope ? "rad/s²/√Hz" : "m/s³/√Hz";
    case NoiseTerm::kRateRamp:
      return gyroscope ? "rad/s²" : "m/s³";
  }
  return "";
}

}  // namespace mpcal::noise_units
