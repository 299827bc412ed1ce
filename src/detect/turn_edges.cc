// Where the turns start and stop (detect.h, ExtendToMotion): the two
// sensors, sample by sample, beside each detected position.
#include "mpcal/detect.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Core>

namespace mpcal {
namespace {

// The window ahead of an edge (kMotionEdgeWindowS) in samples, at least.
constexpr std::size_t kMinEdgeWindow = 3;
// χ² with 6 degrees of freedom at 0.01 %: a position stops growing at the
// first window the noise alone would reach once in ten thousand, so that a
// still stretch of half a second (50 windows) stops short about once in 200.
// A false stop costs only the samples not added; a step into the motion
// would cost a bias.
constexpr double kStillChi2 = 27.856;
// A turn starts gently (a hand, like a minimum-jerk profile, speeds up as t²
// or slower), below the noise of one window for a few of them: the edge is
// put back by two windows from the first window that shows the motion, so
// that no rotation is left out of the turn.
constexpr std::size_t kBackOffWindows = 2;

struct Rest {
  Eigen::Vector3d gyro_mean = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_std = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_mean = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_std = Eigen::Vector3d::Zero();
};

Rest RestOf(const RecordingView& rec, const StaticInterval& in) {
  Rest r;
  r.accel_mean = in.mean;
  r.accel_std = in.std;
  const auto n = static_cast<double>(in.end - in.begin);
  for (std::size_t i = in.begin; i < in.end; ++i) r.gyro_mean += rec.gyro_radps[i];
  r.gyro_mean /= n;
  for (std::size_t i = in.begin; i < in.end; ++i) {
    r.gyro_std += (rec.gyro_radps[i] - r.gyro_mean).cwiseAbs2();
  }
  r.gyro_std = (r.gyro_std / std::max(n - 1.0, 1.0)).cwiseSqrt();
  return r;
}

Eigen::Vector3d MedianPerAxis(const std::vector<Eigen::Vector3d>& v) {
  Eigen::Vector3d out;
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> values;
    values.reserve(v.size());
    for (const Eigen::Vector3d& x : v) values.push_back(x[axis]);
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    out[axis] = values[values.size() / 2];
  }
  return out;
}

// Σ (departure / scatter)² over the axes. An axis whose readings never
// moved at rest (scatter 0) is at rest only where they still have not.
double Chi2(const Eigen::Vector3d& departure, const Eigen::Vector3d& scatter) {
  double sum = 0.0;
  for (int axis = 0; axis < 3; ++axis) {
    if (scatter[axis] > 0.0) {
      sum += std::pow(departure[axis] / scatter[axis], 2);
    } else if (departure[axis] != 0.0) {
      return std::numeric_limits<double>::infinity();
    }
  }
  return sum;
}

// Whether samples [first, last) are at rest as `rest` describes it: the χ²
// of their means' departures over the six axes.
bool AtRest(const RecordingView& rec,
            const Rest& rest,
            std::size_t first,
            std::size_t last) {
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel = Eigen::Vector3d::Zero();
  for (std::size_t i = first; i < last; ++i) {
    gyro += rec.gyro_radps[i];
    accel += rec.accel[i];
  }
  const auto n = static_cast<double>(last - first);
  return n * (Chi2(gyro / n - rest.gyro_mean, rest.gyro_std) +
              Chi2(accel / n - rest.accel_mean, rest.accel_std)) <=
         kStillChi2;
}

}  // namespace

std::vector<StaticInterval> ExtendToMotion(const RecordingView& rec,
                                           std::span<const StaticInterval> intervals) {
  std::vector<StaticInterval> out(intervals.begin(), intervals.end());
  if (intervals.empty() || rec.gyro_radps.size() != rec.size() || rec.size() < 2)
    return out;
  std::vector<Rest> rests;
  rests.reserve(intervals.size());
  for (const StaticInterval& in : intervals) rests.push_back(RestOf(rec, in));
  // A position quieter than the median is a quantised sensor that did not
  // move, not a quieter one: its own scatter would stop it at the first count.
  std::vector<Eigen::Vector3d> gyro_stds;
  std::vector<Eigen::Vector3d> accel_stds;
  gyro_stds.reserve(rests.size());
  accel_stds.reserve(rests.size());
  for (const Rest& r : rests) {
    gyro_stds.push_back(r.gyro_std);
    accel_stds.push_back(r.accel_std);
  }
  const Eigen::Vector3d gyro_floor = MedianPerAxis(gyro_stds);
  const Eigen::Vector3d accel_floor = MedianPerAxis(accel_stds);
  for (Rest& r : rests) {
    r.gyro_std = r.gyro_std.cwiseMax(gyro_floor);
    r.accel_std = r.accel_std.cwiseMax(accel_floor);
  }
  const double span_s = rec.time_s.back() - rec.time_s.front();
  const double period_s = span_s / static_cast<double>(rec.size() - 1);
  const auto w =
      std::max(kMinEdgeWindow,
               static_cast<std::size_t>(std::lround(kMotionEdgeWindowS / period_s)));
  std::size_t floor_index = 0;  // the previous position's extended end
  for (std::size_t k = 0; k < out.size(); ++k) {
    StaticInterval& in = out[k];
    std::size_t begin = in.begin;
    while (begin >= floor_index + w && AtRest(rec, rests[k], begin - w, begin)) --begin;
    in.begin = std::min(begin + kBackOffWindows * w, in.begin);
    const std::size_t limit = k + 1 < out.size() ? intervals[k + 1].begin : rec.size();
    std::size_t end = in.end;
    while (end + w <= limit && AtRest(rec, rests[k], end, end + w)) ++end;
    in.end = std::max(end - std::min(end, kBackOffWindows * w), in.end);
    in.start_s = rec.time_s[in.begin];
    in.end_s = rec.time_s[in.end - 1];
    floor_index = in.end;
  }
  return out;
}

}  // namespace mpcal
