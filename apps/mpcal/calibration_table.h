// The calibration as people read it: each parameter ±1σ in the units they
// use (bias in mg and m/s², scale-factor error in ppm, non-orthogonality in
// mrad), then the fit. Shared by `calibrate` and `demo`.
#pragma once

#include <optional>
#include <string>

#include "mpcal/calibrate.h"
#include "mpcal/calibration.h"

namespace mpcal::cli {

/// A column of values to print beside the estimate (e.g. the truth, or the
/// Cramér-Rao 1σ), in the packed order of kParameterNames, SI.
struct ExtraColumn {
  std::string title;
  Eigen::Matrix<double, 9, 1> values_si;
};

/// The parameter table of `calibration`, with optional extra columns.
std::string FormatParameterTable(const Calibration& calibration,
                                 const std::vector<ExtraColumn>& extra = {});

/// The positions found and how the fit went, a few lines.
std::string FormatFitSummary(const CalibrateResult& result);

/// Prints each warning as `mpcal: warning: ...` on stderr.
void PrintWarnings(const std::vector<std::string>& warnings);

}  // namespace mpcal::cli
