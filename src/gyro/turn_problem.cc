#include "turn_problem.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

#include <Eigen/Geometry>

#include "mpcal/error.h"
#include "rotation.h"

namespace mpcal::internal {

GyroSamples SamplesOf(const RecordingView& recording) {
  if (!recording.gyro_samples.empty() &&
      recording.gyro_samples.size() == recording.gyro_samples_time_s.size()) {
    return {recording.gyro_samples_time_s, recording.gyro_samples};
  }
  return {recording.time_s, recording.gyro_radps};
}

std::pair<std::size_t, std::size_t> SamplesWithin(const GyroSamples& samples,
                                                  double from_s,
                                                  double to_s) {
  const auto t = samples.time_s;
  const auto first = std::lower_bound(t.begin(), t.end(), from_s);
  const auto last = std::upper_bound(first, t.end(), to_s);
  return {static_cast<std::size_t>(first - t.begin()),
          static_cast<std::size_t>(last - t.begin())};
}

namespace {

Eigen::Matrix3d CrossMatrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d k;
  k << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return k;
}

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

struct PositionGyro {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  double std = 0.0;  // RMS over the axes of the per-axis sample std
  std::size_t samples = 0;
  double centre_s = 0.0;
};

// The gyroscope's samples within the position's time span: its own stream
// when it was recorded apart, whose scatter is the sensor's noise.
PositionGyro GyroAt(const RecordingView& rec, const StaticInterval& in) {
  PositionGyro p;
  GyroSamples s = SamplesOf(rec);
  auto [first, last] = SamplesWithin(s, rec.time_s[in.begin], rec.time_s[in.end - 1]);
  if (last < first + 2) {  // a position of under two of its own samples
    s = {rec.time_s, rec.gyro_radps};
    first = in.begin, last = in.end;
  }
  const std::span<const Eigen::Vector3d> rate = s.rate;
  const std::size_t n = last - first;
  // Two passes for the scatter: raw counts near 32768 would cancel in a
  // one-pass sum of squares.
  for (std::size_t i = first; i < last; ++i) p.mean += rate[i];
  p.mean /= static_cast<double>(n);
  Eigen::Vector3d sq = Eigen::Vector3d::Zero();
  for (std::size_t i = first; i < last; ++i) sq += (rate[i] - p.mean).cwiseAbs2();
  p.std = n > 1 ? std::sqrt(sq.sum() / 3.0 / static_cast<double>(n - 1)) : 0.0;
  p.samples = n;
  p.centre_s = 0.5 * (rec.time_s[in.begin] + rec.time_s[in.end - 1]);
  return p;
}

// Each tangent component of the mean direction over `samples` samples of
// the position `in`: the accelerometer's noise of the mean over g.
double MeanDirectionVariance(const StaticInterval& in,
                             const Calibration& accel,
                             std::size_t samples) {
  const Eigen::Vector3d std_mps2 = in.std * accel.mps2_per_unit;
  const double n = static_cast<double>(std::max<std::size_t>(samples, 1));
  return std_mps2.squaredNorm() / 3.0 / n / (accel.gravity_mps2 * accel.gravity_mps2);
}

// The direction over `window_s` at the end (or start) of a position, in the
// body frame of its last (first) sample, both as the plain mean of the
// corrected readings and with each sample's specific force carried to the
// edge by the gyroscope (nominal scale `radps_per_unit`, the position's
// bias): the hand sways slowly while it holds a position, and the carried
// mean follows it, at the price of the gyroscope's noise over the window
// (turn_weights.h chooses). Adds the variance of each tangent component of
// the accelerometer's mean to `*variance`.
EdgeDirections EdgeDirection(const RecordingView& rec,
                             const StaticInterval& in,
                             const Calibration& accel,
                             double window_s,
                             bool at_end,
                             const Eigen::Vector3d& gyro_bias,
                             double radps_per_unit,
                             double* variance) {
  const double edge_s =
      at_end ? rec.time_s[in.end - 1] - window_s : rec.time_s[in.begin] + window_s;
  std::size_t first = in.begin;
  std::size_t last = in.end;  // one past
  if (at_end) {
    while (first + 1 < last && rec.time_s[first] < edge_s) ++first;
  } else {
    while (last - 1 > first && rec.time_s[last - 1] > edge_s) --last;
  }
  Eigen::Vector3d carried = Eigen::Vector3d::Zero();
  Eigen::Vector3d still = Eigen::Vector3d::Zero();
  const Calibration::AffineCorrection correct = accel.Affine();
  const bool carry = radps_per_unit > 0.0 && !rec.gyro_radps.empty();
  auto step = [&](std::size_t i) {  // rotation from sample i to i + 1
    const Eigen::Vector3d w =
        (0.5 * (rec.gyro_radps[i] + rec.gyro_radps[i + 1]) - gyro_bias) * radps_per_unit;
    return ExpSO3(w * (rec.time_s[i + 1] - rec.time_s[i]));
  };
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  if (at_end) {
    for (std::size_t i = last; i-- > first;) {  // r = R_{i, anchor}
      if (carry && i + 1 < last) r = step(i) * r;
      const Eigen::Vector3d f = correct(rec.accel[i]);
      carried += r.transpose() * f;
      still += f;
    }
  } else {
    for (std::size_t i = first; i < last; ++i) {  // r = R_{anchor, i}
      if (carry && i > first) r = r * step(i - 1);
      const Eigen::Vector3d f = correct(rec.accel[i]);
      carried += r * f;
      still += f;
    }
  }
  *variance += MeanDirectionVariance(in, accel, last - first);
  return {
      carried.normalized(), still.normalized(), rec.time_s[last - 1] - rec.time_s[first]};
}

}  // namespace

void UseDirections(const Eigen::Vector3d& u_from,
                   const Eigen::Vector3d& u_to,
                   TurnData* turn) {
  turn->u_from = u_from;
  turn->u_to = u_to;
  const Eigen::Vector3d e1 = u_to.unitOrthogonal();
  turn->basis_to.col(0) = e1;
  turn->basis_to.col(1) = u_to.cross(e1);
  turn->cache = TurnCache{};
}

double TurnData::Sigma(double radps_per_unit) const {
  return std::sqrt(direction_variance_rad2 +
                   radps_per_unit * radps_per_unit * gyro_variance_raw2s2);
}

namespace {

void CheckIntervals(const RecordingView& rec, std::span<const StaticInterval> intervals) {
  if (rec.gyro_radps.size() != rec.size() || rec.empty()) {
    throw Error(ErrorKind::kColumns,
                fmt::format("{}: the log has no gyroscope readings", rec.source));
  }
  if (intervals.size() < 2) {
    throw Error(ErrorKind::kSession,
                fmt::format("{}: {} static position(s) give no turn for the gyroscope",
                            rec.source,
                            intervals.size()));
  }
  for (std::size_t k = 0; k < intervals.size(); ++k) {
    const StaticInterval& in = intervals[k];
    if (in.begin >= in.end || in.end > rec.size() ||
        (k > 0 && in.begin < intervals[k - 1].end)) {
      throw Error(ErrorKind::kInput,
                  fmt::format("{}: static position {} lies outside the recording or "
                              "overlaps the one before",
                              rec.source,
                              k + 1));
    }
  }
}

// g-sensitivity: the bias at rest regressed on the specific force (and
// time, so that a drift is not taken for it), b_j = c + G f_j + d t_j. Only
// the part of the bias that is not G f is interpolated across a turn; G f
// follows the specific force sample by sample. Removes G f from `rest_bias`
// when the model keeps it.
void FitGSensitivity(std::span<const StaticInterval> intervals,
                     const Calibration& accel,
                     const std::vector<PositionGyro>& gyro,
                     GSensitivity mode,
                     double min_f,
                     TurnProblem* problem,
                     std::vector<Eigen::Vector3d>* rest_bias) {
  constexpr std::size_t kMinPositionsForG = 15;
  if (mode == GSensitivity::kOff || intervals.size() < kMinPositionsForG) return;
  const auto n = static_cast<Eigen::Index>(intervals.size());
  Eigen::MatrixXd x(n, 5);
  Eigen::MatrixXd y(n, 3);
  const double t0 = gyro.front().centre_s;
  for (Eigen::Index j = 0; j < n; ++j) {
    const auto k = static_cast<std::size_t>(j);
    x.row(j) << 1.0, accel.Correct(intervals[k].mean).transpose(), gyro[k].centre_s - t0;
    y.row(j) = gyro[k].mean.transpose();
  }
  const Eigen::MatrixXd coef = x.colPivHouseholderQr().solve(y);  // 5 × 3
  Eigen::MatrixXd x0(n, 2);
  x0 << x.col(0), x.col(4);
  const Eigen::MatrixXd coef0 = x0.colPivHouseholderQr().solve(y);
  const double rss1 = (y - x * coef).squaredNorm();
  const double rss0 = (y - x0 * coef0).squaredNorm();
  // 9 more parameters (3 per axis), 3·(n − 5) residual degrees of freedom.
  const double dof = 3.0 * static_cast<double>(n - 5);
  problem->g_sensitivity_f = rss1 > 0.0 ? ((rss0 - rss1) / 9.0) / (rss1 / dof) : 0.0;
  if (mode != GSensitivity::kOn && problem->g_sensitivity_f <= min_f) return;
  problem->g_sensitivity_raw_per_mps2 = coef.middleRows(1, 3).transpose();
  problem->g_sensitivity_used = true;
  for (std::size_t k = 0; k < gyro.size(); ++k) {
    (*rest_bias)[k] -=
        problem->g_sensitivity_raw_per_mps2 * accel.Correct(intervals[k].mean);
  }
}

// The points of a turn's integration: the gyroscope's samples from its start
// to its end, the rate interpolated linearly between two samples at an end
// that does not fall on one (a gyroscope recorded apart: the turn's ends are
// the accelerometer's rows), and one sample beyond each end where there is
// one, for the four-point rule. `row` is the accelerometer's row nearest the
// point, for the g-sensitivity.
struct RatePoint {
  double t_s = 0.0;
  Eigen::Vector3d rate = Eigen::Vector3d::Zero();
  std::size_t row = 0;
  bool sample = true;
};

std::vector<RatePoint> TurnPoints(const RecordingView& rec, const TurnData& t) {
  const GyroSamples s = SamplesOf(rec);
  const std::size_t n = s.time_s.size();
  const auto [first, last] = SamplesWithin(s, t.start_s, t.end_s);
  auto row_at = [&](double time) {
    const auto it = std::lower_bound(rec.time_s.begin(), rec.time_s.end(), time);
    std::size_t i = static_cast<std::size_t>(it - rec.time_s.begin());
    if (i == rec.size() || (i > 0 && time - rec.time_s[i - 1] < rec.time_s[i] - time))
      --i;
    return i;
  };
  auto sample = [&](std::size_t j) {
    return RatePoint{s.time_s[j], s.rate[j], row_at(s.time_s[j]), true};
  };
  auto between = [&](double time) {
    const auto it = std::upper_bound(s.time_s.begin(), s.time_s.end(), time);
    const std::size_t k = std::clamp<std::size_t>(
        static_cast<std::size_t>(it - s.time_s.begin()), 1, n - 1);
    const double h = s.time_s[k] - s.time_s[k - 1];
    const double f = h > 0.0 ? std::clamp((time - s.time_s[k - 1]) / h, 0.0, 1.0) : 0.0;
    return RatePoint{
        time, (1.0 - f) * s.rate[k - 1] + f * s.rate[k], row_at(time), false};
  };
  std::vector<RatePoint> points;
  const bool starts_on_sample = first < last && s.time_s[first] == t.start_s;
  const bool ends_on_sample = first < last && s.time_s[last - 1] == t.end_s;
  if (starts_on_sample && first > 0) points.push_back(sample(first - 1));
  if (!starts_on_sample) points.push_back(between(t.start_s));
  for (std::size_t j = first; j < last; ++j) points.push_back(sample(j));
  if (!ends_on_sample) points.push_back(between(t.end_s));
  if (ends_on_sample && last < n) points.push_back(sample(last));
  return points;
}

// The bias-free increments of turn `t` (its begin/end set), the bias
// interpolated between the two positions' rest biases `bias_a`, `bias_b`
// (plus G f sample by sample), and the gyroscope's part of its variance.
void FillIncrements(const RecordingView& rec,
                    const Calibration& accel,
                    const PositionGyro& a,
                    const PositionGyro& b,
                    const Eigen::Vector3d& bias_a,
                    const Eigen::Vector3d& bias_b,
                    const TurnProblem& problem,
                    TurnData* t) {
  const double span_s = std::max(b.centre_s - a.centre_s, 1e-9);
  const Eigen::Matrix3d& g_sens = problem.g_sensitivity_raw_per_mps2;
  const bool with_g = g_sens.any();
  const Calibration::AffineCorrection correct = accel.Affine();
  // Bias-free rates from one sample before the turn to one after it (when
  // the recording has them), for the four-point rule below.
  std::vector<RatePoint> points = TurnPoints(rec, *t);
  std::vector<double> lambdas;
  lambdas.reserve(points.size());
  for (RatePoint& p : points) {
    const double l = std::clamp((p.t_s - a.centre_s) / span_s, 0.0, 1.0);
    Eigen::Vector3d bias = (1.0 - l) * bias_a + l * bias_b;
    if (with_g) bias += g_sens * correct(rec.accel[p.row]);
    p.rate -= bias;
    lambdas.push_back(l);
  }
  // The turn runs from the first point at or after its start to the last
  // at or before its end; the others are the four-point rule's neighbours.
  std::size_t begin = 0;
  while (begin < points.size() && points[begin].t_s < t->start_s) ++begin;
  std::size_t end = points.size();
  while (end > begin && points[end - 1].t_s > t->end_s) --end;
  const auto at = [&](std::size_t k) -> const RatePoint& { return points[k]; };
  t->steps.reserve(end > begin ? end - begin - 1 : 0);
  double lambda_sum = 0.0;
  for (std::size_t k = begin; k + 1 < end; ++k) {
    const double dt = at(k + 1).t_s - at(k).t_s;
    // The angle over the interval by the cubic through the rates at k − 1 …
    // k + 2, dt (−w₋₁ + 13 w₀ + 13 w₁ − w₂)/24, where the trapezoid's
    // dt (w₀ + w₁)/2 errs by dt³ ẅ/12 (on the simulator's turns, which shake
    // by 3° at 3-9 Hz, sampled at 100 Hz, it takes a fifth of the variance
    // the integration adds to a turn; the rest is not the rate's quadrature,
    // and is gone at 400 Hz). Both ends move by the same amount, so the
    // coning term keeps its form; in the middle of a turn every sample still
    // weighs dt, so the white noise is integrated as before. Four samples
    // of the gyroscope's own, not an end interpolated between two.
    Eigen::Vector3d shift = Eigen::Vector3d::Zero();
    if (k > 0 && k + 2 < points.size() && at(k - 1).sample && at(k).sample &&
        at(k + 1).sample && at(k + 2).sample) {
      shift =
          (at(k).rate + at(k + 1).rate - at(k - 1).rate - at(k + 2).rate) * (dt / 24.0);
    }
    t->steps.push_back({at(k).rate * dt + shift, at(k + 1).rate * dt + shift});
    lambda_sum += 0.5 * (lambdas[k] + lambdas[k + 1]);
  }
  const double duration = t->end_s - t->start_s;
  const double lambda = t->steps.empty() ? 0.5 : lambda_sum / t->steps.size();
  // White noise integrated over the turn (angle random walk), and the
  // error of the two measured biases carried through the interpolation.
  const double var_sample = problem.noise_std_raw * problem.noise_std_raw;
  const double arw = var_sample * problem.sample_period_s * duration;
  const double bias = duration * duration *
                      ((1.0 - lambda) * (1.0 - lambda) * var_sample / a.samples +
                       lambda * lambda * var_sample / b.samples);
  t->gyro_variance_raw2s2 = arw + bias;
}

double MedianSamplePeriod(const GyroSamples& s) {
  std::vector<double> periods;
  const std::size_t n = s.time_s.size();
  for (std::size_t i = 1; i < n; i += std::max<std::size_t>(1, n / 1000)) {
    periods.push_back(s.time_s[i] - s.time_s[i - 1]);
  }
  return Median(periods);
}

}  // namespace

TurnProblem BuildTurnProblem(const RecordingView& rec,
                             std::span<const StaticInterval> intervals,
                             const Calibration& accel,
                             double direction_window_s,
                             GSensitivity g_sensitivity,
                             double min_f,
                             double carry_radps_per_unit) {
  CheckIntervals(rec, intervals);
  TurnProblem problem;
  std::vector<PositionGyro> gyro;
  std::vector<double> stds;
  for (const StaticInterval& in : intervals) {
    gyro.push_back(GyroAt(rec, in));
    stds.push_back(gyro.back().std);
    problem.bias_samples.push_back(gyro.back().samples);
    problem.bias_raw.push_back({gyro.back().centre_s, gyro.back().mean});
  }
  // The typical scatter at rest is the white noise; a position far quieter
  // is quantisation of a sensor that does not move, not a better gyroscope.
  problem.noise_std_raw = Median(stds);
  problem.sample_period_s = MedianSamplePeriod(SamplesOf(rec));
  std::vector<Eigen::Vector3d> rest_bias;
  rest_bias.reserve(gyro.size());
  for (const PositionGyro& p : gyro) rest_bias.push_back(p.mean);
  FitGSensitivity(intervals, accel, gyro, g_sensitivity, min_f, &problem, &rest_bias);
  for (const auto& b : rest_bias) problem.bias_without_g_raw += b;
  problem.bias_without_g_raw /= static_cast<double>(rest_bias.size());

  // The turns run between the positions' edges as the sensors show them, not
  // as detection trimmed them; the biases stay the detected positions' means.
  const std::vector<StaticInterval> edges = mpcal::ExtendToMotion(rec, intervals);
  for (std::size_t k = 0; k + 1 < intervals.size(); ++k) {
    TurnData t;
    t.from_position = k;
    t.begin = edges[k].end - 1;
    t.end = edges[k + 1].begin;
    t.start_s = rec.time_s[t.begin];
    t.end_s = rec.time_s[t.end];
    if (direction_window_s > 0.0) {
      t.from = EdgeDirection(rec,
                             edges[k],
                             accel,
                             direction_window_s,
                             true,
                             gyro[k].mean,
                             carry_radps_per_unit,
                             &t.direction_variance_rad2);
      t.to = EdgeDirection(rec,
                           edges[k + 1],
                           accel,
                           direction_window_s,
                           false,
                           gyro[k + 1].mean,
                           carry_radps_per_unit,
                           &t.direction_variance_rad2);
    } else {
      const Eigen::Vector3d from = accel.Correct(intervals[k].mean).normalized();
      const Eigen::Vector3d to = accel.Correct(intervals[k + 1].mean).normalized();
      t.from = {from, from, 0.0};
      t.to = {to, to, 0.0};
      t.direction_variance_rad2 =
          MeanDirectionVariance(intervals[k], accel, intervals[k].samples()) +
          MeanDirectionVariance(intervals[k + 1], accel, intervals[k + 1].samples());
    }
    FillIncrements(
        rec, accel, gyro[k], gyro[k + 1], rest_bias[k], rest_bias[k + 1], problem, &t);
    UseDirections(t.from.carried, t.to.carried, &t);
    problem.turns.push_back(std::move(t));
  }
  return problem;
}

namespace {

// The entry of `entries` at the key `matches`, computed by `fill` into the
// least recently used one when absent; `next` is the least recently used.
template <typename Entry, typename Matches, typename Fill>
const Entry& Lookup(std::array<Entry, 2>& entries,
                    std::size_t& next,
                    Matches matches,
                    Fill fill) {
  for (std::size_t i = 0; i < entries.size(); ++i) {
    if (entries[i].valid && matches(entries[i])) {
      next = 1 - i;
      return entries[i];
    }
  }
  Entry& entry = entries[next];
  fill(entry);
  entry.valid = true;
  next = 1 - next;
  return entry;
}

// The cache entry of `turn` at `m`, computed (with the Jacobian) when absent.
const TurnCache::Full& FullAt(const TurnData& turn, const Eigen::Matrix3d& m) {
  return Lookup(
      turn.cache.full,
      turn.cache.next_full,
      [&](const TurnCache::Full& e) { return e.m == m; },
      [&](TurnCache::Full& e) {
        e.m = m;
        e.rotation = RotationOverTurn(m, turn.steps, &e.d_theta);
      });
}

const TurnCache::Along& AlongAt(const TurnData& turn,
                                const Eigen::Matrix3d& m,
                                const Eigen::Matrix3d& direction) {
  return Lookup(
      turn.cache.along,
      turn.cache.next_along,
      [&](const TurnCache::Along& e) { return e.m == m && e.direction == direction; },
      [&](TurnCache::Along& e) {
        e.m = m;
        e.direction = direction;
        e.rotation = RotationOverTurnAlong(m, turn.steps, direction, &e.d_theta);
      });
}

// The residual and the map of δθ to it, at the rotation `r`.
Eigen::Matrix<double, 2, 3> Residual(const TurnData& turn,
                                     const Eigen::Matrix3d& r,
                                     Eigen::Vector2d* residual) {
  const Eigen::Vector3d carried = r.transpose() * turn.u_from;
  if (residual != nullptr) *residual = turn.basis_to.transpose() * carried;
  // R' = R exp([δθ]×) carries u to exp(−[δθ]×) Rᵀu ≈ Rᵀu + [Rᵀu]× δθ.
  return turn.basis_to.transpose() * CrossMatrix(carried);
}

}  // namespace

Eigen::Matrix3d TurnResidual(const TurnData& turn,
                             const Eigen::Matrix3d& m,
                             Eigen::Vector2d* residual,
                             Eigen::Matrix<double, 2, 9>* jacobian) {
  const TurnCache::Full& entry = FullAt(turn, m);
  const Eigen::Matrix<double, 2, 3> d_residual = Residual(turn, entry.rotation, residual);
  if (jacobian != nullptr) *jacobian = d_residual * entry.d_theta;
  return entry.rotation;
}

Eigen::Matrix3d TurnResidualAlong(const TurnData& turn,
                                  const Eigen::Matrix3d& m,
                                  const Eigen::Matrix3d& direction,
                                  Eigen::Vector2d* residual,
                                  Eigen::Vector2d* derivative) {
  const TurnCache::Along& entry = AlongAt(turn, m, direction);
  const Eigen::Matrix<double, 2, 3> d_residual = Residual(turn, entry.rotation, residual);
  if (derivative != nullptr) *derivative = d_residual * entry.d_theta;
  return entry.rotation;
}

double TurnTilt(const TurnData& turn, const Eigen::Matrix3d& rotation) {
  const Eigen::Vector3d carried = rotation.transpose() * turn.u_from;
  return std::atan2(carried.cross(turn.u_to).norm(), carried.dot(turn.u_to));
}

}  // namespace mpcal::internal
