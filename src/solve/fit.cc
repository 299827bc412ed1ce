#include "fit.h"

#include <cmath>
#include <numeric>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "mpcal/error.h"
#include "observability.h"
#include "residual.h"
#include "weights.h"

namespace mpcal::internal {
namespace {

// Tuning constants of the robust losses for 95 % efficiency on Gaussian
// residuals of unit scale (Huber 1964; Holland & Welsch 1977).
constexpr double kHuberTuning = 1.345;
constexpr double kCauchyTuning = 2.385;

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

// Where the positions' coverage of the sphere shows what to add.
Advice DetectAdvice() {
  Advice advice;
  advice.stage = Stage::kDetect;
  return advice;
}

}  // namespace

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

std::vector<double> Leverages(const Eigen::MatrixXd& j) {
  const Eigen::MatrixXd hat = j * (j.transpose() * j).ldlt().solve(j.transpose());
  std::vector<double> h(static_cast<std::size_t>(j.rows()));
  for (Eigen::Index k = 0; k < j.rows(); ++k) h[static_cast<std::size_t>(k)] = hat(k, k);
  return h;
}

std::vector<std::string> EstimatedNames(ModelKind model, bool drift) {
  std::vector<std::string> names;
  names.reserve(kNumModelParameters + 3);
  for (int i = 0; i < ParameterCount(model); ++i) names.emplace_back(kParameterNames[i]);
  if (drift) names.insert(names.end(), {"bias_drift_x", "bias_drift_y", "bias_drift_z"});
  return names;
}

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

void Fit::Run() {
  sigmas_ = Sigmas(blocks_.Model());
  Build(RobustLoss::kNone);
  ThrowIfUndetermined();
  summary_ = RunSolver(options_, *problem_);
  iterations_ = static_cast<int>(summary_.iterations.size()) - 1;
  WeighByScatter();
  Build(options_.robust);
  summary_ = RunSolver(options_, *problem_);
  iterations_ += static_cast<int>(summary_.iterations.size()) - 1;
}

void Fit::ThrowIfUndetermined() {
  const Observability obs = AnalyseObservability(Jacobian(), Names());
  if (obs.undetermined.empty()) return;
  const bool only_angles = std::all_of(
      obs.undetermined.begin(), obs.undetermined.end(), [](const std::string& name) {
        return name.starts_with("theta");
      });
  // Only the angles missing: the six-position protocol still calibrates
  // bias and scale. Otherwise the coverage of the sphere shows what to add.
  Advice advice;
  if (only_angles) {
    advice.settings.push_back(
        {Option::kModel, std::string(ToString(ModelKind::kBiasScale6))});
  } else {
    advice = DetectAdvice();
  }
  throw Error(ErrorKind::kSession,
              fmt::format("the {} static positions do not determine {}: their "
                          "orientations do not span the sphere; record more positions, "
                          "with each axis pointing up and down and at the cube's edges "
                          "and corners{}",
                          input_.positions.size(),
                          fmt::join(obs.undetermined, ", "),
                          only_angles ? "; or calibrate bias and scale only (the "
                                        "six-position protocol)"
                                      : ""),
              advice);
}

// The second pass weighs each position by its noise at the first estimate
// plus the scatter of the positions that noise leaves unexplained (zero for
// white noise, dominant on many real recordings).
void Fit::WeighByScatter() {
  sigmas_ = Sigmas(blocks_.Model());
  own_sigmas_ = sigmas_;
  std::vector<double> residuals;
  for (std::size_t k = 0; k < input_.positions.size(); ++k)
    residuals.push_back(Residual(k));
  const std::vector<double> leverages = Leverages(Jacobian());
  scatter_variance_ = PositionScatterVariance(residuals, sigmas_, leverages);
  // Too few residuals to estimate the scatter: the one known from more
  // positions of the same session (the split-half check's halves).
  const double parameters = std::accumulate(leverages.begin(), leverages.end(), 0.0);
  if (options_.known_position_scatter_mps2 &&
      static_cast<double>(residuals.size()) - parameters < kMinScatterRedundancy - 0.5) {
    scatter_variance_ = std::pow(*options_.known_position_scatter_mps2, 2);
  }
  for (double& sigma : sigmas_) sigma = std::sqrt(sigma * sigma + scatter_variance_);
  std::vector<double> whitened_abs;
  for (std::size_t k = 0; k < input_.positions.size(); ++k) {
    whitened_abs.push_back(std::abs(residuals[k] / sigmas_[k]));
  }
  loss_scale_ = std::max(kMadToSigma * Median(whitened_abs), 1e-12);
}

double Fit::Residual(std::size_t k) const {
  return Magnitude(blocks_.ModelAt(Dt(input_.positions[k])),
                   input_.positions[k],
                   options_.gravity_mps2);
}

double Fit::PredictedWithout(std::size_t k) const {
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

Eigen::MatrixXd Fit::Jacobian() {
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

Eigen::MatrixXd Fit::UnscaledCovariance() {
  ceres::Covariance::Options cov_options;
  // Dense SVD: the problem is 9 × K, and SVD still answers near rank loss.
  cov_options.algorithm_type = ceres::DENSE_SVD;
  cov_options.null_space_rank = -1;
  ceres::Covariance covariance(cov_options);
  const std::vector<double*> estimated = Estimated();
  const std::vector<const double*> blocks(estimated.begin(), estimated.end());
  if (!covariance.Compute(blocks, problem_.get())) {
    throw Error(ErrorKind::kSession,
                fmt::format("the covariance of the fit over {} static positions could "
                            "not be computed: they do not determine the parameters; "
                            "record more orientations",
                            input_.positions.size()),
                DetectAdvice());
  }
  const int p = static_cast<int>(Names().size());
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> c(p, p);
  covariance.GetCovarianceMatrix(blocks, c.data());
  return c;
}

std::vector<double> Fit::Sigmas(const ErrorModel& m) const {
  std::vector<double> s;
  for (std::size_t k = 0; k < input_.positions.size(); ++k) {
    ErrorModel at = m;
    at.bias_mps2 += Drift() * Dt(input_.positions[k]);
    s.push_back(ResidualSigma(
        at, input_.positions[k].mean_mps2, input_.noise[k], input_.positions[k].samples));
  }
  return s;
}

void Fit::AddResiduals(const std::vector<PositionObservation>& positions,
                       const std::vector<double>& sigmas,
                       RobustLoss loss,
                       Blocks& blocks,
                       ceres::Problem& problem) const {
  for (std::size_t k = 0; k < positions.size(); ++k) {
    if (drifts()) {
      auto* cost = new ceres::AutoDiffCostFunction<DriftMagnitudeResidual, 1, 3, 3, 3, 3>(
          new DriftMagnitudeResidual(positions[k].mean_mps2,
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
        new MagnitudeResidual(positions[k].mean_mps2, options_.gravity_mps2, sigmas[k]));
    problem.AddResidualBlock(
        cost, MakeLoss(loss, loss_scale_), blocks.bias, blocks.scale, blocks.angles);
  }
  if (options_.model == ModelKind::kBiasScale6) {
    problem.SetParameterBlockConstant(blocks.angles);
  }
}

void Fit::Build(RobustLoss loss) {
  problem_ = std::make_unique<ceres::Problem>();
  AddResiduals(input_.positions, sigmas_, loss, blocks_, *problem_);
}

std::vector<double*> Fit::Estimated() {
  std::vector<double*> blocks = {blocks_.bias, blocks_.scale};
  if (options_.model == ModelKind::kShinElSheimy9) blocks.push_back(blocks_.angles);
  if (drifts()) blocks.push_back(blocks_.drift);
  return blocks;
}

double ChiSquare(const Fit& fit, const std::vector<double>& sigmas) {
  double chi2 = 0.0;
  for (std::size_t j = 0; j < fit.size(); ++j) {
    chi2 += std::pow(fit.Residual(j) / sigmas[j], 2);
  }
  return chi2;
}

StandardisedResiduals Standardise(Fit& fit) {
  const std::vector<double> leverage = Leverages(fit.Jacobian());
  StandardisedResiduals z;
  for (std::size_t k = 0; k < fit.size(); ++k) {
    const double root = std::sqrt(1.0 - std::clamp(leverage[k], 0.0, 0.999));
    z.total.push_back(fit.Residual(k) / (fit.sigmas()[k] * root));
    z.own.push_back(fit.Residual(k) / (fit.own_sigmas()[k] * root));
  }
  return z;
}

}  // namespace mpcal::internal
