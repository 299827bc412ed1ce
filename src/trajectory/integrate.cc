// Still test, strapdown integration, alignment and metrics.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include <fmt/format.h>

#include "mpcal/count.h"
#include "mpcal/error.h"
#include "mpcal/plausible.h"
#include "mpcal/trajectory.h"

namespace mpcal {
namespace {

constexpr double kQuietQuantile = 0.10;

void ThrowIfInvalid(const std::string& problem, std::string_view what) {
  if (!problem.empty()) {
    throw Error(ErrorKind::kOption, fmt::format("{}: {}", what, problem));
  }
}

// Centred moving standard deviation (norm over the three axes) with the
// window clipped at the ends, in O(n) from prefix sums.
std::vector<double> MovingStd(std::span<const Eigen::Vector3d> x, std::size_t half) {
  const std::size_t n = x.size();
  std::vector<Eigen::Vector3d> s1(n + 1, Eigen::Vector3d::Zero());
  std::vector<Eigen::Vector3d> s2(n + 1, Eigen::Vector3d::Zero());
  // Subtract the first sample so that the sums of squares stay small
  // (readings near 9.8 m/s² would lose digits otherwise).
  const Eigen::Vector3d shift = x.empty() ? Eigen::Vector3d::Zero() : x[0];
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d d = x[i] - shift;
    s1[i + 1] = s1[i] + d;
    s2[i + 1] = s2[i] + d.cwiseProduct(d);
  }
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t a = i >= half ? i - half : 0;
    const std::size_t b = std::min(n, i + half + 1);
    const double m = static_cast<double>(b - a);
    const Eigen::Vector3d mean = (s1[b] - s1[a]) / m;
    const Eigen::Vector3d var = (s2[b] - s2[a]) / m - mean.cwiseProduct(mean);
    out[i] = std::sqrt(std::max(0.0, var.sum()));
  }
  return out;
}

// Norm of the centred moving mean of x − centre.
std::vector<double> MovingMeanOffset(std::span<const Eigen::Vector3d> x,
                                     const Eigen::Vector3d& centre,
                                     std::size_t half) {
  const std::size_t n = x.size();
  std::vector<Eigen::Vector3d> s1(n + 1, Eigen::Vector3d::Zero());
  for (std::size_t i = 0; i < n; ++i) s1[i + 1] = s1[i] + (x[i] - centre);
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t a = i >= half ? i - half : 0;
    const std::size_t b = std::min(n, i + half + 1);
    out[i] = ((s1[b] - s1[a]) / static_cast<double>(b - a)).norm();
  }
  return out;
}

double Quantile(std::vector<double> values, double q) {
  const auto k = static_cast<std::ptrdiff_t>(q * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return values[static_cast<std::size_t>(k)];
}

Eigen::Vector3d Horizontal(const Eigen::Vector3d& v) { return {v.x(), v.y(), 0.0}; }

// Levelling and the gyroscope's bias need the log to start at rest for
// options.min_initial_rest_s; z-up needs no levelling (the advice).
void CheckInitialRest(std::span<const double> time_s,
                      std::size_t rest_end,
                      bool gyro_used,
                      const IntegrateOptions& options) {
  const double rest_s = rest_end > 0 ? time_s[rest_end - 1] - time_s[0] : 0.0;
  const bool needs_rest = options.mount == MountMode::kLevel || gyro_used;
  if (!needs_rest || (rest_end > 0 && rest_s >= options.min_initial_rest_s)) return;
  Advice advice;
  if (options.mount == MountMode::kLevel) advice.settings = {{Option::kMount, "z-up"}};
  throw Error(
      ErrorKind::kSession,
      fmt::format("the log starts with {:.2f} s at rest, but {} needs at least "
                  "{} s still at the start; record a rest before walking",
                  rest_s,
                  options.mount == MountMode::kLevel ? "levelling" : "the gyroscope bias",
                  options.min_initial_rest_s),
      advice);
}

}  // namespace

std::string_view ToString(MountMode mode) {
  return mode == MountMode::kZUp ? "z-up" : "level";
}

std::optional<MountMode> ParseMountMode(std::string_view name) {
  if (name == "level") return MountMode::kLevel;
  if (name == "z-up" || name == "zup") return MountMode::kZUp;
  return std::nullopt;
}

std::string StillOptions::Validate() const {
  if (!(window_s > 0.0) || !std::isfinite(window_s)) return "window_s must be positive";
  if (!(threshold_factor >= 1.0) || !std::isfinite(threshold_factor)) {
    return "threshold_factor must be at least 1";
  }
  if (!(min_accel_threshold_mps2 >= 0.0)) return "min_accel_threshold_mps2 must be >= 0";
  if (!(min_gyro_threshold_radps >= 0.0)) return "min_gyro_threshold_radps must be >= 0";
  if (!(min_still_s >= 0.0)) return "min_still_s must be >= 0";
  return "";
}

std::string IntegrateOptions::Validate() const {
  if (!IsPlausibleGravity(gravity_mps2)) {
    return fmt::format("gravity_mps2 must be a gravity magnitude in m/s2 ({}..{})",
                       kMinGravityMps2,
                       kMaxGravityMps2);
  }
  if (!(min_initial_rest_s >= 0.0)) return "min_initial_rest_s must be >= 0";
  return "";
}

StillResult DetectStill(std::span<const double> time_s,
                        std::span<const Eigen::Vector3d> specific_force_mps2,
                        std::span<const Eigen::Vector3d> gyro_radps,
                        const StillOptions& options) {
  ThrowIfInvalid(options.Validate(), "still test options");
  const std::size_t n = time_s.size();
  if (specific_force_mps2.size() != n ||
      (!gyro_radps.empty() && gyro_radps.size() != n)) {
    throw Error(ErrorKind::kInput,
                "still test: time, accelerometer and gyroscope have different lengths");
  }
  if (n < 3)
    throw Error(
        ErrorKind::kInput,
        fmt::format("still test: {} too few", Count(n, "sample is", "samples are")));
  const double span_s = time_s.back() - time_s.front();
  const double dt = span_s / static_cast<double>(n - 1);
  if (!(dt > 0.0))
    throw Error(ErrorKind::kInput, "still test: the sample times do not increase");
  if (span_s < options.window_s) {
    throw Error(
        ErrorKind::kInput,
        fmt::format("still test: the log ({:.2f} s) is shorter than one window ({} s)",
                    span_s,
                    options.window_s));
  }
  const auto half =
      static_cast<std::size_t>(std::max(1.0, std::round(options.window_s / dt / 2)));

  StillResult result;
  result.accel_std_mps2 = MovingStd(specific_force_mps2, half);
  const std::vector<double>& a_std = result.accel_std_mps2;
  result.accel_threshold_mps2 =
      std::max(options.min_accel_threshold_mps2,
               options.threshold_factor * Quantile(a_std, kQuietQuantile));
  std::vector<double> g_std;
  if (!gyro_radps.empty()) {
    // A turn at a steady rate has no spread: measure the gyroscope against
    // its typical (median) reading, which is its bias when the device is
    // mostly not turning.
    Eigen::Vector3d median;
    for (int axis = 0; axis < 3; ++axis) {
      std::vector<double> v(n);
      for (std::size_t i = 0; i < n; ++i) v[i] = gyro_radps[i][axis];
      median[axis] = Quantile(std::move(v), 0.5);
    }
    g_std = MovingStd(gyro_radps, half);
    const std::vector<double> g_off = MovingMeanOffset(gyro_radps, median, half);
    for (std::size_t i = 0; i < n; ++i) g_std[i] = std::hypot(g_std[i], g_off[i]);
    result.gyro_threshold_radps =
        std::max(options.min_gyro_threshold_radps,
                 options.threshold_factor * Quantile(g_std, kQuietQuantile));
  }
  result.still.assign(n, false);
  for (std::size_t i = 0; i < n; ++i) {
    result.still[i] = a_std[i] < result.accel_threshold_mps2 &&
                      (g_std.empty() || g_std[i] < result.gyro_threshold_radps);
  }
  // Runs of still samples; too short ones are motion (a foot at the top of a
  // step looks still for a moment).
  std::size_t i = 0;
  while (i < n) {
    if (!result.still[i]) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < n && result.still[j]) ++j;
    if (time_s[j - 1] - time_s[i] < options.min_still_s) {
      std::fill(result.still.begin() + static_cast<std::ptrdiff_t>(i),
                result.still.begin() + static_cast<std::ptrdiff_t>(j),
                false);
    } else {
      result.intervals.emplace_back(i, j);
    }
    i = j;
  }
  if (!result.intervals.empty() && result.intervals.front().first == 0) {
    result.initial_rest_end = result.intervals.front().second;
  }
  return result;
}

IntegrationResult IntegrateTrajectory(
    std::span<const double> time_s,
    std::span<const Eigen::Vector3d> specific_force_mps2,
    std::span<const Eigen::Vector3d> gyro_radps,
    const StillResult& still,
    const IntegrateOptions& options) {
  ThrowIfInvalid(options.Validate(), "integration options");
  const std::size_t n = time_s.size();
  if (specific_force_mps2.size() != n || still.still.size() != n ||
      (!gyro_radps.empty() && gyro_radps.size() != n)) {
    throw Error(
        ErrorKind::kInput,
        "integration: time, readings, gyroscope and still flags differ in length");
  }
  if (n < 2) throw Error(ErrorKind::kInput, "integration: fewer than two samples");

  IntegrationResult result;
  result.gyro_used = options.use_gyro && !gyro_radps.empty();
  const std::size_t rest_end = still.initial_rest_end;
  CheckInitialRest(time_s, rest_end, result.gyro_used, options);
  if (rest_end > 0) {
    Eigen::Vector3d f_mean = Eigen::Vector3d::Zero();
    Eigen::Vector3d w_mean = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < rest_end; ++i) {
      f_mean += specific_force_mps2[i];
      if (result.gyro_used) w_mean += gyro_radps[i];
    }
    f_mean /= static_cast<double>(rest_end);
    if (result.gyro_used) result.gyro_bias_radps = w_mean / static_cast<double>(rest_end);
    if (options.mount == MountMode::kLevel) {
      // The rotation taking the measured "up" onto the navigation z axis.
      result.R_nav_sensor =
          Eigen::Quaterniond::FromTwoVectors(f_mean, Eigen::Vector3d::UnitZ())
              .toRotationMatrix();
    }
  }
  result.initial_tilt_rad = std::acos(std::clamp(result.R_nav_sensor(2, 2), -1.0, 1.0));

  const Eigen::Vector3d gravity(0.0, 0.0, options.gravity_mps2);
  Eigen::Quaterniond q(result.R_nav_sensor);
  result.path.time_s.assign(time_s.begin(), time_s.end());
  result.path.position_m.assign(n, Eigen::Vector3d::Zero());
  result.velocity_mps.assign(n, Eigen::Vector3d::Zero());
  Eigen::Vector3d a_prev = q * specific_force_mps2[0] - gravity;
  for (std::size_t k = 1; k < n; ++k) {
    const double dt = time_s[k] - time_s[k - 1];
    if (result.gyro_used) {
      const Eigen::Vector3d w =
          0.5 * (gyro_radps[k - 1] + gyro_radps[k]) - result.gyro_bias_radps;
      const double angle = w.norm() * dt;
      if (angle > 0.0) {
        q = (q * Eigen::Quaterniond(Eigen::AngleAxisd(angle, w.normalized())))
                .normalized();
      }
    }
    const Eigen::Vector3d a = q * specific_force_mps2[k] - gravity;
    Eigen::Vector3d v = result.velocity_mps[k - 1] + 0.5 * (a_prev + a) * dt;
    if (options.zero_velocity_updates && still.still[k]) {
      v.setZero();
      ++result.zero_velocity_samples;
    }
    result.velocity_mps[k] = v;
    result.path.position_m[k] =
        result.path.position_m[k - 1] + 0.5 * (result.velocity_mps[k - 1] + v) * dt;
    a_prev = a;
  }
  return result;
}

Eigen::Vector3d TimedPath::At(double t) const {
  // Release builds drop asserts: an empty path would read past its end.
  if (time_s.empty() || position_m.size() != time_s.size()) {
    throw Error(ErrorKind::kInput,
                fmt::format("a path of {} times and {} positions has no position at "
                            "{} s",
                            time_s.size(),
                            position_m.size(),
                            t));
  }
  if (t <= time_s.front()) return position_m.front();
  if (t >= time_s.back()) return position_m.back();
  const auto it = std::upper_bound(time_s.begin(), time_s.end(), t);
  const auto k = static_cast<std::size_t>(it - time_s.begin());
  const double w = (t - time_s[k - 1]) / (time_s[k] - time_s[k - 1]);
  return (1.0 - w) * position_m[k - 1] + w * position_m[k];
}

double AlignToReference(TimedPath& path,
                        const TimedPath& reference,
                        double t_start,
                        double t_heading) {
  const Eigen::Vector3d p0 = path.At(t_start);
  const Eigen::Vector3d r0 = reference.At(t_start);
  const Eigen::Vector3d dp = Horizontal(path.At(t_heading) - p0);
  const Eigen::Vector3d dr = Horizontal(reference.At(t_heading) - r0);
  double angle = 0.0;
  if (dp.norm() > 0.0 && dr.norm() > 0.0) {
    angle = std::atan2(dr.y(), dr.x()) - std::atan2(dp.y(), dp.x());
    angle = std::remainder(angle, 2.0 * M_PI);
  }
  const Eigen::Matrix3d rot =
      Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (Eigen::Vector3d& p : path.position_m) p = rot * (p - p0) + r0;
  return angle;
}

double HorizontalPathLength(std::span<const Eigen::Vector3d> positions_m, double step_m) {
  // A NaN step would count no step at all: a length of (almost) zero.
  if (!(step_m >= 0.0) || !std::isfinite(step_m)) {
    throw Error(ErrorKind::kOption,
                fmt::format("the path length's step must be >= 0 m (got {})", step_m));
  }
  if (positions_m.empty()) return 0.0;
  double length = 0.0;
  Eigen::Vector3d last = Horizontal(positions_m.front());
  for (const Eigen::Vector3d& p : positions_m) {
    const double d = (Horizontal(p) - last).norm();
    if (d >= step_m) {
      length += d;
      last = Horizontal(p);
    }
  }
  // The last stretch shorter than a step still belongs to the path.
  length += (Horizontal(positions_m.back()) - last).norm();
  return length;
}

PathMetrics ComparePaths(const TimedPath& path,
                         const TimedPath& reference,
                         double step_m) {
  PathMetrics m;
  if (reference.empty() || path.empty()) return m;
  std::vector<Eigen::Vector3d> sampled;
  sampled.reserve(reference.size());
  double sum_sq = 0.0;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    sampled.push_back(path.At(reference.time_s[i]));
    const double d = Horizontal(sampled.back() - reference.position_m[i]).norm();
    sum_sq += d * d;
    m.horizontal_max_m = std::max(m.horizontal_max_m, d);
  }
  m.horizontal_rms_m = std::sqrt(sum_sq / static_cast<double>(reference.size()));
  m.start_end_distance_m = Horizontal(sampled.back() - sampled.front()).norm();
  m.path_length_m = HorizontalPathLength(sampled, step_m);
  return m;
}

}  // namespace mpcal
