// The multi-position least squares (Souza & Machado 2016, eq 12) with Ceres.
#include "mpcal/solve.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <ceres/ceres.h>
#include <fmt/format.h>

#include "mpcal/error.h"
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

std::vector<double> MagnitudeResiduals(const ErrorModel& model,
                                       std::span<const PositionObservation> positions,
                                       double gravity_mps2) {
  std::vector<double> r;
  r.reserve(positions.size());
  for (const auto& p : positions) r.push_back(model.Correct(p.mean_mps2).norm() - gravity_mps2);
  return r;
}

double Rms(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x * x;
  return v.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(v.size()));
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

// The weighted least-squares problem over `blocks`.
std::unique_ptr<ceres::Problem> BuildProblem(std::span<const PositionObservation> positions,
                                             const std::vector<double>& sigmas,
                                             const SolveOptions& options, double loss_scale,
                                             Blocks& blocks) {
  auto problem = std::make_unique<ceres::Problem>();
  for (std::size_t k = 0; k < positions.size(); ++k) {
    auto* cost = new ceres::AutoDiffCostFunction<MagnitudeResidual, 1, 3, 3, 3>(
        new MagnitudeResidual(positions[k].mean_mps2, options.gravity_mps2, sigmas[k]));
    problem->AddResidualBlock(cost, MakeLoss(options.robust, loss_scale), blocks.bias,
                              blocks.scale, blocks.angles);
  }
  if (options.model == ModelKind::kBiasScale6) problem->SetParameterBlockConstant(blocks.angles);
  return problem;
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

// The estimated parameter blocks, in packed order.
std::vector<double*> EstimatedBlocks(ModelKind model, Blocks& blocks) {
  std::vector<double*> b = {blocks.bias, blocks.scale};
  if (model == ModelKind::kShinElSheimy9) b.push_back(blocks.angles);
  return b;
}

// Whitened residuals × estimated parameters, at the blocks' current values.
Eigen::MatrixXd Jacobian(ceres::Problem& problem, const std::vector<double*>& estimated) {
  ceres::Problem::EvaluateOptions eval;
  eval.parameter_blocks = estimated;
  ceres::CRSMatrix crs;
  problem.Evaluate(eval, nullptr, nullptr, nullptr, &crs);
  Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int row = 0; row < crs.num_rows; ++row) {
    for (int i = crs.rows[row]; i < crs.rows[row + 1]; ++i) {
      jacobian(row, crs.cols[i]) = crs.values[i];
    }
  }
  return jacobian;
}

std::vector<std::string> EstimatedNames(ModelKind model) {
  std::vector<std::string> names;
  for (int i = 0; i < ParameterCount(model); ++i) names.emplace_back(kParameterNames[i]);
  return names;
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
  if (!(gravity_mps2 > 9.7 && gravity_mps2 < 9.9)) {
    return fmt::format("gravity_mps2 = {} is not a gravity on Earth (9.78..9.84 m/s2)",
                       gravity_mps2);
  }
  if (max_iterations < 1) return "max_iterations must be at least 1";
  return "";
}

std::string SolveResult::BriefReport() const {
  return fmt::format("{} after {} iterations; |a|-g RMS {:.3g} -> {:.3g} m/s2; variance factor {:.3g}",
                     ToString(status), iterations, residual_rms_before_mps2,
                     residual_rms_after_mps2, variance_factor);
}

SolveResult Solve(std::span<const PositionObservation> positions,
                  const SolveOptions& options) {
  if (const std::string problem = options.Validate(); !problem.empty()) {
    throw Error("solve options: " + problem);
  }
  const int p = ParameterCount(options.model);
  if (static_cast<int>(positions.size()) < p + 1) {
    throw Error(fmt::format(
        "{} static positions are too few for the {} model ({} parameters): it needs at "
        "least {}, and more than 18 spanning the sphere for reliable results{}",
        positions.size(), ToString(options.model), p, p + 1,
        options.model == ModelKind::kShinElSheimy9 && positions.size() >= 6
            ? "; with the six axis-up/axis-down positions use --model bias-scale-6"
            : ""));
  }
  for (std::size_t k = 0; k < positions.size(); ++k) {
    if (!positions[k].mean_mps2.allFinite() || !positions[k].sample_std_mps2.allFinite()) {
      throw Error(fmt::format("static position {} (at {:.2f} s) has a non-finite mean", k + 1,
                              positions[k].start_s));
    }
  }

  SolveResult result;
  result.initial = InitialiseSixPosition(positions, options.gravity_mps2);
  result.residual_before_mps2 = MagnitudeResiduals(ErrorModel{}, positions, options.gravity_mps2);
  result.residual_rms_before_mps2 = Rms(result.residual_before_mps2);

  const std::vector<Eigen::Vector3d> noise = internal::UsableNoise(positions);
  auto sigmas_at = [&](const ErrorModel& m) {
    std::vector<double> s;
    s.reserve(positions.size());
    for (std::size_t k = 0; k < positions.size(); ++k) {
      s.push_back(internal::ResidualSigma(m, positions[k].mean_mps2, noise[k],
                                          positions[k].samples));
    }
    return s;
  };

  Blocks blocks(result.initial);
  const std::vector<double*> estimated = EstimatedBlocks(options.model, blocks);
  std::vector<double> sigmas = sigmas_at(result.initial);
  SolveOptions first_options = options;
  first_options.robust = RobustLoss::kNone;
  std::unique_ptr<ceres::Problem> problem =
      BuildProblem(positions, sigmas, first_options, 1.0, blocks);

  // Which parameters can these positions determine? Asked before solving: a
  // solver let loose on an undetermined problem wanders off, and the
  // Jacobian where it stops says nothing about the design.
  const internal::Observability obs =
      internal::AnalyseObservability(Jacobian(*problem, estimated), EstimatedNames(options.model));
  if (!obs.undetermined.empty()) {
    throw Error(fmt::format(
        "the {} static positions do not determine {}: their orientations do not span "
        "the sphere; record more positions, with each axis pointing up and down and "
        "at the cube's edges and corners (run 'mpcal detect' to see the coverage)",
        positions.size(), fmt::join(obs.undetermined, ", ")));
  }

  // Two passes: the weights depend (weakly) on the parameters, so the second
  // weighs each position at the first estimate. A robust loss, when asked
  // for, enters in the second pass, scaled to the whitened residuals of the
  // first so that it reacts to outliers and not to the overall noise level.
  ceres::Solver::Summary summary = RunSolver(options, *problem);
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;
  sigmas = sigmas_at(blocks.Model());
  std::vector<double> whitened_abs;
  const std::vector<double> first = MagnitudeResiduals(blocks.Model(), positions, options.gravity_mps2);
  for (std::size_t k = 0; k < first.size(); ++k) whitened_abs.push_back(std::abs(first[k] / sigmas[k]));
  const double loss_scale = std::max(kMadToSigma * Median(whitened_abs), 1e-12);
  problem = BuildProblem(positions, sigmas, options, loss_scale, blocks);
  summary = RunSolver(options, *problem);
  result.iterations += static_cast<int>(summary.iterations.size()) - 1;

  result.estimate = blocks.Model();
  result.final_cost = summary.final_cost;
  result.residual_after_mps2 = MagnitudeResiduals(result.estimate, positions, options.gravity_mps2);
  result.residual_rms_after_mps2 = Rms(result.residual_after_mps2);

  const bool plausible =
      result.estimate.scale_factor_error.cwiseAbs().maxCoeff() < kMaxPlausibleScaleError &&
      std::max({std::abs(result.estimate.theta_yz_rad), std::abs(result.estimate.theta_zx_rad),
                std::abs(result.estimate.theta_zy_rad)}) < kMaxPlausibleAngleRad &&
      ToVector(result.estimate).allFinite();
  if (summary.termination_type == ceres::CONVERGENCE && plausible) {
    result.status = SolveStatus::kConverged;
    result.message = summary.message;
  } else {
    result.status = SolveStatus::kNoConvergence;
    result.message = plausible ? summary.message
                               : "the estimate left the plausible range (|s| < 0.5, "
                                 "|angle| < 0.5 rad): the solver diverged";
    return result;
  }

  for (const std::string& name :
       internal::AnalyseObservability(Jacobian(*problem, estimated),
                                      EstimatedNames(options.model))
           .poorly_determined) {
    result.warnings.push_back(fmt::format(
        "{} is poorly determined by these positions (strongly correlated with other "
        "parameters): add positions that fill the gaps 'mpcal detect' shows",
        name));
  }

  // Covariance: (JᵀJ)⁻¹ of the whitened problem, scaled by the a-posteriori
  // variance of unit weight (METHOD.md §3).
  double chi2 = 0.0;
  for (std::size_t k = 0; k < positions.size(); ++k) {
    chi2 += std::pow(result.residual_after_mps2[k] / sigmas[k], 2);
  }
  const int dof = static_cast<int>(positions.size()) - p;
  result.variance_factor = chi2 / dof;
  ceres::Covariance::Options cov_options;
  // Dense SVD: the problem is 9 × K, and SVD still answers near rank loss.
  cov_options.algorithm_type = ceres::DENSE_SVD;
  cov_options.null_space_rank = -1;
  ceres::Covariance covariance(cov_options);
  const std::vector<const double*> estimated_const(estimated.begin(), estimated.end());
  if (!covariance.Compute(estimated_const, problem.get())) {
    throw Error(fmt::format("the covariance of the {} static positions' fit could not be "
                            "computed: the positions do not determine the parameters; "
                            "record more orientations",
                            positions.size()));
  }
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> unscaled(p, p);
  covariance.GetCovarianceMatrix(estimated_const, unscaled.data());
  result.covariance.topLeftCorner(p, p) = result.variance_factor * unscaled;
  Eigen::Matrix<double, 9, 1> sd = result.covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  result.std = FromVector(sd);
  return result;
}

}  // namespace mpcal
