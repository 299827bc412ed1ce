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
};

double Magnitude(const ErrorModel& model, const PositionObservation& p, double gravity_mps2) {
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

std::vector<std::string> EstimatedNames(ModelKind model) {
  std::vector<std::string> names;
  for (int i = 0; i < ParameterCount(model); ++i) names.emplace_back(kParameterNames[i]);
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
  Fit(const FitInput& input, const ErrorModel& start, const SolveOptions& options)
      : input_(input), options_(options), blocks_(start) {}

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
        internal::AnalyseObservability(Jacobian(), EstimatedNames(options_.model));
    if (!obs.undetermined.empty()) {
      const bool only_angles =
          std::all_of(obs.undetermined.begin(), obs.undetermined.end(),
                      [](const std::string& name) { return name.starts_with("theta"); });
      throw Error(fmt::format(
          "the {} static positions do not determine {}: their orientations do not span "
          "the sphere; record more positions, with each axis pointing up and down and "
          "at the cube's edges and corners (run 'mpcal detect' to see the coverage){}",
          input_.positions.size(), fmt::join(obs.undetermined, ", "),
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
    for (std::size_t k = 0; k < input_.positions.size(); ++k) residuals.push_back(Residual(k));
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
    return Magnitude(blocks_.Model(), input_.positions[k], options_.gravity_mps2);
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
    return Magnitude(blocks.Model(), input_.positions[k], options_.gravity_mps2);
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
      throw Error(fmt::format("the covariance of the fit over {} static positions could "
                              "not be computed: they do not determine the parameters; "
                              "record more orientations",
                              input_.positions.size()));
    }
    const int p = ParameterCount(options_.model);
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> c(p, p);
    covariance.GetCovarianceMatrix(blocks, c.data());
    return c;
  }

  ErrorModel Estimate() const { return blocks_.Model(); }
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
      s.push_back(internal::ResidualSigma(m, input_.positions[k].mean_mps2, input_.noise[k],
                                          input_.positions[k].samples));
    }
    return s;
  }

  void AddResiduals(const std::vector<PositionObservation>& positions,
                    const std::vector<double>& sigmas, RobustLoss loss, Blocks& blocks,
                    ceres::Problem& problem) const {
    for (std::size_t k = 0; k < positions.size(); ++k) {
      auto* cost = new ceres::AutoDiffCostFunction<MagnitudeResidual, 1, 3, 3, 3>(
          new MagnitudeResidual(positions[k].mean_mps2, options_.gravity_mps2, sigmas[k]));
      problem.AddResidualBlock(cost, MakeLoss(loss, loss_scale_), blocks.bias, blocks.scale,
                               blocks.angles);
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
    return blocks;
  }

  FitInput input_;
  SolveOptions options_;
  Blocks blocks_;
  std::vector<double> sigmas_;
  std::vector<double> own_sigmas_;
  double loss_scale_ = 1.0;
  double scatter_variance_ = 0.0;
  std::unique_ptr<ceres::Problem> problem_;
  ceres::Solver::Summary summary_;
  int iterations_ = 0;
};

FitInput Select(std::span<const PositionObservation> positions,
                const std::vector<Eigen::Vector3d>& noise, const std::vector<bool>& used) {
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
                       gravity_mps2, kMinGravityMps2, kMaxGravityMps2);
  }
  if (max_iterations < 1) return "max_iterations must be at least 1";
  if (!(outlier_threshold > 1.0)) return "outlier_threshold must be above 1";
  return "";
}

std::string SolveResult::BriefReport() const {
  return fmt::format(
      "{} after {} iterations; |a|-g RMS {:.3g} -> {:.3g} m/s2; variance factor {:.3g}",
      ToString(status), iterations, residual_rms_before_mps2, residual_rms_after_mps2,
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
        count, ToString(options.model), p, p,
        options.model == ModelKind::kShinElSheimy9 && count >= 6
            ? "; with the six axis-up/axis-down positions use --model bias-scale-6"
            : ""));
  }
  for (std::size_t k = 0; k < count; ++k) {
    if (!positions[k].mean_mps2.allFinite() || !positions[k].sample_std_mps2.allFinite()) {
      throw Error(fmt::format("static position {} (at {:.2f} s) has a non-finite mean", k + 1,
                              positions[k].start_s));
    }
  }

  SolveResult result;
  result.used.assign(count, true);
  result.initial = InitialiseSixPosition(positions, options.gravity_mps2);
  ErrorModel nominal;
  nominal.bias_mps2 = options.nominal_offset_mps2;
  result.residual_before_mps2 = MagnitudeResiduals(nominal, positions, options.gravity_mps2);
  const std::vector<Eigen::Vector3d> noise = internal::UsableNoise(positions);

  auto fit = std::make_unique<Fit>(Select(positions, noise, result.used), result.initial, options);
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
    auto refit = std::make_unique<Fit>(Select(positions, noise, result.used),
                                       fit->Estimate(), options);
    try {
      refit->Run();
    } catch (const Error&) {
      // The position is needed to determine the parameters: keep it.
      result.used[k] = true;
      result.warnings.push_back(fmt::format(
          "position {} ({:.1f}-{:.1f} s) fits badly ({:.1f} times its noise) but cannot "
          "be excluded: no other position determines the same parameters",
          k + 1, positions[k].start_s, positions[k].end_s, std::abs(z.own[worst])));
      break;
    }
    result.warnings.push_back(fmt::format(
        "position {} ({:.1f}-{:.1f} s) excluded as an outlier: its residual is {:.1f} times "
        "its noise level (was the sensor bumped or not fully still?)",
        k + 1, positions[k].start_s, positions[k].end_s, std::abs(z.own[worst])));
    fit = std::move(refit);
    result.iterations += fit->iterations();
    ++excluded;
  }

  result.estimate = fit->Estimate();
  result.position_scatter_mps2 = std::sqrt(fit->scatter_variance());
  result.final_cost = fit->summary().final_cost;
  result.residual_after_mps2 = MagnitudeResiduals(result.estimate, positions, options.gravity_mps2);
  result.residual_rms_before_mps2 = Rms(result.residual_before_mps2, result.used);
  result.residual_rms_after_mps2 = Rms(result.residual_after_mps2, result.used);

  const bool plausible =
      result.estimate.scale_factor_error.cwiseAbs().maxCoeff() < kMaxPlausibleScaleError &&
      std::max({std::abs(result.estimate.theta_yz_rad), std::abs(result.estimate.theta_zx_rad),
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
       internal::AnalyseObservability(fit->Jacobian(), EstimatedNames(options.model))
           .poorly_determined) {
    result.warnings.push_back(fmt::format(
        "{} is poorly determined by these positions (strongly correlated with other "
        "parameters): add positions that fill the gaps 'mpcal detect' shows",
        name));
  }

  const int dof = static_cast<int>(std::count(result.used.begin(), result.used.end(), true)) - p;
  if (dof == 0) {
    result.warnings.push_back(fmt::format(
        "{} positions for {} parameters leave no redundancy: the residuals are zero by "
        "construction and cannot reveal a bad position; the 1σ come from the sensor noise "
        "alone. Record a few more positions (edges, corners) to check the fit",
        count, p));
  }

  // Cross-validation: each used position predicted by the fit without it;
  // an excluded one is already predicted by the final fit, which lacks it.
  const FitInput in = Select(positions, noise, result.used);
  const std::vector<double> z = Standardised(*fit, in.positions.size());
  result.standardised_residual.assign(count, 0.0);
  for (std::size_t j = 0; j < in.index.size(); ++j) result.standardised_residual[in.index[j]] = z[j];
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
          internal::AnalyseObservability(without, EstimatedNames(options.model)).undetermined.empty();
      result.cross_validation_residual_mps2[in.index[j]] =
          determined ? fit->PredictedWithout(j) : std::numeric_limits<double>::quiet_NaN();
      predicted[in.index[j]] = determined;
    }
    result.cross_validation_rms_mps2 = Rms(result.cross_validation_residual_mps2, predicted);
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
  result.covariance.topLeftCorner(p, p) =
      std::max(1.0, covariance_scale) * fit->UnscaledCovariance();
  result.std = FromVector(result.covariance.diagonal().cwiseMax(0.0).cwiseSqrt());
  return result;
}

}  // namespace mpcal
