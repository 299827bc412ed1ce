// The named steps of Solve (solve.cc), in the order it takes them: check the
// input, exclude outliers, choose a drifting bias, judge convergence, warn,
// cross-validate, scale the covariance, widen it by the split-half check.
// Each step that carries a rule (WorstOutlier, BiasReferenceTime,
// IsPlausibleEstimate, CovarianceScale, DriftFTest) is a function of plain
// numbers, tested on its own (tests/solve/solve_steps_test.cc).
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "fit.h"
#include "mpcal/solve.h"

namespace mpcal::internal {

/// Throws mpcal::Error for invalid options, fewer positions than the model
/// has parameters (advising the six-parameter model when six or more are
/// given) or a non-finite position mean.
void CheckSolveInput(std::span<const PositionObservation> positions,
                     const SolveOptions& options);

/// A position this many times its own noise level off the fit is a bump,
/// not part of a heavy-tailed scatter, when it also stands out from the
/// scatter model by the outlier threshold.
inline constexpr double kOwnNoiseOutlier = 10.0;

/// The outlier rule: the index (into z) of the position to exclude next, or
/// nullopt. Against the scatter model σ_k² + τ² (`z.total`), beyond
/// `threshold` times a robust scale of the rest (1.4826 × the median |z|,
/// never below 1); a position beyond kOwnNoiseOutlier times its own noise
/// level (`z.own`) is judged against `threshold` alone, whatever that robust
/// scale (residuals heavier-tailed than the scatter model must not shelter
/// it). The worst by its excess over its limit goes first.
std::optional<std::size_t> WorstOutlier(const StandardisedResiduals& z, double threshold);

/// Outliers, worst first, one at a time (a bumped position pulls the fit
/// towards itself and can hide a second one until it is gone), at most
/// kMaxOutlierShare of the positions and never below p + 1 used. A position
/// the parameters cannot do without is kept, with a warning.
void ExcludeOutliers(std::span<const PositionObservation> positions,
                     const std::vector<Eigen::Vector3d>& noise,
                     const SolveOptions& options,
                     std::unique_ptr<Fit>& fit,
                     SolveResult& result);

/// The time a drifting bias is reported at: options.bias_reference_time_s,
/// else the mean of the used positions' middles, where the bias is nearly
/// uncorrelated with the drift rate (so it is the bias a constant-bias fit
/// finds, and a drift chosen by chance barely moves it).
double BiasReferenceTime(std::span<const PositionObservation> positions,
                         const std::vector<bool>& used,
                         const SolveOptions& options);

/// The F test of a drifting bias: F = ((χ²₀ − χ²₁)/3) / (χ²₁/redundancy)
/// with F(3, redundancy); its p-value, or nullopt when χ²₁ is not positive.
std::optional<double> DriftFTest(double chi2_constant, double chi2_drift, int redundancy);

/// The bias drift model fitted to the same positions and chosen over the
/// constant bias when DriftFTest rejects it at
/// options.bias_drift_significance (or when options.force_bias_drift):
/// `fit` is then replaced by the drifting fit.
/// \throws mpcal::Error when forced and the positions cannot carry it.
void ChooseBiasDrift(const FitInput& in,
                     const SolveOptions& options,
                     double reference_s,
                     std::unique_ptr<Fit>& fit,
                     SolveResult& result);

/// Whether an estimate is in the region where the model means anything for
/// a MEMS part (|s| < 0.5, |angle| < 0.5 rad, finite): beyond it the solver
/// has diverged, whatever Ceres says.
bool IsPlausibleEstimate(const ErrorModel& estimate);

/// The residuals after the fit (with the drift at each position's time) and
/// their RMS, the scatter, the cost, the status and its message. False when
/// the fit did not converge or left the plausible region.
bool JudgeFit(std::span<const PositionObservation> positions,
              const SolveOptions& options,
              double reference_s,
              Fit& fit,
              SolveResult& result);

/// The warnings of a converged fit: poorly determined parameters (also in
/// result.poorly_determined) and no redundancy at all.
void WarnAboutDetermination(
    std::size_t count, int parameters, int dof, Fit& fit, SolveResult& result);

/// Standardised residuals of the used positions, and with
/// options.cross_validate and dof > 0, each used position predicted by the
/// fit without it (NaN where the rest do not determine the parameters).
void CrossValidate(std::span<const PositionObservation> positions,
                   const std::vector<Eigen::Vector3d>& noise,
                   const SolveOptions& options,
                   int dof,
                   Fit& fit,
                   SolveResult& result);

/// The factor the unscaled covariance (JᵀJ)⁻¹ is multiplied by: the update
/// (kPriorDof + χ²)/(kPriorDof + dof) of a scaled inverse-χ² prior centred
/// on 1 worth kPriorDof residuals, never below 1 (docs/method.md §3.6).
inline constexpr double kPriorDof = 10.0;
double CovarianceScale(double chi2, int dof);

/// The variance factor, covariance and 1σ of a converged fit.
void SetCovariance(int dof, Fit& fit, SolveResult& result);

/// The split-half check, and every 1σ widened by its rule when two halves
/// disagree beyond chance (docs/method.md §9).
void WidenBySplitHalves(std::span<const PositionObservation> positions,
                        const SolveOptions& options,
                        SolveResult& result);

}  // namespace mpcal::internal
