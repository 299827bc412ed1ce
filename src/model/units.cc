#include "mpcal/units.h"

#include <numbers>

namespace mpcal {

std::string_view ToString(AccelUnits units) {
  switch (units) {
    case AccelUnits::kMps2:
      return "mps2";
    case AccelUnits::kG:
      return "g";
    case AccelUnits::kCounts:
      return "counts";
  }
  return "unknown";
}

std::string_view UnitSymbol(AccelUnits units) {
  return units == AccelUnits::kMps2 ? "m/s\u00b2" : ToString(units);
}

std::optional<AccelUnits> ParseAccelUnits(std::string_view name) {
  if (name == "mps2" || name == "m/s2" || name == "m/s^2") return AccelUnits::kMps2;
  if (name == "g") return AccelUnits::kG;
  if (name == "counts") return AccelUnits::kCounts;
  return std::nullopt;
}

std::optional<double> FixedMps2PerUnit(AccelUnits units) {
  switch (units) {
    case AccelUnits::kMps2:
      return 1.0;
    case AccelUnits::kG:
      return kStandardGravityMps2;
    case AccelUnits::kCounts:
      return std::nullopt;
  }
  return std::nullopt;
}

std::string_view ToString(GyroUnits units) {
  switch (units) {
    case GyroUnits::kRadps:
      return "rads";
    case GyroUnits::kDps:
      return "dps";
    case GyroUnits::kCounts:
      return "counts";
  }
  return "unknown";
}

std::optional<GyroUnits> ParseGyroUnits(std::string_view name) {
  if (name == "rads" || name == "rad/s") return GyroUnits::kRadps;
  if (name == "dps" || name == "deg/s") return GyroUnits::kDps;
  if (name == "counts") return GyroUnits::kCounts;
  return std::nullopt;
}

std::optional<double> FixedRadpsPerUnit(GyroUnits units) {
  switch (units) {
    case GyroUnits::kRadps:
      return 1.0;
    case GyroUnits::kDps:
      return std::numbers::pi / 180.0;
    case GyroUnits::kCounts:
      return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace mpcal
