// The units the report shows (the paper's): bias in mg beside m/s², scale-
// factor error in ppm, non-orthogonality in mrad. SI stays inside.
#pragma once

#include <string_view>

#include "mpcal/units.h"

namespace mpcal::report {

inline constexpr double kMgPerMps2 = 1000.0 / kStandardGravityMps2;
inline constexpr double kPpm = 1e6;
inline constexpr double kMradPerRad = 1e3;

/// Display factor and unit of the i-th packed model parameter (order of
/// kParameterNames): mg, ppm or mrad.
struct DisplayUnit {
  double factor;
  std::string_view unit;
};
inline DisplayUnit ParameterDisplayUnit(int i) {
  if (i < 3) return {kMgPerMps2, "mg"};
  if (i < 6) return {kPpm, "ppm"};
  return {kMradPerRad, "mrad"};
}

/// Human name of the i-th packed parameter, e.g. "bias x", "θyz".
inline std::string_view ParameterLabel(int i) {
  static constexpr std::string_view kLabels[] = {"bias x",
                                                 "bias y",
                                                 "bias z",
                                                 "scale-factor error x",
                                                 "scale-factor error y",
                                                 "scale-factor error z",
                                                 "non-orthogonality \u03b8yz",
                                                 "non-orthogonality \u03b8zx",
                                                 "non-orthogonality \u03b8zy"};
  return kLabels[i];
}

/// Short name for narrow table columns: "bias x", "scale x", "θyz".
inline std::string_view ParameterShortLabel(int i) {
  static constexpr std::string_view kLabels[] = {"bias x",
                                                 "bias y",
                                                 "bias z",
                                                 "scale x",
                                                 "scale y",
                                                 "scale z",
                                                 "\u03b8yz",
                                                 "\u03b8zx",
                                                 "\u03b8zy"};
  return kLabels[i];
}

}  // namespace mpcal::report
