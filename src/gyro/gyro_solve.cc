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
#include <Eigen/Eigenvalues>

#include <Eigen/Geometry>

#include "gyro_observability.h"
#include "mpcal/error.h"
#include "mpcal/gyro.h"
#include "mpcal/plausible.h"
#include "rotation.h"
#include "turn_problem.h"
#include "turn_weights.h"

namespace mpcal {
namespace {

using internal::TurnData;
using internal::TurnProblem;
using RowMajor3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

// Turns whose gravity directions differ by less than this carry too little
// tilt to estimate the nominal scale of raw counts from.
constexpr double kMinScaleTurnRad = 20.0 * std::numbers::pi / 180.0;
// Beyond these the fit has left the region where the model means anything.
// What a gyroscope's M can be (plausible.h): the file's reader refuses the
// rest, so the fit does not offer it.
constexpr double kMaxPlausibleScaleError = kMaxScaleFactorError;
constexpr double kMaxPlausibleMisalignment = kMaxGyroMisalignment;
// The a-priori noise level counts as this many residuals of evidence in the
// variance factor (solve.cc uses the same rule for the accelerometer).
constexpr double kPriorDof = 10.0;
// Each turn gives two equations: five turns for the nine entries of M.
constexpr std::size_t kMinTurns = 5;

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

// M = k·I, one common scale: for the nominal scale of raw counts. Its
// derivative along I alone: 3 values per sample where M's needs 27.
class ScaleCost : public ceres::SizedCostFunction<2, 1> {
 public:
  ScaleCost(const TurnData& turn, double sigma) : turn_(turn), sigma_(sigma) {}
  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override {
    const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
    Eigen::Vector2d r;
    Eigen::Vector2d d;
    const bool want_j = jacobians != nullptr && jacobians[0] != nullptr;
    internal::TurnResidualAlong(
        turn_, parameters[0][0] * identity, identity, &r, want_j ? &d : nullptr);
    residuals[0] = r[0] / sigma_;
    residuals[1] = r[1] / sigma_;
    if (want_j) {
      jacobians[0][0] = d[0] / sigma_;
      jacobians[0][1] = d[1] / sigma_;
    }
    return true;
  }

 private:
  const TurnData& turn_;
  double sigma_;
};

// Levenberg-Marquardt on at most 9 parameters in one block: a dense QR of a
// 2·turns × 9 Jacobian costs nothing beside the evaluation of the turns, so
// the solver's options only matter through the evaluations they ask for.
// Each iteration costs an evaluation of every turn with its Jacobian and one
// without: the tolerances stop where a further step would move the estimate
// by less than 1e-4 of its 1σ (the cost is about one per residual, and a
// step of δ σ changes it by δ²/2: a relative change of 1e-10 is δ ~ 1e-4).
ceres::Solver::Summary RunSolver(ceres::Problem& problem, int max_iterations) {
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = max_iterations;
  options.function_tolerance = 1e-10;
  options.gradient_tolerance = 1e-12;
  options.parameter_tolerance = 1e-10;
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

// Every turn at one effective matrix (raw increments → rad): rotations,
// tilts, χ² and the whitened Jacobian per entry of M (the effective matrix
// over the nominal scale), in one pass over the samples.
struct TurnEvaluation {
  std::vector<Eigen::Matrix3d> rotations;
  std::vector<double> tilts_rad;
  double chi2 = 0.0;
  Eigen::MatrixXd jacobian;  // 2·turns × 9
};

TurnEvaluation EvaluateTurns(const TurnProblem& problem,
                             const Eigen::Matrix3d& m_eff,
                             double scale) {
  TurnEvaluation e;
  e.jacobian.resize(static_cast<Eigen::Index>(2 * problem.turns.size()), 9);
  for (std::size_t k = 0; k < problem.turns.size(); ++k) {
    const TurnData& t = problem.turns[k];
    const double sigma = t.Sigma(scale);
    Eigen::Vector2d r;
    Eigen::Matrix<double, 2, 9> jk;
    e.rotations.push_back(internal::TurnResidual(t, m_eff, &r, &jk));
    e.tilts_rad.push_back(internal::TurnTilt(t, e.rotations.back()));
    e.chi2 += (r / sigma).squaredNorm();
    e.jacobian.middleRows(static_cast<Eigen::Index>(2 * k), 2) = jk * scale / sigma;
  }
  return e;
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

// The rest of what the file's reader accepts (plausible.h): every 1σ of M
// below kMaxScaleFactorError, G within 10 °/s per g.
bool PlausibleSpread(const GyroCalibration& c) {
  if (c.m_covariance) {
    for (int i = 0; i < 9; ++i) {
      if (!((*c.m_covariance)(i, i) < kMaxScaleFactorError * kMaxScaleFactorError)) {
        return false;
      }
    }
  }
  return !c.g_sensitivity_radps_per_mps2 ||
         c.g_sensitivity_radps_per_mps2->cwiseAbs().maxCoeff() <=
             kMaxGyroGSensitivityRadpsPerMps2;
}

// The Moore-Penrose inverse of the information (the covariance of the
// entries it determines; directions it does not determine get none).
Eigen::Matrix<double, 9, 9> PseudoInverse(
    const Eigen::Matrix<double, 9, 9>& information) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> eig(information);
  const Eigen::Matrix<double, 9, 1>& values = eig.eigenvalues();
  const double floor = 1e-14 * values.cwiseAbs().maxCoeff();
  Eigen::Matrix<double, 9, 1> inverse = Eigen::Matrix<double, 9, 1>::Zero();
  for (int i = 0; i < 9; ++i) {
    if (values[i] > floor) inverse[i] = 1.0 / values[i];
  }
  return eig.eigenvectors() * inverse.asDiagonal() * eig.eigenvectors().transpose();
}

double ResolveScale(const RecordingView& recording,
                    const GyroOptions& options,
                    const TurnProblem& problem) {
  if (options.radps_per_unit > 0.0) return options.radps_per_unit;
  if (const auto fixed = FixedRadpsPerUnit(recording.gyro_units)) return *fixed;
  const double guess = GuessScale(problem);
  if (!(guess > 0.0)) {
    throw Error(ErrorKind::kSession,
                fmt::format("{}: no turn between the static positions tilts gravity by "
                            "more than 20 degrees, so the scale of the gyroscope's raw "
                            "counts cannot be found",
                            recording.source),
                Advice{{Setting{Option::kLogGyroUnits, ""}}, Stage::kNone, ""});
  }
  return FitScale(problem, guess, options.max_iterations);
}

internal::TurnProblem BuildProblem(const RecordingView& recording,
                                   std::span<const StaticInterval> intervals,
                                   const Calibration& accel,
                                   const GyroOptions& options,
                                   double carry_radps_per_unit) {
  return internal::BuildTurnProblem(recording,
                                    intervals,
                                    accel,
                                    options.direction_window_s,
                                    options.g_sensitivity,
                                    options.g_sensitivity_min_f,
                                    carry_radps_per_unit);
}

// The nominal scale that carries the directions to the turns' ends: for raw
// counts found first from a problem without that carrying.
double CarryScale(const RecordingView& recording,
                  std::span<const StaticInterval> intervals,
                  const Calibration& accel,
                  const GyroOptions& options) {
  if (options.radps_per_unit > 0.0) return options.radps_per_unit;
  if (const auto fixed = FixedRadpsPerUnit(recording.gyro_units)) return *fixed;
  const TurnProblem first = BuildProblem(recording, intervals, accel, options, 0.0);
  constexpr std::size_t kMinTurnsForScale = 5;
  if (first.turns.size() < kMinTurnsForScale) return 0.0;
  return ResolveScale(recording, options, first);
}

std::vector<GyroTurn> DescribeTurns(const TurnProblem& problem) {
  std::vector<GyroTurn> turns;
  for (const TurnData& t : problem.turns) {
    GyroTurn turn;
    turn.from_position = t.from_position;
    turn.begin = t.begin;
    turn.end = t.end;
    turn.start_s = t.start_s;
    turn.end_s = t.end_s;
    turns.push_back(turn);
  }
  return turns;
}

GyroFinding TooFewTurns(std::size_t turns) {
  GyroFinding few;
  few.kind = GyroFindingKind::kTooFewTurns;
  few.value = static_cast<double>(turns);
  few.limit = static_cast<double>(kMinTurns);
  few.turn_axes = {true, true, true};
  for (int j = 0; j < 9; ++j) few.parameters.push_back(j);
  return few;
}

// The bias at every position, its mean and the mean's scatter, and G.
void FillBias(const TurnProblem& problem, double scale, GyroCalibration* c) {
  for (const auto& b : problem.bias_raw) {
    c->position_bias.push_back({b.t_s, b.bias_radps * scale});
  }
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& b : c->position_bias) mean += b.bias_radps;
  const double n = static_cast<double>(c->position_bias.size());
  mean /= n;
  Eigen::Vector3d spread = Eigen::Vector3d::Zero();
  for (const auto& b : c->position_bias) spread += (b.bias_radps - mean).cwiseAbs2();
  c->bias_radps =
      problem.g_sensitivity_used ? (problem.bias_without_g_raw * scale).eval() : mean;
  if (problem.g_sensitivity_used) {
    c->g_sensitivity_radps_per_mps2 = problem.g_sensitivity_raw_per_mps2 * scale;
  }
  c->bias_std_radps = (spread / std::max(n - 1.0, 1.0) / n).cwiseSqrt();
}

// Residuals, covariance, findings and summary at the solution `m_raw`.
void Finish(const TurnProblem& problem,
            const Eigen::Matrix3d& m_raw,
            double scale,
            const GyroOptions& options,
            const ceres::Solver::Summary& summary,
            GyroResult* result) {
  GyroCalibration& c = result->calibration;
  c.m = m_raw / scale;
  const TurnEvaluation after = EvaluateTurns(problem, m_raw, scale);
  std::vector<double> before;
  for (std::size_t k = 0; k < problem.turns.size(); ++k) {
    GyroTurn& turn = result->turns[k];
    turn.residual_after_rad = after.tilts_rad[k];
    const Eigen::AngleAxisd aa(after.rotations[k]);
    turn.angle_rad = aa.angle();
    turn.axis = aa.axis();
    before.push_back(turn.residual_before_rad);
  }
  const double dof = 2.0 * static_cast<double>(problem.turns.size()) - 9.0;
  result->covariance_scale = std::max(1.0, (kPriorDof + after.chi2) / (kPriorDof + dof));
  result->information = after.jacobian.transpose() * after.jacobian;
  result->findings = internal::AnalyseGyroObservability(after.jacobian,
                                                        result->covariance_scale,
                                                        options.poorly_determined_std,
                                                        &result->singular_values);
  c.m_covariance = result->covariance_scale * PseudoInverse(result->information);
  FillBias(problem, scale, &c);
  result->g_sensitivity_f = problem.g_sensitivity_f;

  GyroFitSummary fit;
  fit.turns = static_cast<int>(problem.turns.size());
  fit.residual_rms_before_rad = Rms(before);
  fit.residual_rms_after_rad = Rms(after.tilts_rad);
  fit.iterations = static_cast<int>(summary.iterations.size()) - 1;
  fit.variance_factor = dof > 0 ? after.chi2 / dof : 1.0;
  fit.noise_std_radps = problem.noise_std_raw * scale;
  fit.sample_period_s = problem.sample_period_s;
  const bool plausible = Plausible(c.m);
  const bool plausible_spread = PlausibleSpread(c);
  fit.converged =
      summary.termination_type == ceres::CONVERGENCE && plausible && plausible_spread;
  c.fit = fit;
  result->status = fit.converged ? GyroStatus::kConverged : GyroStatus::kNoConvergence;
  // The turns may determine M at the nominal start and not at the estimate
  // (a log in deg/s read as rad/s turns 57 times too far): such an M is
  // not a calibration, whatever the solver says.
  for (const GyroFinding& f : result->findings) {
    if (f.kind == GyroFindingKind::kUndetermined)
      result->status = GyroStatus::kUndetermined;
  }
  result->message =
      !plausible ? "the estimate left the plausible range (|scale - 1| < 0.5, "
                   "|misalignment| < 0.5): the solver diverged"
      : !plausible_spread
          ? "the estimate's 1σ of M (0.5 or more) or its bias's g-sensitivity "
            "(beyond 10 deg/s per g) is not a sensor's"
          : summary.message;
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

GyroResult CalibrateGyroscope(const RecordingView& recording,
                              std::span<const StaticInterval> intervals,
                              const Calibration& accel,
                              const GyroOptions& options) {
  if (const std::string problem = options.Validate(); !problem.empty()) {
    throw Error(ErrorKind::kOption, "gyroscope options: " + problem);
  }
  const double carry_scale = CarryScale(recording, intervals, accel, options);
  TurnProblem problem = BuildProblem(recording, intervals, accel, options, carry_scale);
  GyroResult result;
  result.directions =
      internal::WeighTurns(recording, intervals, accel, carry_scale, &problem);
  // The file records the units of the log's columns as written, so that it
  // applies to the logs as written: a log in deg/s is held in rad/s
  // (Recording::gyro_radps), and its nominal factor to rad/s is π/180.
  const bool counts = recording.gyro_units == GyroUnits::kCounts;
  result.calibration.input_units = counts ? GyroUnits::kCounts : recording.gyro_log_units;
  const double held_per_log_unit =
      counts ? 1.0 : FixedRadpsPerUnit(recording.gyro_log_units).value_or(1.0);
  result.turns = DescribeTurns(problem);
  if (problem.turns.size() < kMinTurns) {
    result.findings.push_back(TooFewTurns(problem.turns.size()));
    result.status = GyroStatus::kUndetermined;
    return result;
  }
  // For raw counts the scale fitted for the carrying is the nominal scale:
  // fitted again on the carried directions it moves by 1e-5 of itself, which
  // M's diagonal (relative to it) absorbs, at twice the cost of the solve.
  const double scale =
      carry_scale > 0.0 ? carry_scale : ResolveScale(recording, options, problem);
  result.calibration.radps_per_unit = scale * held_per_log_unit;

  // Before: nominal scale and per-position bias. The observability is asked
  // before solving: a solver let loose on an undetermined problem wanders off.
  Eigen::Matrix3d m_start = scale * Eigen::Matrix3d::Identity();
  const TurnEvaluation before = EvaluateTurns(problem, m_start, scale);
  for (std::size_t k = 0; k < problem.turns.size(); ++k) {
    result.turns[k].residual_before_rad = before.tilts_rad[k];
    result.turns[k].sigma_rad = problem.turns[k].Sigma(scale);
  }
  Eigen::Matrix<double, 9, 1> singular;
  result.findings = internal::AnalyseGyroObservability(
      before.jacobian, 1.0, options.poorly_determined_std, &singular);
  for (const GyroFinding& f : result.findings) {
    if (f.kind == GyroFindingKind::kUndetermined) {
      result.status = GyroStatus::kUndetermined;
      return result;
    }
  }

  RowMajor3 m_eff = m_start;
  ceres::Problem p;
  for (const TurnData& t : problem.turns) {
    p.AddResidualBlock(new TurnCost(t, t.Sigma(scale)), nullptr, m_eff.data());
  }
  const ceres::Solver::Summary summary = RunSolver(p, options.max_iterations);
  Finish(problem, m_eff, scale, options, summary, &result);
  return result;
}

Eigen::Matrix<double, 9, 9> GyroCramerRaoBound(const RecordingView& recording,
                                               std::span<const StaticInterval> intervals,
                                               const Calibration& accel,
                                               const GyroCalibration& truth) {
  internal::TurnProblem problem = internal::BuildTurnProblem(
      recording,
      intervals,
      accel,
      GyroOptions().direction_window_s,
      truth.g_sensitivity_radps_per_mps2 ? GSensitivity::kOn : GSensitivity::kOff,
      GyroOptions().g_sensitivity_min_f,
      internal::HeldRadpsPerUnit(recording, truth));
  const double scale = internal::HeldRadpsPerUnit(recording, truth);
  internal::WeighTurns(recording, intervals, accel, scale, &problem);
  const Eigen::MatrixXd j = EvaluateTurns(problem, truth.m * scale, scale).jacobian;
  const Eigen::MatrixXd information = j.transpose() * j;
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(information);
  const Eigen::VectorXd d = ldlt.vectorD().cwiseAbs();
  if (ldlt.info() != Eigen::Success || d.minCoeff() <= 1e-12 * d.maxCoeff()) {
    throw Error(ErrorKind::kSession,
                fmt::format("gyroscope Cramér-Rao bound: the {} turns do not determine M",
                            problem.turns.size()));
  }
  return ldlt.solve(Eigen::MatrixXd::Identity(9, 9));
}

Eigen::Matrix3d IntegrateRotation(const RecordingView& recording,
                                  std::size_t begin,
                                  std::size_t end,
                                  const GyroCalibration& gyro) {
  if (recording.gyro_radps.size() != recording.size() || recording.empty()) {
    throw Error(ErrorKind::kColumns,
                fmt::format("{}: the log has no gyroscope readings", recording.source));
  }
  if (begin > end || end >= recording.size()) {
    throw Error(ErrorKind::kInput,
                fmt::format("{}: samples {}-{} are outside the recording ({} samples)",
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
