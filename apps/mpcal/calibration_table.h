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

/// The parameter table of `calibration`, with optional extra columns; with
/// `details`, the nominal scale of raw counts under it.
std::string FormatParameterTable(const Calibration& calibration,
                                 const std::vector<ExtraColumn>& extra = {},
                                 bool details = true);

/// The positions found and how the fit went, a few lines.
std::string FormatFitSummary(const CalibrateResult& result);

/// Holds each warning, printed as `mpcal: warning: ...` on stderr when the
/// command ends well (FlushWarnings); a command that fails prints only its
/// error line, with the first warning folded into it.
void PrintWarnings(const std::vector<std::string>& warnings);
/// Prints the held warnings now (the command has finished its work).
void FlushWarnings();
/// The held warnings, emptied.
std::vector<std::string> TakeHeldWarnings();

}  // namespace mpcal::cli
