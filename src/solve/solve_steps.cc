#include "solve_steps.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "mpcal/count.h"
#include "mpcal/distributions.h"
#include "mpcal/error.h"
#include "mpcal/plausible.h"
#include "observability.h"
#include "split_half.h"

namespace mpcal::internal {
namespace {

// Beyond these the solver has left the region where the model means anything
// for a MEMS part: the fit has diverged, whatever Ceres says.
constexpr double kMaxPlausibleScaleError = 0.5;
constexpr double kMaxPlausibleAngleRad = 0.5;

// At most this share of the positions is excluded as outliers: beyond it the
// session itself is bad, and hiding that would mislead.
constexpr double kMaxOutlierShare = 0.2;

// Fewer redundant positions than this, with the drift's three parameters
// fitted, leave the test too little to judge by.
constexpr int kMinDriftRedundancy = 3;

SolveNote OutlierNote(SolveNoteKind kind,
                      const PositionObservation& position,
                      std::size_t k,
                      double own_z) {
  SolveNote note;
  note.kind = kind;
  note.position = k;
  note.start_s = position.start_s;
  note.end_s = position.end_s;
  note.residual_z = std::abs(own_z);
  return note;
}

// One position out; false (and the position back in, with a warning) when
// the rest no longer determine the parameters.
bool TryExclude(std::span<const PositionObservation> positions,
                const std::vector<Eigen::Vector3d>& noise,
                const SolveOptions& options,
                std::size_t k,
                double own_z,
                std::unique_ptr<Fit>& fit,
                SolveResult& result) {
  result.used[k] = false;
  auto refit = std::make_unique<Fit>(
      Select(positions, noise, result.used), fit->Estimate(), options);
  try {
    refit->Run();
  } catch (const Error&) {
    result.used[k] = true;
    result.notes.push_back(
        OutlierNote(SolveNoteKind::kOutlierKept, positions[k], k, own_z));
    result.warnings.push_back(fmt::format(
        "position {} ({:.1f}-{:.1f} s) fits badly ({:.1f} times its noise) but cannot "
        "be excluded: no other position determines the same parameters",
        k + 1,
        positions[k].start_s,
        positions[k].end_s,
        std::abs(own_z)));
    return false;
  }
  result.notes.push_back(
      OutlierNote(SolveNoteKind::kOutlierExcluded, positions[k], k, own_z));
  result.warnings.push_back(
      fmt::format("position {} ({:.1f}-{:.1f} s) excluded as an outlier: its residual "
                  "is {:.1f} times "
                  "its noise level (was the sensor bumped or not fully still?)",
                  k + 1,
                  positions[k].start_s,
                  positions[k].end_s,
                  std::abs(own_z)));
  fit = std::move(refit);
  result.iterations += fit->iterations();
  return true;
}

}  // namespace

void CheckSolveInput(std::span<const PositionObservation> positions,
                     const SolveOptions& options) {
  if (const std::string problem = options.Validate(); !problem.empty()) {
    throw Error(ErrorKind::kOption, "solve options: " + problem);
  }
  const int p = ParameterCount(options.model);
  const std::size_t count = positions.size();
  if (static_cast<int>(count) < p) {
    // Six or more: the axis-up/axis-down positions of the six-position
    // protocol may be all there is, and its model fits them.
    const bool six_would_do = options.model == ModelKind::kShinElSheimy9 && count >= 6;
    Advice advice;
    if (six_would_do) {
      advice.settings.push_back(
          {Option::kModel, std::string(ToString(ModelKind::kBiasScale6))});
    }
    throw Error(ErrorKind::kSession,
                fmt::format("{} too few for the {} model ({} "
                            "parameters): it needs at least {}, and more than 18 "
                            "spanning the sphere for reliable results{}",
                            Count(count, "static position is", "static positions are"),
                            ToString(options.model),
                            p,
                            p,
                            six_would_do ? "; with the six axis-up/axis-down positions, "
                                           "calibrate bias and scale only"
                                         : ""),
                advice);
  }
  for (std::size_t k = 0; k < count; ++k) {
    if (!positions[k].mean_mps2.allFinite() ||
        !positions[k].sample_std_mps2.allFinite()) {
      throw Error(ErrorKind::kInput,
                  fmt::format("static position {} (at {:.2f} s) has a non-finite mean",
                              k + 1,
                              positions[k].start_s));
    }
  }
}

std::optional<std::size_t> WorstOutlier(const StandardisedResiduals& z,
                                        double threshold) {
  if (z.total.empty()) return std::nullopt;
  std::vector<double> abs_z;
  for (double v : z.total) abs_z.push_back(std::abs(v));
  const double scale = std::max(1.0, kMadToSigma * Median(abs_z));
  std::size_t worst = 0;
  double worst_excess = 0.0;
  for (std::size_t j = 0; j < abs_z.size(); ++j) {
    const bool far_beyond_own_noise = std::abs(z.own[j]) > kOwnNoiseOutlier;
    const double excess = abs_z[j] / (threshold * (far_beyond_own_noise ? 1.0 : scale));
    if (excess > worst_excess) {
      worst = j;
      worst_excess = excess;
    }
  }
  if (worst_excess <= 1.0) return std::nullopt;
  return worst;
}

void ExcludeOutliers(std::span<const PositionObservation> positions,
                     const std::vector<Eigen::Vector3d>& noise,
                     const SolveOptions& options,
                     std::unique_ptr<Fit>& fit,
                     SolveResult& result) {
  const auto count = static_cast<int>(positions.size());
  const int max_excluded = std::min(static_cast<int>(kMaxOutlierShare * count),
                                    count - (ParameterCount(options.model) + 1));
  for (int excluded = 0; excluded < max_excluded; ++excluded) {
    const FitInput in = Select(positions, noise, result.used);
    const StandardisedResiduals z = Standardise(*fit);
    const std::optional<std::size_t> worst = WorstOutlier(z, options.outlier_threshold);
    if (!worst) return;
    if (!TryExclude(
            positions, noise, options, in.index[*worst], z.own[*worst], fit, result)) {
      return;
    }
  }
}

double BiasReferenceTime(std::span<const PositionObservation> positions,
                         const std::vector<bool>& used,
                         const SolveOptions& options) {
  if (options.bias_reference_time_s) return *options.bias_reference_time_s;
  double sum_s = 0.0;
  int used_count = 0;
  for (std::size_t k = 0; k < positions.size(); ++k) {
    if (!used[k]) continue;
    sum_s += MidTime(positions[k]);
    ++used_count;
  }
  return sum_s / std::max(used_count, 1);
}

std::optional<double> DriftFTest(double chi2_constant,
                                 double chi2_drift,
                                 int redundancy) {
  if (!(chi2_drift > 0.0) || redundancy < 1) return std::nullopt;
  const double f = (chi2_constant - chi2_drift) / 3.0 / (chi2_drift / redundancy);
  return FUpperTail(f, 3, redundancy);
}

namespace {

// The test of the drift's three parameters. When the drifting fit's residuals
// show no scatter beyond the sensor noise (its scatter test at 1 % did not
// fire), the weights are known — each position's
// noise, measured from its own thousands of samples — and the likelihood
// ratio, the drop in χ² under those weights, is χ² with 3 degrees of
// freedom. Otherwise the weights' level is estimated from the residuals and
// the F test accounts for it, both χ² with the constant fit's weights (its
// noise and scatter). The F test alone missed most drifts at few redundant
// positions (F(3, 2) rejects at 1 % beyond 99, χ²(3)/3 beyond 3.8), and a
// missed drift goes into the scatter and the 1σ of every parameter.
std::optional<double> DriftPValue(const Fit& constant,
                                  const Fit& drifting,
                                  int redundancy) {
  if (drifting.scatter_variance() == 0.0) {
    const double drop =
        ChiSquare(constant, drifting.sigmas()) - ChiSquare(drifting, drifting.sigmas());
    if (!std::isfinite(drop)) return std::nullopt;
    return ChiSquareUpperTail(std::max(drop, 0.0), 3);
  }
  return DriftFTest(ChiSquare(constant, constant.sigmas()),
                    ChiSquare(drifting, constant.sigmas()),
                    redundancy);
}

}  // namespace

void ChooseBiasDrift(const FitInput& in,
                     const SolveOptions& options,
                     double reference_s,
                     std::unique_ptr<Fit>& fit,
                     SolveResult& result) {
  const int redundancy =
      static_cast<int>(in.positions.size()) - ParameterCount(options.model) - 3;
  if (options.force_bias_drift && redundancy < 1) {
    throw Error(ErrorKind::kSession,
                fmt::format("{} too few for the model with a drifting bias",
                            Count(in.positions.size(), "position is", "positions are")));
  }
  if (redundancy < (options.force_bias_drift ? 1 : kMinDriftRedundancy)) return;
  auto drifting = std::make_unique<Fit>(in, fit->Estimate(), options, reference_s);
  try {
    drifting->Run();
  } catch (const Error&) {
    if (options.force_bias_drift) throw;
    return;  // the positions do not separate a drift from the other parameters
  }
  if (drifting->summary().termination_type != ceres::CONVERGENCE) {
    if (options.force_bias_drift)
      throw Error(ErrorKind::kSession, "the fit with a drifting bias did not converge");
    return;
  }
  const std::optional<double> p_value = DriftPValue(*fit, *drifting, redundancy);
  if (!p_value) return;
  result.bias_drift_p_value = *p_value;
  if (!(*p_value < options.bias_drift_significance) && !options.force_bias_drift) return;
  BiasDrift drift;
  drift.mps2_per_s = drifting->Drift();
  drift.reference_time_s = reference_s;
  drift.p_value = *p_value;
  result.bias_drift = drift;
  result.iterations += drifting->iterations();
  fit = std::move(drifting);
}

bool IsPlausibleEstimate(const ErrorModel& estimate) {
  return estimate.scale_factor_error.cwiseAbs().maxCoeff() < kMaxPlausibleScaleError &&
         std::max({std::abs(estimate.theta_yz_rad),
                   std::abs(estimate.theta_zx_rad),
                   std::abs(estimate.theta_zy_rad)}) < kMaxPlausibleAngleRad &&
         ToVector(estimate).allFinite();
}

bool JudgeFit(std::span<const PositionObservation> positions,
              const SolveOptions& options,
              double reference_s,
              Fit& fit,
              SolveResult& result) {
  result.estimate = fit.Estimate();
  result.position_scatter_mps2 = std::sqrt(fit.scatter_variance());
  result.final_cost = fit.summary().final_cost;
  result.residual_after_mps2.clear();
  for (const PositionObservation& p : positions) {
    ErrorModel at = result.estimate;
    if (fit.drifts()) at.bias_mps2 += fit.Drift() * (MidTime(p) - reference_s);
    result.residual_after_mps2.push_back(Magnitude(at, p, options.gravity_mps2));
  }
  result.residual_rms_before_mps2 = Rms(result.residual_before_mps2, result.used);
  result.residual_rms_after_mps2 = Rms(result.residual_after_mps2, result.used);

  const bool plausible = IsPlausibleEstimate(result.estimate);
  if (fit.summary().termination_type != ceres::CONVERGENCE || !plausible) {
    result.status = SolveStatus::kNoConvergence;
    result.message = plausible ? fit.summary().message
                               : "the estimate left the plausible range (|s| < 0.5, "
                                 "|angle| < 0.5 rad): the solver diverged";
    return false;
  }
  result.status = SolveStatus::kConverged;
  result.message = fit.summary().message;
  return true;
}

void WarnAboutDetermination(
    std::size_t count, int parameters, int dof, Fit& fit, SolveResult& result) {
  for (const std::string& name :
       AnalyseObservability(fit.Jacobian(), fit.Names()).poorly_determined) {
    result.poorly_determined.push_back(name);
    SolveNote note;
    note.kind = SolveNoteKind::kPoorlyDetermined;
    note.parameter = name;
    result.notes.push_back(note);
    result.warnings.push_back(
        fmt::format("{} is poorly determined by these positions (strongly correlated "
                    "with other parameters): add positions that fill the gaps in their "
                    "coverage of the sphere",
                    name));
  }
  if (dof == 0) {
    SolveNote note;
    note.kind = SolveNoteKind::kNoRedundancy;
    note.positions = count;
    note.parameters = parameters;
    result.notes.push_back(note);
    result.warnings.push_back(fmt::format(
        "{} positions for {} parameters leave no redundancy: the residuals are zero by "
        "construction and cannot reveal a bad position; the 1σ come from the sensor "
        "noise "
        "alone. Record a few more positions (edges, corners) to check the fit",
        count,
        parameters));
  }
}

void CrossValidate(std::span<const PositionObservation> positions,
                   const std::vector<Eigen::Vector3d>& noise,
                   const SolveOptions& options,
                   int dof,
                   Fit& fit,
                   SolveResult& result) {
  // An excluded position is already predicted by the final fit, which lacks it.
  const FitInput in = Select(positions, noise, result.used);
  const std::vector<double> z = Standardise(fit).total;
  result.standardised_residual.assign(positions.size(), 0.0);
  for (std::size_t j = 0; j < in.index.size(); ++j)
    result.standardised_residual[in.index[j]] = z[j];
  if (!options.cross_validate || dof <= 0) return;
  // A position that alone determines some parameter (the only one with +x
  // up, say) cannot be predicted without it: NaN, not a made-up number.
  result.cross_validation_residual_mps2 = result.residual_after_mps2;
  const Eigen::MatrixXd jacobian = fit.Jacobian();
  std::vector<bool> predicted = result.used;
  for (std::size_t j = 0; j < in.index.size(); ++j) {
    Eigen::MatrixXd without(jacobian.rows() - 1, jacobian.cols());
    const auto row = static_cast<Eigen::Index>(j);
    without << jacobian.topRows(row), jacobian.bottomRows(jacobian.rows() - row - 1);
    const bool determined =
        AnalyseObservability(without, fit.Names()).undetermined.empty();
    result.cross_validation_residual_mps2[in.index[j]] =
        determined ? fit.PredictedWithout(j) : std::numeric_limits<double>::quiet_NaN();
    predicted[in.index[j]] = determined;
  }
  result.cross_validation_rms_mps2 =
      Rms(result.cross_validation_residual_mps2, predicted);
}

// The weights already carry the noise measured from thousands of samples per
// position; K − p residuals (5 for 14 positions) can reveal extra error (hand
// tremor, non-white noise, misfit) but would often understate the noise by
// half if trusted the other way. Nor are a few residuals trusted alone the
// other way: 5 residuals at 3.7 times their expected square by chance (1
// session in 2000) raise the 1σ by 1.4, not 1.9, while 30 at that level, a
// real misfit, raise it by 1.7.
double CovarianceScale(double chi2, int dof) {
  return std::max(1.0, (kPriorDof + chi2) / (kPriorDof + dof));
}

void SetCovariance(int dof, Fit& fit, SolveResult& result) {
  const double chi2 = ChiSquare(fit, fit.sigmas());
  // With no redundancy the residuals say nothing: keep the a-priori level.
  result.variance_factor = dof > 0 ? chi2 / dof : 1.0;
  const Eigen::MatrixXd covariance =
      CovarianceScale(chi2, dof) * fit.UnscaledCovariance();
  const int p = static_cast<int>(fit.Names().size()) - (fit.drifts() ? 3 : 0);
  result.covariance.topLeftCorner(p, p) = covariance.topLeftCorner(p, p);
  result.std = FromVector(result.covariance.diagonal().cwiseMax(0.0).cwiseSqrt());
  if (fit.drifts()) {
    result.bias_drift->std_mps2_per_s =
        covariance.bottomRightCorner(3, 3).diagonal().cwiseMax(0.0).cwiseSqrt();
  }
}

void WidenBySplitHalves(std::span<const PositionObservation> positions,
                        const SolveOptions& options,
                        SolveResult& result) {
  result.split_half = CheckSplitHalves(positions, result.used, options);
  const double widening = result.split_half->widening;
  if (!(widening > 1.0)) return;
  result.covariance *= widening * widening;
  result.std = FromVector(result.covariance.diagonal().cwiseMax(0.0).cwiseSqrt());
  if (result.bias_drift) result.bias_drift->std_mps2_per_s *= widening;
  for (const SplitHalfComparison& c : result.split_half->comparisons) {
    if (!c.determined || !c.disagree) continue;
    SolveNote note;
    note.kind = SolveNoteKind::kHalvesDisagree;
    note.halves = c;
    note.widening = widening;
    result.notes.push_back(note);
    result.warnings.push_back(
        fmt::format("the two halves of the positions ({}, {} and {}) give estimates that "
                    "differ beyond "
                    "their 1σ (RMS z {:.2f} over {} parameters, chi-square p = {:.2g}): "
                    "something the "
                    "model does not capture (a drifting bias, a bumped stretch) is in "
                    "the session; every "
                    "1σ is widened by {:.2f}",
                    c.kind == SplitKind::kByTime ? "by time" : "alternate positions",
                    c.positions_first,
                    c.positions_second,
                    c.rms_z,
                    c.dof,
                    c.p_value,
                    widening));
  }
}

}  // namespace mpcal::internal
