// One weighted least-squares fit of the multi-position method (Souza &
// Machado 2016, eq 12) with Ceres, and the helpers the steps of Solve share:
// the magnitude residuals, the selection of the used positions, leverages
// and standardised residuals. Room-private: Ceres stays in src/solve.
#pragma once

#include <algorithm>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <ceres/ceres.h>
#include <Eigen/Core>

#include "mpcal/model.h"
#include "mpcal/solve.h"

namespace mpcal::internal {

// Consistency factor of the median absolute deviation for Gaussian data.
inline constexpr double kMadToSigma = 1.4826;

// The parameter blocks Ceres estimates, in the packed order of model.h.
struct Blocks {
  double bias[3];
  double scale[3];
  double angles[3];
  double drift[3] = {0.0, 0.0, 0.0};  // m/s² per s, with a drifting bias

  explicit Blocks(const ErrorModel& m) {
    double p[kNumModelParameters];
    m.ToParameters(p);
    std::copy(p, p + 3, bias);
    std::copy(p + 3, p + 6, scale);
    std::copy(p + 6, p + 9, angles);
  }
  ErrorModel Model() const {
    double p[kNumModelParameters];
    std::copy(bias, bias + 3, p);
    std::copy(scale, scale + 3, p + 3);
    std::copy(angles, angles + 3, p + 6);
    return ErrorModel::FromParameters(p);
  }
  // The model with the bias of a position held `dt_s` from the reference.
  ErrorModel ModelAt(double dt_s) const {
    ErrorModel m = Model();
    m.bias_mps2 += Eigen::Vector3d(drift[0], drift[1], drift[2]) * dt_s;
    return m;
  }
};

/// The middle of a position (s), where a drifting bias is taken to act on it.
double MidTime(const PositionObservation& p);

/// |Correct(mean)| − g of one position (m/s²).
double Magnitude(const ErrorModel& model,
                 const PositionObservation& p,
                 double gravity_mps2);

/// Magnitude() of every position.
std::vector<double> MagnitudeResiduals(const ErrorModel& model,
                                       std::span<const PositionObservation> positions,
                                       double gravity_mps2);

/// RMS of the entries of `v` whose `used` is true; 0 when none is.
double Rms(const std::vector<double>& v, const std::vector<bool>& used);

/// The element of rank size/2 (the upper median). \pre v not empty.
double Median(std::vector<double> v);

/// The diagonal of the hat matrix J (JᵀJ)⁻¹ Jᵀ of a whitened Jacobian: how
/// much each position pulls the fit towards itself (they sum to p).
std::vector<double> Leverages(const Eigen::MatrixXd& j);

/// The names of the estimated parameters (packed order), with the three
/// drift rates last when the bias drifts.
std::vector<std::string> EstimatedNames(ModelKind model, bool drift = false);

// The positions one fit uses, with the noise of each made safe to weigh by.
struct FitInput {
  std::vector<std::size_t> index;  // into the caller's positions
  std::vector<PositionObservation> positions;
  std::vector<Eigen::Vector3d> noise;
};
/// The used positions (used[k]) with their noise.
FitInput Select(std::span<const PositionObservation> positions,
                const std::vector<Eigen::Vector3d>& noise,
                const std::vector<bool>& used);

// One weighted least-squares fit and the state the covariance, the
// observability check and cross-validation need afterwards.
class Fit {
 public:
  // With `drift_reference_s`, the bias drifts linearly in time and the
  // estimate's bias is the bias at that time.
  Fit(const FitInput& input,
      const ErrorModel& start,
      const SolveOptions& options,
      std::optional<double> drift_reference_s = std::nullopt)
      : input_(input),
        options_(options),
        blocks_(start),
        drift_reference_s_(drift_reference_s) {}

  // Two passes: the weights depend on the parameters and on the residuals, so
  // the second weighs each position at the first estimate. A robust loss, when
  // asked for, enters in the second pass, scaled to the whitened residuals of
  // the first so that it reacts to outliers and not to the overall noise level.
  //
  // Throws mpcal::Error when the positions leave parameters undetermined:
  // asked before solving, since a solver let loose on an undetermined
  // problem wanders off, and the Jacobian where it stops says nothing.
  void Run();

  // |a| − g of position k at the fit's estimate, or predicted by a refit
  // without it (one pass from this estimate, with the same weights).
  double Residual(std::size_t k) const;
  double PredictedWithout(std::size_t k) const;

  // Whitened residuals × estimated parameters at the current estimate.
  Eigen::MatrixXd Jacobian();

  // (JᵀJ)⁻¹ of the whitened problem, by Ceres; p × p in packed order.
  // Throws mpcal::Error when Ceres cannot compute it.
  Eigen::MatrixXd UnscaledCovariance();

  ErrorModel Estimate() const { return blocks_.Model(); }
  bool drifts() const { return drift_reference_s_.has_value(); }
  Eigen::Vector3d Drift() const {
    return Eigen::Vector3d(blocks_.drift[0], blocks_.drift[1], blocks_.drift[2]);
  }
  // The estimated parameters, in the order of the covariance.
  std::vector<std::string> Names() const {
    return EstimatedNames(options_.model, drifts());
  }
  /// σ of each position's residual from its sensor noise alone, without the
  /// scatter component.
  const std::vector<double>& own_sigmas() const { return own_sigmas_; }
  double scatter_variance() const { return scatter_variance_; }
  const std::vector<double>& sigmas() const { return sigmas_; }
  const ceres::Solver::Summary& summary() const { return summary_; }
  int iterations() const { return iterations_; }
  std::size_t size() const { return input_.positions.size(); }

 private:
  std::vector<double> Sigmas(const ErrorModel& m) const;
  void ThrowIfUndetermined();
  void WeighByScatter();
  void AddResiduals(const std::vector<PositionObservation>& positions,
                    const std::vector<double>& sigmas,
                    RobustLoss loss,
                    Blocks& blocks,
                    ceres::Problem& problem) const;
  void Build(RobustLoss loss);
  // Ceres names parameter blocks by their address.
  std::vector<double*> Estimated();
  // Time of a position from the drift's reference (0 without drift).
  double Dt(const PositionObservation& p) const {
    return drift_reference_s_ ? MidTime(p) - *drift_reference_s_ : 0.0;
  }

  FitInput input_;
  SolveOptions options_;
  Blocks blocks_;
  std::optional<double> drift_reference_s_;
  std::vector<double> sigmas_;
  std::vector<double> own_sigmas_;
  double loss_scale_ = 1.0;
  double scatter_variance_ = 0.0;
  std::unique_ptr<ceres::Problem> problem_;
  ceres::Solver::Summary summary_;
  int iterations_ = 0;
};

/// χ² of the fit's residuals against the weights `sigmas` (one per used
/// position, in the fit's order).
double ChiSquare(const Fit& fit, const std::vector<double>& sigmas);

// Each used position's residual in units of its standard deviation under
// the scatter model (σ_k² + τ², `total`) and under its sensor noise alone
// (σ_k², `own`), corrected for the pull it has on the fit (leverage h:
// var(e_k) = σ² (1 − h_k)).
struct StandardisedResiduals {
  std::vector<double> total;
  std::vector<double> own;
};

StandardisedResiduals Standardise(Fit& fit);

}  // namespace mpcal::internal
