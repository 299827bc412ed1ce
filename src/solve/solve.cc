// The multi-position least squares (Souza & Machado 2016, eq 12) with Ceres,
// with outlier positions excluded and every position cross-validated.
#include "mpcal/solve.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include <ceres/ceres.h>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "mpcal/error.h"
#include "mpcal/plausible.h"
#include "observability.h"
#include "residual.h"
#include "split_half.h"
#include "weights.h"

namespace mpcal {
namespace {

using internal::MagnitudeResidual;

// Beyond these the solver has left the region where the model means anything
// for a MEMS part: the fit has diverged, whatever Ceres says.
constexpr double kMaxPlausibleScaleError = 0.5;
constexpr double kMaxPlausibleAngleRad = 0.5;

// Tuning constants of the robust losses for 95 % efficiency on Gaussian
// residuals of unit scale (Huber 1964; Holland & Welsch 1977).
constexpr double kHuberTuning = 1.345;
constexpr double kCauchyTuning = 2.385;

// Consistency factor of the median absolute deviation for Gaussian data.
constexpr double kMadToSigma = 1.4826;

// At most this share of the positions is excluded as outliers: beyond it the
// session itself is bad, and hiding that would mislead.
constexpr double kMaxOutlierShare = 0.2;

// A position this many times its own noise level off the fit is a bump, not
// part of a heavy-tailed scatter, when it also stands out from the scatter
// model by the outlier threshold.
constexpr double kOwnNoiseOutlier = 10.0;

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

// The middle of a position, where a drifting bias is taken to act on it.
double MidTime(const PositionObservation& p) { return 0.5 * (p.start_s + p.end_s); }

double Magnitude(const ErrorModel& model,
                 const PositionObservation& p,
                 double gravity_mps2) {
  return model.Correct(p.mean_mps2).norm() - gravity_mps2;
}

std::vector<double> MagnitudeResiduals(const ErrorModel& model,
                                       std::span<const PositionObservation> positions,
                                       double gravity_mps2) {
  std::vector<double> r;
  r.reserve(positions.size());
  for (const auto& p : positions) r.push_back(Magnitude(model, p, gravity_mps2));
  return r;
}

double Rms(const std::vector<double>& v, const std::vector<bool>& used) {
  double sum = 0.0;
  int n = 0;
  for (std::size_t k = 0; k < v.size(); ++k) {
    if (!used[k]) continue;
    sum += v[k] * v[k];
    ++n;
  }
  return n == 0 ? 0.0 : std::sqrt(sum / n);
}

double Median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

ceres::LossFunction* MakeLoss(RobustLoss loss, double scale) {
  switch (loss) {
    case RobustLoss::kNone:
      return nullptr;
    case RobustLoss::kHuber:
      return new ceres::HuberLoss(kHuberTuning * scale);
    case RobustLoss::kCauchy:
      return new ceres::CauchyLoss(kCauchyTuning * scale);
  }
  return nullptr;
}

std::vector<std::string> EstimatedNames(ModelKind model, bool drift = false) {
  std::vector<std::string> names;
  for (int i = 0; i < ParameterCount(model); ++i) names.emplace_back(kParameterNames[i]);
  if (drift) names.insert(names.end(), {"bias_drift_x", "bias_drift_y", "bias_drift_z"});
  return names;
}

ceres::Solver::Summary RunSolver(const SolveOptions& options, ceres::Problem& problem) {
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = options.max_iterations;
  solver.function_tolerance = 1e-14;
  solver.gradient_tolerance = 1e-14;
  solver.parameter_tolerance = 1e-14;
  solver.logging_type = ceres::SILENT;
  solver.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  return summary;
}

// The diagonal of the hat matrix J (JᵀJ)⁻¹ Jᵀ of a whitened Jacobian: how
// much each position pulls the fit towards itself (they sum to p).
std::vector<double> Leverages(const Eigen::MatrixXd& j) {
  const Eigen::MatrixXd hat = j * (j.transpose() * j).ldlt().solve(j.transpose());
  std::vector<double> h(static_cast<std::size_t>(j.rows()));
  for (Eigen::Index k = 0; k < j.rows(); ++k) h[static_cast<std::size_t>(k)] = hat(k, k);
  return h;
}

// The positions one fit uses, with the noise of each made safe to weigh by.
struct FitInput {
  std::vector<std::size_t> index;  // into the caller's positions
  std::vector<PositionObservation> positions;
  std::vector<Eigen::Vector3d> noise;
};

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
  // the second weighs each position at the first estimate. A robust loss, when asked
  // for, enters in the second pass, scaled to the whitened residuals of the
  // first so that it reacts to outliers and not to the overall noise level.
  //
  // Throws mpcal::Error when the positions leave parameters undetermined:
  // asked before solving, since a solver let loose on an undetermined
  // problem wanders off, and the Jacobian where it stops says nothing.
  void Run() {
    sigmas_ = Sigmas(blocks_.Model());
    Build(RobustLoss::kNone);
    const internal::Observability obs =
        internal::AnalyseObservability(Jacobian(), Names());
    if (!obs.undetermined.empty()) {
      const bool only_angles = std::all_of(
          obs.undetermined.begin(), obs.undetermined.end(), [](const std::string& name) {
            return name.starts_with("theta");
          });
      throw Error(fmt::format(
          "the {} static positions do not determine {}: their orientations do not span "
          "the sphere; record more positions, with each axis pointing up and down and "
          "at the cube's edges and corners (run 'mpcal detect' to see the coverage){}",
          input_.positions.size(),
          fmt::join(obs.undetermined, ", "),
          only_angles ? "; or calibrate bias and scale only with --model bias-scale-6 "
                        "(the six-position protocol)"
                      : ""));
    }
    summary_ = RunSolver(options_, *problem_);
    iterations_ = static_cast<int>(summary_.iterations.size()) - 1;

    // The second pass weighs each position by its noise at the first
    // estimate plus the scatter of the positions that noise leaves
    // unexplained (zero for white noise, dominant on many real recordings).
    sigmas_ = Sigmas(blocks_.Model());
    own_sigmas_ = sigmas_;
    std::vector<double> residuals;
    for (std::size_t k = 0; k < input_.positions.size(); ++k)
      residuals.push_back(Residual(k));
    scatter_variance_ =
        internal::PositionScatterVariance(residuals, sigmas_, Leverages(Jacobian()));
    for (double& sigma : sigmas_) sigma = std::sqrt(sigma * sigma + scatter_variance_);
    std::vector<double> whitened_abs;
    for (std::size_t k = 0; k < input_.positions.size(); ++k) {
      whitened_abs.push_back(std::abs(residuals[k] / sigmas_[k]));
    }
    loss_scale_ = std::max(kMadToSigma * Median(whitened_abs), 1e-12);
    Build(options_.robust);
    summary_ = RunSolver(options_, *problem_);
    iterations_ += static_cast<int>(summary_.iterations.size()) - 1;
  }

  // |a| − g of position k at the fit's estimate, or predicted by a refit
  // without it (one pass from this estimate, with the same weights).
  double Residual(std::size_t k) const {
    return Magnitude(blocks_.ModelAt(Dt(input_.positions[k])),
                     input_.positions[k],
                     options_.gravity_mps2);
  }
  double PredictedWithout(std::size_t k) const {
    FitInput rest;
    std::vector<double> sigmas;
    for (std::size_t j = 0; j < input_.positions.size(); ++j) {
      if (j == k) continue;
      rest.positions.push_back(input_.positions[j]);
      sigmas.push_back(sigmas_[j]);
    }
    Blocks blocks = blocks_;
    ceres::Problem problem;
    AddResiduals(rest.positions, sigmas, options_.robust, blocks, problem);
    RunSolver(options_, problem);
    return Magnitude(blocks.ModelAt(Dt(input_.positions[k])),
                     input_.positions[k],
                     options_.gravity_mps2);
  }

  // Whitened residuals × estimated parameters at the current estimate.
  Eigen::MatrixXd Jacobian() {
    ceres::Problem::EvaluateOptions eval;
    eval.parameter_blocks = Estimated();
    ceres::CRSMatrix crs;
    problem_->Evaluate(eval, nullptr, nullptr, nullptr, &crs);
    Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
    for (int row = 0; row < crs.num_rows; ++row) {
      for (int i = crs.rows[row]; i < crs.rows[row + 1]; ++i) {
        jacobian(row, crs.cols[i]) = crs.values[i];
      }
    }
    return jacobian;
  }

  // (JᵀJ)⁻¹ of the whitened problem, by Ceres; p × p in packed order.
  Eigen::MatrixXd UnscaledCovariance() {
    ceres::Covariance::Options cov_options;
    // Dense SVD: the problem is 9 × K, and SVD still answers near rank loss.
    cov_options.algorithm_type = ceres::DENSE_SVD;
    cov_options.null_space_rank = -1;
    ceres::Covariance covariance(cov_options);
    const std::vector<double*> estimated = Estimated();
    const std::vector<const double*> blocks(estimated.begin(), estimated.end());
    if (!covariance.Compute(blocks, problem_.get())) {
      throw Error(
          fmt::format("the covariance of the fit over {} static positions could "
                      "not be computed: they do not determine the parameters; "
                      "record more orientations",
                      input_.positions.size()));
    }
    const int p = static_cast<int>(Names().size());
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> c(p, p);
    covariance.GetCovarianceMatrix(blocks, c.data());
    return c;
  }

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

 private:
  std::vector<double> Sigmas(const ErrorModel& m) const {
    std::vector<double> s;
    for (std::size_t k = 0; k < input_.positions.size(); ++k) {
      ErrorModel at = m;
      at.bias_mps2 += Drift() * Dt(input_.positions[k]);
      s.push_back(internal::ResidualSigma(at,
                                          input_.positions[k].mean_mps2,
                                          input_.noise[k],
                                          input_.positions[k].samples));
    }
    return s;
  }

  void AddResiduals(const std::vector<PositionObservation>& positions,
                    const std::vector<double>& sigmas,
                    RobustLoss loss,
                    Blocks& blocks,
                    ceres::Problem& problem) const {
    for (std::size_t k = 0; k < positions.size(); ++k) {
      if (drifts()) {
        auto* cost = new ceres::
            AutoDiffCostFunction<internal::DriftMagnitudeResidual, 1, 3, 3, 3, 3>(
                new internal::DriftMagnitudeResidual(positions[k].mean_mps2,
                                                     options_.gravity_mps2,
                                                     sigmas[k],
                                                     Dt(positions[k])));
        problem.AddResidualBlock(cost,
                                 MakeLoss(loss, loss_scale_),
                                 blocks.bias,
                                 blocks.scale,
                                 blocks.angles,
                                 blocks.drift);
        continue;
      }
      auto* cost = new ceres::AutoDiffCostFunction<MagnitudeResidual, 1, 3, 3, 3>(
          new MagnitudeResidual(
              positions[k].mean_mps2, options_.gravity_mps2, sigmas[k]));
      problem.AddResidualBlock(
          cost, MakeLoss(loss, loss_scale_), blocks.bias, blocks.scale, blocks.angles);
    }
    if (options_.model == ModelKind::kBiasScale6) {
      problem.SetParameterBlockConstant(blocks.angles);
    }
  }

  void Build(RobustLoss loss) {
    problem_ = std::make_unique<ceres::Problem>();
    AddResiduals(input_.positions, sigmas_, loss, blocks_, *problem_);
  }

  // Ceres names parameter blocks by their address.
  std::vector<double*> Estimated() {
    std::vector<double*> blocks = {blocks_.bias, blocks_.scale};
    if (options_.model == ModelKind::kShinElSheimy9) blocks.push_back(blocks_.angles);
    if (drifts()) blocks.push_back(blocks_.drift);
    return blocks;
  }

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

FitInput Select(std::span<const PositionObservation> positions,
                const std::vector<Eigen::Vector3d>& noise,
                const std::vector<bool>& used) {
  FitInput in;
  for (std::size_t k = 0; k < positions.size(); ++k) {
    if (!used[k]) continue;
    in.index.push_back(k);
    in.positions.push_back(positions[k]);
    in.noise.push_back(noise[k]);
  }
  return in;
}

// Each used position's residual in units of its standard deviation under
// the scatter model (σ_k² + τ², `total`) and under its sensor noise alone
// (σ_k², `own`), corrected for the pull it has on the fit (leverage h:
// var(e_k) = σ² (1 − h_k)).
struct StandardisedResiduals {
  std::vector<double> total;
  std::vector<double> own;
};

StandardisedResiduals Standardise(Fit& fit, std::size_t count) {
  const std::vector<double> leverage = Leverages(fit.Jacobian());
  StandardisedResiduals z;
  for (std::size_t k = 0; k < count; ++k) {
    const double root = std::sqrt(1.0 - std::clamp(leverage[k], 0.0, 0.999));
    z.total.push_back(fit.Residual(k) / (fit.sigmas()[k] * root));
    z.own.push_back(fit.Residual(k) / (fit.own_sigmas()[k] * root));
  }
  return z;
}

std::vector<double> Standardised(Fit& fit, std::size_t count) {
  return Standardise(fit, count).total;
}

// The split-half check, and every 1σ widened by its rule when two halves
// disagree beyond chance (METHOD.md §9).
void WidenBySplitHalves(std::span<const PositionObservation> positions,
                        const SolveOptions& options,
                        SolveResult& result) {
  result.split_half = internal::CheckSplitHalves(positions, result.used, options);
  const double widening = result.split_half->widening;
  if (!(widening > 1.0)) return;
  result.covariance *= widening * widening;
  result.std = FromVector(result.covariance.diagonal().cwiseMax(0.0).cwiseSqrt());
  if (result.bias_drift) result.bias_drift->std_mps2_per_s *= widening;
  for (const SplitHalfComparison& c : result.split_half->comparisons) {
    if (!c.determined || !c.disagree) continue;
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

// Fewer redundant positions than this, with the drift's three parameters
// fitted, leave the F test too little to judge by.
constexpr int kMinDriftRedundancy = 3;

// The bias drift model fitted to the same positions and chosen over the
// constant bias when it is significant: an F test of the drop in χ² for its
// three parameters, both χ² with the constant fit's weights (its noise and
// scatter), F(3, K − p − 3), at options.bias_drift_significance. F rather
// than a χ² test, since the weights' overall level is itself uncertain.
void ChooseBiasDrift(const FitInput& in,
                     const SolveOptions& options,
                     double reference_s,
                     std::unique_ptr<Fit>& fit,
                     SolveResult& result) {
  const int redundancy =
      static_cast<int>(in.positions.size()) - ParameterCount(options.model) - 3;
  if (options.force_bias_drift && redundancy < 1) {
    throw Error(fmt::format("{} positions are too few for the model with a drifting bias",
                            in.positions.size()));
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
      throw Error("the fit with a drifting bias did not converge");
    return;
  }
  double chi2_constant = 0.0;
  double chi2_drift = 0.0;
  for (std::size_t j = 0; j < in.positions.size(); ++j) {
    chi2_constant += std::pow(fit->Residual(j) / fit->sigmas()[j], 2);
    chi2_drift += std::pow(drifting->Residual(j) / fit->sigmas()[j], 2);
  }
  if (!(chi2_drift > 0.0)) return;
  const double f = (chi2_constant - chi2_drift) / 3.0 / (chi2_drift / redundancy);
  const double p_value = internal::FUpperTail(f, 3, redundancy);
  result.bias_drift_p_value = p_value;
  if (!(p_value < options.bias_drift_significance) && !options.force_bias_drift) return;
  BiasDrift drift;
  drift.mps2_per_s = drifting->Drift();
  drift.reference_time_s = reference_s;
  drift.p_value = p_value;
  result.bias_drift = drift;
  result.iterations += drifting->iterations();
  fit = std::move(drifting);
}

}  // namespace

std::string_view ToString(RobustLoss loss) {
  switch (loss) {
    case RobustLoss::kNone:
      return "none";
    case RobustLoss::kHuber:
      return "huber";
    case RobustLoss::kCauchy:
      return "cauchy";
  }
  return "unknown";
}

std::optional<RobustLoss> ParseRobustLoss(std::string_view name) {
  for (RobustLoss l : {RobustLoss::kNone, RobustLoss::kHuber, RobustLoss::kCauchy}) {
    if (name == ToString(l)) return l;
  }
  return std::nullopt;
}

std::string_view ToString(SolveStatus status) {
  return status == SolveStatus::kConverged ? "converged" : "no convergence";
}

std::string SolveOptions::Validate() const {
  if (!IsPlausibleGravity(gravity_mps2)) {
    return fmt::format("gravity_mps2 = {} is not a gravity on Earth ({}..{} m/s2)",
                       gravity_mps2,
                       kMinGravityMps2,
                       kMaxGravityMps2);
  }
  if (max_iterations < 1) return "max_iterations must be at least 1";
  if (!(outlier_threshold > 1.0)) return "outlier_threshold must be above 1";
  if (!(split_half_significance > 0.0 && split_half_significance < 1.0)) {
    return "split_half_significance must be in (0, 1)";
  }
  return "";
}

std::string SolveResult::BriefReport() const {
  return fmt::format(
      "{} after {} iterations; |a|-g RMS {:.3g} -> {:.3g} m/s2; variance factor {:.3g}",
      ToString(status),
      iterations,
      residual_rms_before_mps2,
      residual_rms_after_mps2,
      variance_factor);
}

SolveResult Solve(std::span<const PositionObservation> positions,
                  const SolveOptions& options) {
  if (const std::string problem = options.Validate(); !problem.empty()) {
    throw Error("solve options: " + problem);
  }
  const int p = ParameterCount(options.model);
  const std::size_t count = positions.size();
  if (static_cast<int>(count) < p) {
    throw Error(fmt::format(
        "{} static positions are too few for the {} model ({} parameters): it needs at "
        "least {}, and more than 18 spanning the sphere for reliable results{}",
        count,
        ToString(options.model),
        p,
        p,
        options.model == ModelKind::kShinElSheimy9 && count >= 6
            ? "; with the six axis-up/axis-down positions use --model bias-scale-6"
            : ""));
  }
  for (std::size_t k = 0; k < count; ++k) {
    if (!positions[k].mean_mps2.allFinite() ||
        !positions[k].sample_std_mps2.allFinite()) {
      throw Error(fmt::format("static position {} (at {:.2f} s) has a non-finite mean",
                              k + 1,
                              positions[k].start_s));
    }
  }

  SolveResult result;
  result.used.assign(count, true);
  result.initial = InitialiseSixPosition(positions, options.gravity_mps2);
  ErrorModel nominal;
  nominal.bias_mps2 = options.nominal_offset_mps2;
  result.residual_before_mps2 =
      MagnitudeResiduals(nominal, positions, options.gravity_mps2);
  const std::vector<Eigen::Vector3d> noise = internal::UsableNoise(positions);

  auto fit = std::make_unique<Fit>(
      Select(positions, noise, result.used), result.initial, options);
  fit->Run();
  result.iterations = fit->iterations();

  // Outliers, worst first, one at a time: a bumped position pulls the fit
  // towards itself and can hide a second one until it is gone.
  const int max_excluded = std::min(static_cast<int>(kMaxOutlierShare * count),
                                    static_cast<int>(count) - (p + 1));
  int excluded = 0;
  while (options.exclude_outliers && excluded < max_excluded) {
    const FitInput in = Select(positions, noise, result.used);
    // Against the scatter model σ_k² + τ², beyond a robust scale of the
    // rest (the MAD of the standardised residuals, never below 1); and a
    // position more than kOwnNoiseOutlier times its own noise level that
    // stands out from the scatter model goes whatever that robust scale
    // (residuals heavier-tailed than the scatter model must not shelter it).
    const StandardisedResiduals z = Standardise(*fit, in.positions.size());
    if (z.total.empty()) break;
    std::vector<double> abs_z;
    for (double v : z.total) abs_z.push_back(std::abs(v));
    const double scale = std::max(1.0, kMadToSigma * Median(abs_z));
    std::size_t worst = 0;
    double worst_excess = 0.0;
    for (std::size_t j = 0; j < abs_z.size(); ++j) {
      const bool far_beyond_own_noise = std::abs(z.own[j]) > kOwnNoiseOutlier;
      const double excess =
          abs_z[j] / (options.outlier_threshold * (far_beyond_own_noise ? 1.0 : scale));
      if (excess > worst_excess) {
        worst = j;
        worst_excess = excess;
      }
    }
    if (worst_excess <= 1.0) break;

    const std::size_t k = in.index[worst];
    result.used[k] = false;
    auto refit = std::make_unique<Fit>(
        Select(positions, noise, result.used), fit->Estimate(), options);
    try {
      refit->Run();
    } catch (const Error&) {
      // The position is needed to determine the parameters: keep it.
      result.used[k] = true;
      result.warnings.push_back(fmt::format(
          "position {} ({:.1f}-{:.1f} s) fits badly ({:.1f} times its noise) but cannot "
          "be excluded: no other position determines the same parameters",
          k + 1,
          positions[k].start_s,
          positions[k].end_s,
          std::abs(z.own[worst])));
      break;
    }
    result.warnings.push_back(
        fmt::format("position {} ({:.1f}-{:.1f} s) excluded as an outlier: its residual "
                    "is {:.1f} times "
                    "its noise level (was the sensor bumped or not fully still?)",
                    k + 1,
                    positions[k].start_s,
                    positions[k].end_s,
                    std::abs(z.own[worst])));
    fit = std::move(refit);
    result.iterations += fit->iterations();
    ++excluded;
  }

  // A drifting bias is reported at the middle of the used positions' times:
  // there it is nearly uncorrelated with the drift rate, so it is the bias a
  // constant-bias fit finds, and a drift chosen by chance barely moves it.
  double mean_time_s = 0.0;
  int used_count = 0;
  for (std::size_t k = 0; k < count; ++k) {
    if (!result.used[k]) continue;
    mean_time_s += MidTime(positions[k]);
    ++used_count;
  }
  const double reference_s =
      options.bias_reference_time_s.value_or(mean_time_s / std::max(used_count, 1));
  if (options.consider_bias_drift || options.force_bias_drift) {
    ChooseBiasDrift(
        Select(positions, noise, result.used), options, reference_s, fit, result);
  }

  result.estimate = fit->Estimate();
  result.position_scatter_mps2 = std::sqrt(fit->scatter_variance());
  result.final_cost = fit->summary().final_cost;
  result.residual_after_mps2 =
      MagnitudeResiduals(result.estimate, positions, options.gravity_mps2);
  if (fit->drifts()) {
    for (std::size_t k = 0; k < count; ++k) {
      ErrorModel at = result.estimate;
      at.bias_mps2 += fit->Drift() * (MidTime(positions[k]) - reference_s);
      result.residual_after_mps2[k] = Magnitude(at, positions[k], options.gravity_mps2);
    }
  }
  result.residual_rms_before_mps2 = Rms(result.residual_before_mps2, result.used);
  result.residual_rms_after_mps2 = Rms(result.residual_after_mps2, result.used);

  const bool plausible =
      result.estimate.scale_factor_error.cwiseAbs().maxCoeff() <
          kMaxPlausibleScaleError &&
      std::max({std::abs(result.estimate.theta_yz_rad),
                std::abs(result.estimate.theta_zx_rad),
                std::abs(result.estimate.theta_zy_rad)}) < kMaxPlausibleAngleRad &&
      ToVector(result.estimate).allFinite();
  if (fit->summary().termination_type != ceres::CONVERGENCE || !plausible) {
    result.status = SolveStatus::kNoConvergence;
    result.message = plausible ? fit->summary().message
                               : "the estimate left the plausible range (|s| < 0.5, "
                                 "|angle| < 0.5 rad): the solver diverged";
    return result;
  }
  result.status = SolveStatus::kConverged;
  result.message = fit->summary().message;

  for (const std::string& name :
       internal::AnalyseObservability(fit->Jacobian(), fit->Names()).poorly_determined) {
    result.warnings.push_back(fmt::format(
        "{} is poorly determined by these positions (strongly correlated with other "
        "parameters): add positions that fill the gaps 'mpcal detect' shows",
        name));
  }

  const int fitted = p + (fit->drifts() ? 3 : 0);
  const int dof =
      static_cast<int>(std::count(result.used.begin(), result.used.end(), true)) - fitted;
  if (dof == 0) {
    result.warnings.push_back(fmt::format(
        "{} positions for {} parameters leave no redundancy: the residuals are zero by "
        "construction and cannot reveal a bad position; the 1σ come from the sensor "
        "noise "
        "alone. Record a few more positions (edges, corners) to check the fit",
        count,
        p));
  }

  // Cross-validation: each used position predicted by the fit without it;
  // an excluded one is already predicted by the final fit, which lacks it.
  const FitInput in = Select(positions, noise, result.used);
  const std::vector<double> z = Standardised(*fit, in.positions.size());
  result.standardised_residual.assign(count, 0.0);
  for (std::size_t j = 0; j < in.index.size(); ++j)
    result.standardised_residual[in.index[j]] = z[j];
  // A position that alone determines some parameter (the only one with +x
  // up, say) cannot be predicted without it: NaN, not a made-up number.
  if (options.cross_validate && dof > 0) {
    result.cross_validation_residual_mps2 = result.residual_after_mps2;
    const Eigen::MatrixXd jacobian = fit->Jacobian();
    std::vector<bool> predicted = result.used;
    for (std::size_t j = 0; j < in.index.size(); ++j) {
      Eigen::MatrixXd without(jacobian.rows() - 1, jacobian.cols());
      const auto row = static_cast<Eigen::Index>(j);
      without << jacobian.topRows(row), jacobian.bottomRows(jacobian.rows() - row - 1);
      const bool determined =
          internal::AnalyseObservability(without, fit->Names()).undetermined.empty();
      result.cross_validation_residual_mps2[in.index[j]] =
          determined ? fit->PredictedWithout(j)
                     : std::numeric_limits<double>::quiet_NaN();
      predicted[in.index[j]] = determined;
    }
    result.cross_validation_rms_mps2 =
        Rms(result.cross_validation_residual_mps2, predicted);
  }

  // Covariance: (JᵀJ)⁻¹ of the whitened problem, scaled up by the
  // a-posteriori variance of unit weight (METHOD.md §3), never shrunk below
  // the a-priori level. The weights already carry the noise measured from
  // thousands of samples per position; K − p residuals (5 for 14 positions)
  // can reveal extra error (hand tremor, non-white noise, misfit) but would
  // often understate the noise by half if trusted the other way. Nor are a
  // few residuals trusted alone the other way: the a-priori level counts as
  // kPriorDof residuals of evidence (the update of a scaled inverse-χ² prior
  // centred on 1), so that 5 residuals at 3.7 times their expected square by
  // chance (1 session in 2000) raise the 1σ by 1.4, not 1.9, while 30 at
  // that level, a real misfit, raise it by 1.7.
  double chi2 = 0.0;
  for (std::size_t j = 0; j < in.index.size(); ++j) {
    chi2 += std::pow(fit->Residual(j) / fit->sigmas()[j], 2);
  }
  // With no redundancy the residuals say nothing: keep the a-priori level.
  result.variance_factor = dof > 0 ? chi2 / dof : 1.0;
  constexpr double kPriorDof = 10.0;
  const double covariance_scale = (kPriorDof + chi2) / (kPriorDof + dof);
  const Eigen::MatrixXd covariance =
      std::max(1.0, covariance_scale) * fit->UnscaledCovariance();
  result.covariance.topLeftCorner(p, p) = covariance.topLeftCorner(p, p);
  result.std = FromVector(result.covariance.diagonal().cwiseMax(0.0).cwiseSqrt());
  if (fit->drifts()) {
    result.bias_drift->std_mps2_per_s =
        covariance.bottomRightCorner(3, 3).diagonal().cwiseMax(0.0).cwiseSqrt();
  }
  if (options.split_half_check) {
    // Halves with a drifting bias report it at the same time as the whole.
    SolveOptions split_options = options;
    split_options.bias_reference_time_s = reference_s;
    split_options.force_bias_drift = result.bias_drift.has_value();
    WidenBySplitHalves(positions, split_options, result);
  }
  return result;
}

}  // namespace mpcal
