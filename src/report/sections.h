// The sections of the report, each a fragment of HTML (<section>…</section>)
// made from one input. report.cc puts together those whose input is given.
#pragma once

#include <functional>
#include <string>

#include "mpcal/calibration.h"
#include "mpcal/report.h"

namespace mpcal::report {

/// Title, date, versions, input files and options (for reproduction), and
/// links to the sections of `main_html` (every <section id> with its <h2>).
std::string HeaderSection(const ReportInputs& inputs,
                          const std::string& generated_at,
                          const std::string& main_html);

/// Parameters ±1σ, fit statistics, residuals per position, sphere coverage,
/// cross-validation and warnings.
std::string CalibrationSection(const Calibration& calibration);

/// The gyroscope of an IMU calibration (empty without one): M ±1σ, the bias
/// at every position; with the session's recording holding the gyroscope,
/// the turn residuals before and after and the turn axes on the sphere
/// (section_gyro.cc).
std::string GyroSection(const Calibration& calibration, const ReportSession* session);

/// The recording against time with its static intervals shaded. With a
/// calibration whose positions lie in the recording, those are shaded and
/// numbered as in the calibration section.
std::string SessionSection(const ReportSession& session, const Calibration* calibration);

/// The trials table and the spread of each parameter against its 1σ.
std::string RepeatabilitySection(const RepeatabilityResult& repeatability);

/// The Allan deviation of each axis with its band and fitted terms, and the
/// terms table (`mpcal noise --json`).
std::string NoiseSection(const NoiseFile& noise);

/// Start-to-end distances and the paths in east-north metres; error against
/// time when the paths are given. Without paths, says so, with the advice
/// worded by `explain_advice` when the caller gives it.
std::string VerificationSection(
    const VerificationSummary& verification,
    const std::function<std::string(const Advice&)>& explain_advice);

}  // namespace mpcal::report
