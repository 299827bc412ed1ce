#include "mpcal/verdict.h"

#include <algorithm>
#include <cmath>

#include "mpcal/distributions.h"
#include "mpcal/model.h"

namespace mpcal {
namespace {

Check FitCheck(const CalibrateResult& result, int dof) {
  const SolveResult& s = result.solve;
  Check c{CheckKind::kFit, Verdict::kGood, CheckFinding::kFitWithinNoise};
  c.value = s.variance_factor;
  if (!s.converged()) {
    c.verdict = Verdict::kDoNotUse;
    c.finding = CheckFinding::kFitNotConverged;
    return c;
  }
  c.count = static_cast<int>(std::count(s.used.begin(), s.used.end(), false));
  // With no redundancy the variance factor is 1 by construction: nothing to test.
  const double p = dof > 0 ? ChiSquareUpperTail(s.variance_factor * dof, dof) : 1.0;
  c.limit = p;
  if (p < kFitSignificance) {
    c.verdict = Verdict::kLookAt;
    c.finding = CheckFinding::kFitBeyondNoise;
  } else if (c.count > 0) {
    c.verdict = Verdict::kLookAt;
    c.finding = CheckFinding::kOutliersExcluded;
  }
  return c;
}

Check PositionsCheck(const CalibrateResult& result, int used, int dof) {
  Check c{CheckKind::kPositions, Verdict::kGood, CheckFinding::kPositionsEnough};
  c.count = used;
  c.value = dof;
  if (!result.solve.poorly_determined.empty()) {
    c.verdict = Verdict::kLookAt;
    c.finding = CheckFinding::kPoorlyDetermined;
    c.count = static_cast<int>(result.solve.poorly_determined.size());
  } else if (dof <= 0) {
    c.verdict = Verdict::kLookAt;
    c.finding = CheckFinding::kPositionsNoRedundancy;
  }
  return c;
}

Check DriftCheck(const CalibrateResult& result, const SolveOptions& options) {
  const SolveResult& s = result.solve;
  Check c{CheckKind::kBiasDrift, Verdict::kGood, CheckFinding::kDriftNotSignificant};
  c.limit = options.bias_drift_significance;
  if (s.bias_drift) {
    // A drifting bias is fitted and reported at its reference time: the
    // numbers hold, but a sensor that had not warmed up drifts on.
    c.verdict = Verdict::kLookAt;
    c.finding = CheckFinding::kDriftFitted;
    c.value = s.bias_drift->p_value;
  } else if (s.bias_drift_p_value) {
    c.value = *s.bias_drift_p_value;
  } else {
    c.verdict = Verdict::kLookAt;
    c.finding = CheckFinding::kDriftNotTested;
  }
  return c;
}

Check SplitHalfCheck(const CalibrateResult& result, const SolveOptions& options) {
  Check c{CheckKind::kSplitHalf, Verdict::kGood, CheckFinding::kSplitConsistent};
  const auto& summary = result.solve.split_half;
  c.finding = CheckFinding::kSplitNotPossible;
  c.verdict = Verdict::kLookAt;
  if (!summary) return c;
  c.limit = PerSplitSignificance(summary->comparisons, options.split_half_significance);
  c.value = 1.0;
  for (const SplitHalfComparison& s : summary->comparisons) {
    if (!s.determined) continue;
    c.finding = CheckFinding::kSplitConsistent;
    c.verdict = Verdict::kGood;
    c.value = std::min(c.value, s.p_value);
    if (s.disagree) ++c.count;
  }
  if (c.count > 0) {
    // Halves of one session that disagree beyond chance: something the
    // model does not capture (a bumped stretch) moves the estimate.
    c.verdict = Verdict::kDoNotUse;
    c.finding = CheckFinding::kSplitDisagree;
  }
  return c;
}

Check UnitsCheck(const CalibrateResult& result) {
  // CheckUnits has refused readings that do not fit their units before
  // the fit; raw counts have no unit to check, only the scale found.
  Check c{CheckKind::kUnits, Verdict::kGood, CheckFinding::kUnitsFixed};
  if (result.calibration.input_units == AccelUnits::kCounts) {
    c.finding = CheckFinding::kUnitsCounts;
    c.value = result.calibration.gravity_mps2 / result.mps2_per_unit;
  }
  return c;
}

Check GyroCheck(const GyroResult& g) {
  Check c{CheckKind::kGyroscope, Verdict::kGood, CheckFinding::kGyroConverged};
  for (const GyroFinding& f : g.findings) {
    if (f.kind == GyroFindingKind::kPoorlyDetermined) {
      c.verdict = Verdict::kLookAt;
      c.finding = CheckFinding::kGyroPoorlyDetermined;
      c.count = static_cast<int>(f.parameters.size());
      c.value = f.value;
      c.limit = f.limit;
    } else {
      c.verdict = Verdict::kDoNotUse;
      c.finding = CheckFinding::kGyroNotCalibrated;
      return c;
    }
  }
  if (g.status == GyroStatus::kNoConvergence) {
    c.verdict = Verdict::kDoNotUse;
    c.finding = CheckFinding::kGyroNotConverged;
    return c;
  }
  if (g.status != GyroStatus::kConverged || !g.calibration.fit) {
    c.verdict = Verdict::kDoNotUse;
    c.finding = CheckFinding::kGyroNotCalibrated;
    return c;
  }
  if (c.finding == CheckFinding::kGyroConverged) {
    c.value = g.calibration.fit->residual_rms_after_rad;
    c.limit = g.calibration.fit->variance_factor;
    c.count = g.calibration.fit->turns;
  }
  return c;
}

}  // namespace

std::vector<Check> JudgeCalibration(const CalibrateResult& result,
                                    const CalibrateOptions& options) {
  const SolveResult& s = result.solve;
  const int used = static_cast<int>(std::count(s.used.begin(), s.used.end(), true));
  const int dof = used - ParameterCount(options.solve.model) - (s.bias_drift ? 3 : 0);
  std::vector<Check> checks{FitCheck(result, dof),
                            PositionsCheck(result, used, dof),
                            DriftCheck(result, options.solve),
                            SplitHalfCheck(result, options.solve),
                            UnitsCheck(result)};
  if (result.gyro) checks.push_back(GyroCheck(*result.gyro));
  return checks;
}

}  // namespace mpcal
