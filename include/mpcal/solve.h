/// \file solve.h
/// \brief The estimator of the modified multi-position method (Souza & Machado
/// 2016, eqs 11-12; Syed et al. 2007): six-position initialisation, then
/// nonlinear least squares over the static-position means, with covariance.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mpcal/calibration.h"
#include "mpcal/model.h"

namespace mpcal {

/// One static position, in m/s² (already scaled by the nominal sensitivity).
struct PositionObservation {
  Eigen::Vector3d mean_mps2 = Eigen::Vector3d::Zero();
  /// Per-axis sample standard deviation of the readings (m/s²).
  Eigen::Vector3d sample_std_mps2 = Eigen::Vector3d::Zero();
  std::size_t samples = 0;
  /// Where it is in the recording (s), for messages.
  double start_s = 0.0;
  double end_s = 0.0;
};

enum class RobustLoss { kNone, kHuber, kCauchy };
std::string_view ToString(RobustLoss loss);
std::optional<RobustLoss> ParseRobustLoss(std::string_view name);

struct SolveOptions {
  ModelKind model = ModelKind::kShinElSheimy9;
  /// Magnitude of gravity at the site (m/s²); see gravity.h.
  double gravity_mps2 = 9.80665;
  /// Robust loss on the whitened residuals; kNone is the paper's estimator.
  RobustLoss robust = RobustLoss::kNone;
  /// Iteration cap of the Levenberg-Marquardt solver.
  int max_iterations = 100;
  /// Exclude positions whose deleted residual (the residual a fit without
  /// them predicts, against that position's own noise level) exceeds
  /// `outlier_threshold` robust standard deviations, one at a time, at most
  /// a fifth of the positions. Turn off to keep every position.
  bool exclude_outliers = true;
  double outlier_threshold = 5.0;
  /// Leave-one-position-out cross-validation (K extra small fits).
  bool cross_validate = true;
  /// The split-half check (four extra fits): the used positions split by
  /// time and alternately (each pair of nearest orientations shared between
  /// the halves, so that both span the sphere as the whole does), each half
  /// calibrated alone, and every 1σ widened when two halves disagree beyond
  /// chance at `split_half_significance`.
  bool split_half_check = true;
  double split_half_significance = 0.01;
  /// A bias drifting linearly over the session, b(t) = b + d·(t − t_ref),
  /// three more parameters: fitted besides the constant bias and chosen
  /// when the improvement rejects a constant bias at
  /// `bias_drift_significance`: by a likelihood-ratio test (χ² with 3
  /// degrees of freedom) when the drifting fit leaves no scatter beyond the
  /// sensor noise, so that the weights are known; by an F test when the
  /// weights' level is estimated from the residuals. Off: the bias is
  /// constant.
  bool consider_bias_drift = true;
  double bias_drift_significance = 0.01;
  /// Fit the drift whatever the test says (the split-half check fits the
  /// halves of a session whose whole showed a drift with it).
  bool force_bias_drift = false;
  /// t_ref in the positions' clock (s): a drifting bias is reported as the
  /// bias at this time. Unset: the mean of the used positions' middles.
  std::optional<double> bias_reference_time_s;
  /// The scatter of the positions beyond their noise (m/s², 1σ) when known
  /// from more positions than these: used when these are too few to
  /// estimate it (fewer than 5 redundant). The split-half check gives each
  /// half the whole session's. Unset: estimated, or zero when too few.
  std::optional<double> known_position_scatter_mps2;
  /// Offset of the readings before calibration (m/s²), for the "before"
  /// residuals only: zero for m/s² and g; for raw counts the ADC's zero
  /// found from the positions, so that "before" means nominal scale and
  /// offset rather than an arbitrary 32768 counts.
  Eigen::Vector3d nominal_offset_mps2 = Eigen::Vector3d::Zero();

  /// Empty string when valid, otherwise names the first bad field.
  std::string Validate() const;
};

/// What a warning of the solver is about.
enum class SolveNoteKind {
  kOutlierExcluded,  ///< a position left out: it fits far beyond its noise
  /// A position that fits far beyond its noise kept: without it the others
  /// do not determine the parameters.
  kOutlierKept,
  kPoorlyDetermined,  ///< a parameter strongly correlated with others
  kNoRedundancy,      ///< as many positions as parameters: nothing checks them
  kHalvesDisagree,    ///< two halves of the positions differ beyond their 1σ
};

/// The facts of one warning of the solver (SolveResult::notes, one per
/// entry of SolveResult::warnings, in the same order).
struct SolveNote {
  SolveNoteKind kind = SolveNoteKind::kOutlierExcluded;
  /// kOutlier*: the position (0-based, in the order given), its times (s,
  /// the positions' clock) and its deleted residual in units of its noise.
  std::size_t position = 0;
  double start_s = 0.0;
  double end_s = 0.0;
  double residual_z = 0.0;
  /// kPoorlyDetermined: the parameter (a name of kParameterNames).
  std::string parameter;
  /// kNoRedundancy: the positions and the parameters they determine.
  std::size_t positions = 0;
  int parameters = 0;
  /// kHalvesDisagree: the comparison, and the factor every 1σ is widened by.
  SplitHalfComparison halves;
  double widening = 1.0;
};

enum class SolveStatus { kConverged, kNoConvergence };
std::string_view ToString(SolveStatus status);

struct SolveResult {
  SolveStatus status = SolveStatus::kNoConvergence;
  std::string message;
  ErrorModel initial;  ///< six-position initialisation
  ErrorModel estimate;
  /// Covariance of the 9 packed parameters (order of kParameterNames), scaled
  /// by the a-posteriori variance of unit weight when that exceeds 1 (the
  /// residuals show more scatter than the measured noise explains). Rows and columns of
  /// parameters held fixed (angles of kBiasScale6) are zero.
  Eigen::Matrix<double, 9, 9> covariance = Eigen::Matrix<double, 9, 9>::Zero();
  ErrorModel std;  ///< square roots of the covariance diagonal
  /// |a_k| − g per position (m/s²) with the raw readings (nominal scale and
  /// offset only) and
  /// at the estimate, for every position given, used or not; the RMS is over
  /// the used ones.
  std::vector<double> residual_before_mps2;
  std::vector<double> residual_after_mps2;
  double residual_rms_before_mps2 = 0.0;
  double residual_rms_after_mps2 = 0.0;
  /// Residual of each position predicted by the fit without it (m/s²); NaN
  /// for a position without which the parameters are undetermined (it cannot
  /// be predicted); empty when cross-validation is off. The RMS is over the
  /// predicted used positions.
  std::vector<double> cross_validation_residual_mps2;
  double cross_validation_rms_mps2 = 0.0;
  /// Whether each position was used; false for excluded outliers.
  std::vector<bool> used;
  /// Each position's deleted residual in units of its noise level.
  std::vector<double> standardised_residual;
  /// Scatter of the positions beyond what their sensor noise explains (m/s²,
  /// 1σ): hand tremor, non-white noise or model error; it enters every
  /// position's weight. Zero when the noise explains the residuals.
  double position_scatter_mps2 = 0.0;
  /// The split-half check; nullopt when it is off. The covariance and std
  /// above already carry its widening.
  std::optional<SplitHalfSummary> split_half;
  /// The drift of the bias when the test chose it (`estimate` then holds
  /// the bias at its reference time), and the test's p-value whenever the
  /// test was made (enough positions for 12 parameters).
  std::optional<BiasDrift> bias_drift;
  std::optional<double> bias_drift_p_value;
  /// The time (s, the positions' clock) the estimated bias refers to: the
  /// drift's reference time with a drifting bias; without, the same time
  /// (options.bias_reference_time_s or the mean of the used positions'
  /// middles), near which a constant-bias fit meets a slowly drifting bias.
  double bias_reference_time_s = 0.0;
  /// χ² of the whitened residuals over degrees of freedom.
  double variance_factor = 0.0;
  double final_cost = 0.0;
  int iterations = 0;
  std::vector<std::string> warnings;
  /// The facts of each of `warnings`, in the same order.
  std::vector<SolveNote> notes;
  /// Parameters the positions determine only poorly (strongly correlated
  /// with others; names of kParameterNames): more orientations, filling the
  /// gaps of their coverage of the sphere (Stage::kDetect shows it), help.
  std::vector<std::string> poorly_determined;

  bool converged() const { return status == SolveStatus::kConverged; }
  /// One line: status, iterations, RMS before/after.
  std::string BriefReport() const;
};

/// Six-position initialisation (Syed et al. 2007): for each axis the recorded
/// positions with that axis nearest up and down give b ≈ (Y_up + Y_down)/2 and
/// 1 + s ≈ (Y_up − Y_down)/(2g); angles start at zero.
/// \throws mpcal::Error if fewer than 2 positions are given.
ErrorModel InitialiseSixPosition(std::span<const PositionObservation> positions,
                                 double gravity_mps2);

/// Estimates the model from the position means.
/// \throws mpcal::Error for invalid options, or fewer positions than the
///   model has parameters (+1), or non-finite observations.
SolveResult Solve(std::span<const PositionObservation> positions,
                  const SolveOptions& options);

}  // namespace mpcal
