// The gyroscope estimator (gyro.h): weighted least squares over the turns
// with Ceres, analytic derivatives through the exponential map, covariance
// by ceres::Covariance scaled as the accelerometer's.
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include <ceres/ceres.h>
#include <fmt/format.h>
#include <Eigen/Cholesky>

#include <Eigen/Geometry>

#include "gyro_observability.h"
#include "mpcal/error.h"
#include "mpcal/gyro.h"
#include "rotation.h"
#include "turn_problem.h"

namespace mpcal {
namespace {

using internal::TurnData;
using internal::TurnProblem;
using RowMajor3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

// Turns whose gravity directions differ by less than this carry too little
// tilt to estimate the nominal scale of raw counts from.
constexpr double kMinScaleTurnRad = 20.0 * std::numbers::pi / 180.0;
// Beyond these the fit has left the region where the model means anything.
constexpr double kMaxPlausibleScaleError = 0.5;
constexpr double kMaxPlausibleMisalignment = 0.5;
// The a-priori noise level counts as this many residuals of evidence in the
// variance factor (solve.cc uses the same rule for the accelerometer).
constexpr double kPriorDof = 10.0;

class TurnCost : public ceres::SizedCostFunction<2, 9> {
 public:
  TurnCost(const TurnData& turn, double sigma) : turn_(turn), sigma_(sigma) {}
  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override {
    const Eigen::Matrix3d m = Eigen::Map<const RowMajor3>(parameters[0]);
    Eigen::Vector2d r;
    Eigen::Matrix<double, 2, 9> j;
    const bool want_j = jacobians != nullptr && jacobians[0] != nullptr;
    internal::TurnResidual(turn_, m, &r, want_j ? &j : nullptr);
    residuals[0] = r[0] / sigma_;
    residuals[1] = r[1] / sigma_;
    if (want_j) {
      Eigen::Map<Eigen::Matrix<double, 2, 9, Eigen::RowMajor>> out(jacobians[0]);
      out = j / sigma_;
    }
    return true;
  }

 private:
  const TurnData& turn_;
  double sigma_;
};

// M = k·I, one common scale: for the nominal scale of raw counts.
class ScaleCost : public ceres::SizedCostFunction<2, 1> {
 public:
  ScaleCost(const TurnData& turn, double sigma) : turn_(turn), sigma_(sigma) {}
  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override {
    const Eigen::Matrix3d m = parameters[0][0] * Eigen::Matrix3d::Identity();
    Eigen::Vector2d r;
    Eigen::Matrix<double, 2, 9> j;
    const bool want_j = jacobians != nullptr && jacobians[0] != nullptr;
    internal::TurnResidual(turn_, m, &r, want_j ? &j : nullptr);
    residuals[0] = r[0] / sigma_;
    residuals[1] = r[1] / sigma_;
    if (want_j) {
      const Eigen::Vector2d d = (j.col(0) + j.col(4) + j.col(8)) / sigma_;
      jacobians[0][0] = d[0];
      jacobians[0][1] = d[1];
    }
    return true;
  }

 private:
  const TurnData& turn_;
  double sigma_;
};

ceres::Solver::Summary RunSolver(ceres::Problem& problem, int max_iterations) {
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = max_iterations;
  options.function_tolerance = 1e-12;
  options.gradient_tolerance = 1e-12;
  options.parameter_tolerance = 1e-12;
  options.logging_type = ceres::SILENT;
  options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  return summary;
}

// Rough nominal scale of raw counts: the tilt between the directions over
// the length of the summed increments, median over the turns of some size.
double GuessScale(const TurnProblem& problem) {
  std::vector<double> ratios;
  for (const TurnData& t : problem.turns) {
    const double tilt = std::acos(std::clamp(t.u_from.dot(t.u_to), -1.0, 1.0));
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const auto& w : t.steps) sum += 0.5 * (w.begin + w.end);
    if (tilt > kMinScaleTurnRad && sum.norm() > 0.0) ratios.push_back(tilt / sum.norm());
  }
  if (ratios.empty()) return 0.0;
  std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
  return ratios[ratios.size() / 2];
}

// Least squares of one common scale from `guess`, weights at that scale.
double FitScale(const TurnProblem& problem, double guess, int max_iterations) {
  double k = guess;
  ceres::Problem p;
  for (const TurnData& t : problem.turns) {
    p.AddResidualBlock(new ScaleCost(t, t.Sigma(guess)), nullptr, &k);
  }
  p.SetParameterLowerBound(&k, 0, 0.2 * guess);
  p.SetParameterUpperBound(&k, 0, 5.0 * guess);
  RunSolver(p, max_iterations);
  return k;
}

// Whitened Jacobian (2·turns × 9) at the effective matrix, per entry of M
// (the effective matrix over the nominal scale).
Eigen::MatrixXd WhitenedJacobian(const TurnProblem& problem,
                                 const Eigen::Matrix3d& m_eff,
                                 double scale) {
  Eigen::MatrixXd j(2 * problem.turns.size(), 9);
  for (std::size_t k = 0; k < problem.turns.size(); ++k) {
    const TurnData& t = problem.turns[k];
    Eigen::Matrix<double, 2, 9> jk;
    internal::TurnResidual(t, m_eff, nullptr, &jk);
    j.middleRows(static_cast<Eigen::Index>(2 * k), 2) = jk * scale / t.Sigma(scale);
  }
  return j;
}

double Rms(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x * x;
  return v.empty() ? 0.0 : std::sqrt(s / static_cast<double>(v.size()));
}

bool Plausible(const Eigen::Matrix3d& m) {
  if (!m.allFinite()) return false;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      const double limit = r == c ? kMaxPlausibleScaleError : kMaxPlausibleMisalignment;
      if (std::abs(m(r, c) - (r == c ? 1.0 : 0.0)) >= limit) return false;
    }
  }
  return true;
}

double ResolveScale(const Recording& recording,
                    const GyroOptions& options,
                    const TurnProblem& problem,
                    bool* found) {
  *found = false;
  if (options.radps_per_unit > 0.0) return options.radps_per_unit;
  if (const auto fixed = FixedRadpsPerUnit(recording.gyro_units)) return *fixed;
  const double guess = GuessScale(problem);
  if (!(guess > 0.0)) {
    throw Error(fmt::format(
        "{}: no turn between the static positions tilts gravity by more than 20 degrees, "
        "so the scale of the gyroscope's raw counts cannot be found",
        recording.source));
  }
  *found = true;
  return FitScale(problem, guess, options.max_iterations);
}

}  // namespace

std::string GyroOptions::Validate() const {
  if (!(radps_per_unit >= 0.0) || !std::isfinite(radps_per_unit)) {
    return "radps_per_unit must be 0 (from the data) or a positive number";
  }
  if (!(direction_window_s >= 0.0) || !std::isfinite(direction_window_s)) {
    return "direction_window_s must be 0 (whole positions) or a positive time";
  }
  if (max_iterations < 1) return "max_iterations must be at least 1";
  if (!(poorly_determined_std > 0.0)) return "poorly_determined_std must be positive";
  return "";
}

std::string_view ToString(GyroFindingKind kind) {
  switch (kind) {
    case GyroFindingKind::kTooFewTurns:
      return "too-few-turns";
    case GyroFindingKind::kUndetermined:
      return "undetermined";
    case GyroFindingKind::kPoorlyDetermined:
      return "poorly-determined";
  }
  return "unknown";
}

std::string_view ToString(GSensitivity mode) {
  switch (mode) {
    case GSensitivity::kOff:
      return "off";
    case GSensitivity::kAuto:
      return "auto";
    case GSensitivity::kOn:
      return "on";
  }
  return "unknown";
}

std::string_view ToString(GyroStatus status) {
  switch (status) {
    case GyroStatus::kConverged:
      return "converged";
    case GyroStatus::kNoConvergence:
      return "no convergence";
    case GyroStatus::kUndetermined:
      return "undetermined";
  }
  return "unknown";
}

GyroResult CalibrateGyroscope(const Recording& recording,
                              std::span<const StaticInterval> intervals,
                              const Calibration& accel,
                              const GyroOptions& options) {
  if (const std::string problem = options.Validate(); !problem.empty()) {
    throw Error("gyroscope options: " + problem);
  }
  // The nominal scale is needed to carry the directions to the turns' ends:
  // for raw counts it is found first from a problem without that carrying.
  double carry_scale = options.radps_per_unit;
  if (!(carry_scale > 0.0)) {
    if (const auto fixed = FixedRadpsPerUnit(recording.gyro_units)) carry_scale = *fixed;
  }
  if (!(carry_scale > 0.0)) {
    const TurnProblem first = internal::BuildTurnProblem(recording,
                                                         intervals,
                                                         accel,
                                                         options.direction_window_s,
                                                         options.g_sensitivity,
                                                         options.g_sensitivity_min_f,
                                                         0.0);
    bool unused = false;
    if (first.turns.size() >= 5)
      carry_scale = ResolveScale(recording, options, first, &unused);
  }
  const TurnProblem problem = internal::BuildTurnProblem(recording,
                                                         intervals,
                                                         accel,
                                                         options.direction_window_s,
                                                         options.g_sensitivity,
                                                         options.g_sensitivity_min_f,
                                                         carry_scale);
  GyroResult result;
  GyroCalibration& c = result.calibration;
  c.input_units = recording.gyro_units;

  const std::size_t turns = problem.turns.size();
  for (const TurnData& t : problem.turns) {
    GyroTurn turn;
    turn.from_position = t.from_position;
    turn.begin = t.begin;
    turn.end = t.end;
    turn.start_s = t.start_s;
    turn.end_s = t.end_s;
    result.turns.push_back(turn);
  }
  if (2 * turns < 10) {
    GyroFinding few;
    few.kind = GyroFindingKind::kTooFewTurns;
    few.value = static_cast<double>(turns);
    few.limit = 5.0;
    few.turn_axes = {true, true, true};
    for (int j = 0; j < 9; ++j) few.parameters.push_back(j);
    result.findings.push_back(few);
    result.status = GyroStatus::kUndetermined;
    return result;
  }

  bool scale_found = false;
  const double scale = ResolveScale(recording, options, problem, &scale_found);
  c.radps_per_unit = scale;
  double m_eff[9];
  Eigen::Map<RowMajor3> m_start(m_eff);
  m_start = scale * Eigen::Matrix3d::Identity();

  // Before: nominal scale and per-position bias.
  for (std::size_t k = 0; k < turns; ++k) {
    const Eigen::Matrix3d r = internal::TurnResidual(
        problem.turns[k], Eigen::Map<RowMajor3>(m_eff), nullptr, nullptr);
    result.turns[k].residual_before_rad = internal::TurnTilt(problem.turns[k], r);
    result.turns[k].sigma_rad = problem.turns[k].Sigma(scale);
  }
  // Asked before solving: a solver let loose on an undetermined problem
  // wanders off.
  Eigen::Matrix<double, 9, 1> singular;
  result.findings = internal::AnalyseGyroObservability(
      WhitenedJacobian(problem, Eigen::Map<RowMajor3>(m_eff), scale),
      1.0,
      options.poorly_determined_std,
      &singular);
  for (const GyroFinding& f : result.findings) {
    if (f.kind == GyroFindingKind::kUndetermined) {
      result.status = GyroStatus::kUndetermined;
      return result;
    }
  }
  result.findings.clear();

  ceres::Problem p;
  for (const TurnData& t : problem.turns) {
    p.AddResidualBlock(new TurnCost(t, t.Sigma(scale)), nullptr, m_eff);
  }
  const ceres::Solver::Summary summary = RunSolver(p, options.max_iterations);
  const Eigen::Matrix3d m_raw = Eigen::Map<RowMajor3>(m_eff);
  c.m = m_raw / scale;

  std::vector<double> before;
  std::vector<double> after;
  double chi2 = 0.0;
  for (std::size_t k = 0; k < turns; ++k) {
    const TurnData& t = problem.turns[k];
    Eigen::Vector2d r;
    const Eigen::Matrix3d rotation = internal::TurnResidual(t, m_raw, &r, nullptr);
    chi2 += (r / t.Sigma(scale)).squaredNorm();
    GyroTurn& turn = result.turns[k];
    turn.residual_after_rad = internal::TurnTilt(t, rotation);
    const Eigen::AngleAxisd aa(rotation);
    turn.angle_rad = aa.angle();
    turn.axis = aa.axis();
    before.push_back(turn.residual_before_rad);
    after.push_back(turn.residual_after_rad);
  }
  const double dof = 2.0 * static_cast<double>(turns) - 9.0;
  result.covariance_scale = std::max(1.0, (kPriorDof + chi2) / (kPriorDof + dof));

  const Eigen::MatrixXd j = WhitenedJacobian(problem, m_raw, scale);
  result.information = j.transpose() * j;
  result.findings = internal::AnalyseGyroObservability(
      j, result.covariance_scale, options.poorly_determined_std, &result.singular_values);

  ceres::Covariance::Options cov_options;
  cov_options.algorithm_type = ceres::DENSE_SVD;
  cov_options.null_space_rank = -1;
  ceres::Covariance covariance(cov_options);
  const std::vector<const double*> blocks = {m_eff};
  Eigen::Matrix<double, 9, 9, Eigen::RowMajor> cov = Eigen::Matrix<double, 9, 9>::Zero();
  if (covariance.Compute(blocks, &p))
    covariance.GetCovarianceBlock(m_eff, m_eff, cov.data());
  c.m_covariance = result.covariance_scale * cov / (scale * scale);

  for (const auto& b : problem.bias_raw) {
    c.position_bias.push_back({b.t_s, b.bias_radps * scale});
  }
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& b : c.position_bias) mean += b.bias_radps;
  mean /= static_cast<double>(c.position_bias.size());
  Eigen::Vector3d spread = Eigen::Vector3d::Zero();
  for (const auto& b : c.position_bias) spread += (b.bias_radps - mean).cwiseAbs2();
  const double n = static_cast<double>(c.position_bias.size());
  c.bias_radps =
      problem.g_sensitivity_used ? (problem.bias_without_g_raw * scale).eval() : mean;
  if (problem.g_sensitivity_used) {
    c.g_sensitivity_radps_per_mps2 = problem.g_sensitivity_raw_per_mps2 * scale;
  }
  result.g_sensitivity_f = problem.g_sensitivity_f;
  c.bias_std_radps = (spread / std::max(n - 1.0, 1.0) / n).cwiseSqrt();

  GyroFitSummary fit;
  fit.turns = static_cast<int>(turns);
  fit.residual_rms_before_rad = Rms(before);
  fit.residual_rms_after_rad = Rms(after);
  fit.iterations = static_cast<int>(summary.iterations.size()) - 1;
  fit.variance_factor = dof > 0 ? chi2 / dof : 1.0;
  fit.noise_std_radps = problem.noise_std_raw * scale;
  fit.sample_period_s = problem.sample_period_s;
  const bool converged = summary.termination_type == ceres::CONVERGENCE && Plausible(c.m);
  fit.converged = converged;
  c.fit = fit;
  result.status = converged ? GyroStatus::kConverged : GyroStatus::kNoConvergence;
  result.message = Plausible(c.m)
                       ? summary.message
                       : "the estimate left the plausible range (|scale - 1| < 0.5, "
                         "|misalignment| < 0.5): the solver diverged";
  (void)scale_found;
  return result;
}

Eigen::Matrix<double, 9, 9> GyroCramerRaoBound(const Recording& recording,
                                               std::span<const StaticInterval> intervals,
                                               const Calibration& accel,
                                               const GyroCalibration& truth) {
  const TurnProblem problem = internal::BuildTurnProblem(
      recording,
      intervals,
      accel,
      GyroOptions().direction_window_s,
      truth.g_sensitivity_radps_per_mps2 ? GSensitivity::kOn : GSensitivity::kOff,
      GyroOptions().g_sensitivity_min_f,
      truth.radps_per_unit);
  const double scale = truth.radps_per_unit;
  const Eigen::MatrixXd j = WhitenedJacobian(problem, truth.m * scale, scale);
  const Eigen::MatrixXd information = j.transpose() * j;
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(information);
  const Eigen::VectorXd d = ldlt.vectorD().cwiseAbs();
  if (ldlt.info() != Eigen::Success || d.minCoeff() <= 1e-12 * d.maxCoeff()) {
    throw Error(fmt::format("gyroscope Cramér-Rao bound: the {} turns do not determine M",
                            problem.turns.size()));
  }
  return ldlt.solve(Eigen::MatrixXd::Identity(9, 9));
}

Eigen::Matrix3d IntegrateRotation(const Recording& recording,
                                  std::size_t begin,
                                  std::size_t end,
                                  const GyroCalibration& gyro) {
  if (recording.gyro_radps.size() != recording.size() || recording.empty()) {
    throw Error(fmt::format("{}: the log has no gyroscope readings", recording.source));
  }
  if (begin > end || end >= recording.size()) {
    throw Error(fmt::format("{}: samples {}-{} are outside the recording ({} samples)",
                            recording.source,
                            begin,
                            end,
                            recording.size()));
  }
  std::vector<internal::TurnStep> steps;
  steps.reserve(end - begin);
  for (std::size_t i = begin; i < end; ++i) {
    const double dt = recording.time_s[i + 1] - recording.time_s[i];
    steps.push_back({gyro.Correct(recording.gyro_radps[i]) * dt,
                     gyro.Correct(recording.gyro_radps[i + 1]) * dt});
  }
  return internal::RotationOverTurn(Eigen::Matrix3d::Identity(), steps, nullptr);
}

}  // namespace mpcal
