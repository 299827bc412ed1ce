#include "mpcal/gyro_log.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "mpcal/error.h"
#include "mpcal/units.h"

namespace mpcal {

Recording ReadGyroLog(const std::string& path, LogOptions options) {
  options.gyroscope_only = true;
  // The reader bounds each reading by its units (plausible.h): a gyroscope's
  // counts may span the ADC's range, a rate in rad/s or deg/s stays far
  // below the bound of m/s².
  options.units = options.gyro_in_counts ? AccelUnits::kCounts : AccelUnits::kMps2;
  return ReadLog(path, options);
}

namespace {

double MedianPeriodS(const std::vector<double>& t) {
  if (t.size() < 2) return 0.0;
  std::vector<double> steps;
  const std::size_t stride = std::max<std::size_t>(1, t.size() / 4096);
  for (std::size_t i = 1; i < t.size(); i += stride) steps.push_back(t[i] - t[i - 1]);
  auto mid = steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2);
  std::nth_element(steps.begin(), mid, steps.end());
  return *mid;
}

bool SameSamples(const Recording& a, const Recording& b, double offset_s) {
  const std::size_t n = a.size();
  if (b.size() != n) return false;
  const double period =
      n > 1 ? (a.time_s.back() - a.time_s.front()) / static_cast<double>(n - 1) : 1.0;
  // A hundredth of a sample: the two files were written by one logger.
  const double tolerance = 0.01 * period;
  for (std::size_t i = 0; i < n; ++i) {
    if (std::abs(b.time_s[i] + offset_s - a.time_s[i]) > tolerance) return false;
  }
  return true;
}

// The angle the gyroscope's rate, linear between its samples, turns through
// from its first sample to each time asked for, asked in increasing order.
class AngleOfRate {
 public:
  AngleOfRate(const std::vector<double>& t, const std::vector<Eigen::Vector3d>& w)
      : t_(t), w_(w), sum_(t.size(), Eigen::Vector3d::Zero()) {
    for (std::size_t k = 1; k < t.size(); ++k) {
      sum_[k] = sum_[k - 1] + 0.5 * (w[k - 1] + w[k]) * (t[k] - t[k - 1]);
    }
  }
  Eigen::Vector3d At(double time) {
    while (k_ + 2 < t_.size() && t_[k_ + 1] <= time) ++k_;
    const double h = t_[k_ + 1] - t_[k_];
    const double tau = std::clamp(time - t_[k_], 0.0, h);
    return sum_[k_] + w_[k_] * tau + (w_[k_ + 1] - w_[k_]) * (tau * tau / (2.0 * h));
  }
  Eigen::Vector3d RateAt(double time) {
    At(time);
    const double h = t_[k_ + 1] - t_[k_];
    const double f = std::clamp((time - t_[k_]) / h, 0.0, 1.0);
    return (1.0 - f) * w_[k_] + f * w_[k_ + 1];
  }

 private:
  const std::vector<double>& t_;
  const std::vector<Eigen::Vector3d>& w_;
  std::vector<Eigen::Vector3d> sum_;
  std::size_t k_ = 0;
};

// The gyroscope's times on the accelerometer's clock.
std::vector<double> GyroTimesOnAccelClock(const Recording& gyro, double offset_s) {
  std::vector<double> t(gyro.time_s);
  for (double& v : t) v += offset_s;
  return t;
}

[[noreturn]] void ThrowNoOverlap(const Recording& rec,
                                 const Recording& gyro,
                                 const StreamMerge& m) {
  throw Error(
      ErrorKind::kInput,
      fmt::format("{} spans {:.6f} to {:.6f} s and {} spans {:.6f} to {:.6f} s: the "
                  "two streams do not overlap in time (recorded apart, or on clocks "
                  "that do not agree), so the gyroscope cannot be put on the "
                  "accelerometer's rows",
                  gyro.source,
                  m.gyro_first_s,
                  m.gyro_last_s,
                  rec.source,
                  m.accel_first_s,
                  m.accel_last_s));
}

// The rows kept: [first, last] within the gyroscope's span.
void Resample(Recording& rec,
              const Recording& gyro,
              const std::vector<double>& tg,
              StreamMerge& m) {
  const auto& ta = rec.time_s;
  const auto lo = std::lower_bound(ta.begin(), ta.end(), tg.front());
  const auto hi = std::upper_bound(ta.begin(), ta.end(), tg.back());
  if (hi - lo < 2 || tg.size() < 2) ThrowNoOverlap(rec, gyro, m);
  const auto first = static_cast<std::size_t>(lo - ta.begin());
  const auto last = static_cast<std::size_t>(hi - ta.begin()) - 1;
  m.rows_dropped_before = first;
  m.rows_dropped_after = ta.size() - 1 - last;

  AngleOfRate angle(tg, gyro.accel);
  std::vector<Eigen::Vector3d> rates;
  rates.reserve(last - first + 1);
  double from = ta[first];
  Eigen::Vector3d angle_from = angle.At(from);
  for (std::size_t i = first; i <= last; ++i) {
    const double to = i < last ? 0.5 * (ta[i] + ta[i + 1]) : ta[i];
    const Eigen::Vector3d angle_to = angle.At(to);
    rates.push_back(to > from ? ((angle_to - angle_from) / (to - from)).eval()
                              : angle.RateAt(ta[i]));
    from = to, angle_from = angle_to;
  }
  for (std::size_t k = 1; k < tg.size(); ++k) {
    const double step = tg[k] - tg[k - 1];
    if (tg[k] > ta[first] && tg[k - 1] < ta[last] && step > m.gyro_gap_s) {
      m.gyro_gap_s = step, m.gyro_gap_at_s = tg[k - 1];
    }
  }
  const auto begin = static_cast<std::ptrdiff_t>(first);
  const auto end = static_cast<std::ptrdiff_t>(last + 1);
  rec.time_s = std::vector<double>(ta.begin() + begin, ta.begin() + end);
  rec.accel =
      std::vector<Eigen::Vector3d>(rec.accel.begin() + begin, rec.accel.begin() + end);
  rec.gyro_radps = std::move(rates);
}

void Judge(StreamMerge& m) {
  const double overlap =
      std::min(m.accel_last_s, m.gyro_last_s) - std::max(m.accel_first_s, m.gyro_first_s);
  const double longer =
      std::max(m.accel_last_s - m.accel_first_s, m.gyro_last_s - m.gyro_first_s);
  if (overlap < 0.9 * longer) m.findings.push_back(StreamFinding::kSpansDiffer);
  const double gyro_period = m.gyro_rate_hz > 0.0 ? 1.0 / m.gyro_rate_hz : 0.0;
  const double accel_period = m.accel_rate_hz > 0.0 ? 1.0 / m.accel_rate_hz : 0.0;
  if (m.gyro_gap_s > 5.0 * gyro_period && m.gyro_gap_s > accel_period) {
    m.findings.push_back(StreamFinding::kGyroGap);
  }
}

}  // namespace

StreamMerge MergeGyroLog(Recording& recording,
                         const Recording& gyro_log,
                         GyroUnits units) {
  if (!recording.gyro_radps.empty()) {
    throw Error(
        fmt::format("{} already has gyroscope columns; give the gyroscope either in "
                    "it or in {}, not both",
                    recording.source,
                    gyro_log.source));
  }
  if (recording.empty() || gyro_log.empty()) {
    throw Error(ErrorKind::kInput,
                fmt::format("{} has no rows",
                            recording.empty() ? recording.source : gyro_log.source));
  }
  const double offset_s =
      static_cast<double>(gyro_log.time_origin_ns - recording.time_origin_ns) * 1e-9;
  StreamMerge m;
  const double accel_period = MedianPeriodS(recording.time_s);
  const double gyro_period = MedianPeriodS(gyro_log.time_s);
  m.accel_rate_hz = accel_period > 0.0 ? 1.0 / accel_period : 0.0;
  m.gyro_rate_hz = gyro_period > 0.0 ? 1.0 / gyro_period : 0.0;
  m.accel_first_s = recording.time_s.front(), m.accel_last_s = recording.time_s.back();
  m.gyro_first_s = gyro_log.time_s.front() + offset_s;
  m.gyro_last_s = gyro_log.time_s.back() + offset_s;
  if (SameSamples(recording, gyro_log, offset_s)) {
    recording.gyro_radps = gyro_log.accel;
  } else {
    m.resampled = true;
    std::vector<double> tg = GyroTimesOnAccelClock(gyro_log, offset_s);
    Resample(recording, gyro_log, tg, m);
    Judge(m);
    recording.gyro_samples_time_s = std::move(tg);
    recording.gyro_samples = gyro_log.accel;
  }
  const double scale = units == GyroUnits::kCounts ? 1.0 : *FixedRadpsPerUnit(units);
  for (Eigen::Vector3d& v : recording.gyro_radps) v *= scale;
  for (Eigen::Vector3d& v : recording.gyro_samples) v *= scale;
  recording.gyro_units =
      units == GyroUnits::kCounts ? GyroUnits::kCounts : GyroUnits::kRadps;
  recording.gyro_log_units = units;
  return m;
}

std::string Describe(StreamFinding finding,
                     const StreamMerge& m,
                     const std::string& accel,
                     const std::string& gyro) {
  switch (finding) {
    case StreamFinding::kSpansDiffer:
      return fmt::format(
          "{} spans {:.3f} to {:.3f} s but {} spans {:.3f} to {:.3f} s: one stream is "
          "much shorter, or their clocks disagree; only the overlap is calibrated",
          accel,
          m.accel_first_s,
          m.accel_last_s,
          gyro,
          m.gyro_first_s,
          m.gyro_last_s);
    case StreamFinding::kGyroGap:
      return fmt::format(
          "{} has a gap of {:.3f} s at {:.3f} s ({:.0f} of its periods): the rates "
          "across it are interpolated, so a turn made during it is not measured",
          gyro,
          m.gyro_gap_s,
          m.gyro_gap_at_s,
          m.gyro_gap_s * m.gyro_rate_hz);
  }
  return {};
}

}  // namespace mpcal
