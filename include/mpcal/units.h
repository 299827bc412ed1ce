/// \file units.h
/// \brief Units of accelerometer readings at the edges of mpcal.
///
/// Inside mpcal everything is SI (m/s², s, rad). A log may be in m/s², in g
/// (standard gravity, 9.80665 m/s² per g — a unit, not the local gravity) or
/// in raw ADC counts, whose nominal scale is found from the data.
#pragma once

#include <optional>
#include <string_view>

namespace mpcal {

/// Standard gravity, the definition of the unit g (m/s²).
inline constexpr double kStandardGravityMps2 = 9.80665;

enum class AccelUnits {
  kMps2,    ///< metres per second squared
  kG,       ///< standard g (9.80665 m/s²)
  kCounts,  ///< raw ADC counts; scale and offset found from the positions
};

/// "mps2", "g" or "counts".
std::string_view ToString(AccelUnits units);
/// The unit as the README's conventions write it in prose and tables:
/// "m/s²", "g" or "counts" (ToString is the name a file or flag gives).
std::string_view UnitSymbol(AccelUnits units);
/// Inverse of ToString (also accepts "m/s2", "m/s^2"); nullopt if unknown.
std::optional<AccelUnits> ParseAccelUnits(std::string_view name);
/// m/s² per unit for kMps2 and kG; nullopt for kCounts (found from data).
std::optional<double> FixedMps2PerUnit(AccelUnits units);

/// Units of gyroscope readings: rad/s, deg/s, or raw ADC counts whose nominal
/// scale (rad/s per count) is found from the turns of a session.
enum class GyroUnits {
  kRadps,   ///< radians per second
  kDps,     ///< degrees per second
  kCounts,  ///< raw ADC counts
};

/// "rads", "dps" or "counts".
std::string_view ToString(GyroUnits units);
/// Inverse of ToString (also "rad/s", "deg/s"); nullopt if unknown.
std::optional<GyroUnits> ParseGyroUnits(std::string_view name);
/// rad/s per unit for kRadps and kDps; nullopt for kCounts (found from data).
std::optional<double> FixedRadpsPerUnit(GyroUnits units);

}  // namespace mpcal
