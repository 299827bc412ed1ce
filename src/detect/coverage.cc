#include "mpcal/coverage.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>
#include <Eigen/Dense>

#include "mpcal/error.h"

namespace mpcal {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;

double AngleDeg(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  return std::acos(std::clamp(u.dot(v), -1.0, 1.0)) * kRadToDeg;
}

// Below this the model's parameters are not all determined by the positions;
// below kWeakObservability they are, but some poorly. Both are ratios of
// singular values of a design built from unit vectors: the 26 cube
// directions give about 0.25 (9 parameters), a generic set of 10 about 0.02,
// positions in one plane 1e-16.
constexpr double kNoObservability = 1e-3;
constexpr double kWeakObservability = 0.02;

std::string SignedAxes(const Eigen::Vector3d& v) {
  std::string s;
  static constexpr char kAxis[] = {'x', 'y', 'z'};
  for (int i = 0; i < 3; ++i) {
    if (std::abs(v[i]) > 1e-9) {
      s += v[i] > 0 ? '+' : '-';
      s += kAxis[i];
    }
  }
  return s;
}

std::vector<CanonicalDirection> MakeCanonical() {
  std::vector<CanonicalDirection> out;
  auto add = [&out](CanonicalDirection::Kind kind, const Eigen::Vector3d& v) {
    static constexpr const char* kKind[] = {"face", "edge", "corner"};
    CanonicalDirection d;
    d.kind = kind;
    d.direction = v.normalized();
    d.down = SignedAxes(-v) + " " + kKind[static_cast<int>(kind)];
    out.push_back(d);
  };
  for (int i = 0; i < 3; ++i) {
    for (const double s : {1.0, -1.0}) {
      add(CanonicalDirection::Kind::kFace, s * Eigen::Vector3d::Unit(i));
    }
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = i + 1; j < 3; ++j) {
      for (const double si : {1.0, -1.0}) {
        for (const double sj : {1.0, -1.0}) {
          add(CanonicalDirection::Kind::kEdge,
              si * Eigen::Vector3d::Unit(i) + sj * Eigen::Vector3d::Unit(j));
        }
      }
    }
  }
  for (const double sx : {1.0, -1.0}) {
    for (const double sy : {1.0, -1.0}) {
      for (const double sz : {1.0, -1.0}) {
        add(CanonicalDirection::Kind::kCorner, Eigen::Vector3d(sx, sy, sz));
      }
    }
  }
  return out;
}

// Fallback offset (see the header): 0, or for unsigned ADC counts the power of
// two nearest the median reading.
Eigen::Vector3d FallbackCentre(std::span<const Eigen::Vector3d> means, AccelUnits units) {
  if (units != AccelUnits::kCounts || means.empty()) return Eigen::Vector3d::Zero();
  std::vector<double> c;
  for (const auto& m : means) {
    for (int i = 0; i < 3; ++i) {
      if (m[i] < 0.0) return Eigen::Vector3d::Zero();
      c.push_back(m[i]);
    }
  }
  std::nth_element(
      c.begin(), c.begin() + static_cast<std::ptrdiff_t>(c.size() / 2), c.end());
  const double median = c[c.size() / 2];
  if (median < 1.0) return Eigen::Vector3d::Zero();
  const double p = std::exp2(std::round(std::log2(median)));
  return std::abs(median - p) < 0.5 * p ? Eigen::Vector3d::Constant(p)
                                        : Eigen::Vector3d::Zero();
}

// Ratio of the smallest non-trivial to the largest singular value of the
// quadric design at the directions (see CoverageResult::observability).
double Observability(const std::vector<Eigen::Vector3d>& u, ModelKind model) {
  const bool full = model == ModelKind::kShinElSheimy9;
  const int cols = full ? 10 : 7;
  const int needed = cols - 1;  // the unit sphere itself is always a null vector
  if (static_cast<int>(u.size()) < needed) return 0.0;
  Eigen::MatrixXd design(static_cast<Eigen::Index>(u.size()), cols);
  for (std::size_t k = 0; k < u.size(); ++k) {
    const Eigen::Vector3d& v = u[k];
    const auto r = static_cast<Eigen::Index>(k);
    if (full) {
      design.row(r) << v.x() * v.x(), v.y() * v.y(), v.z() * v.z(), 2 * v.x() * v.y(),
          2 * v.x() * v.z(), 2 * v.y() * v.z(), v.x(), v.y(), v.z(), 1.0;
    } else {
      design.row(r) << v.x() * v.x(), v.y() * v.y(), v.z() * v.z(), v.x(), v.y(), v.z(),
          1.0;
    }
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(design);
  const Eigen::VectorXd& s = svd.singularValues();
  if (s.size() < needed || s(0) <= 0.0) return 0.0;
  return s(needed - 1) / s(0);
}

std::string JoinNames(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += i + 1 == names.size() ? " and " : ", ";
    out += names[i];
  }
  return out;
}

// The one line of a session that is not enough: its main problem, then what
// to do, in order.
std::string NotEnoughSummary(const CoverageResult& res) {
  std::string out = res.problems.front() + ": " + res.advice.front();
  for (std::size_t k = 1; k < res.advice.size(); ++k) out += "; " + res.advice[k];
  return out;
}

}  // namespace

std::string_view ToString(CoverageVerdict verdict) {
  switch (verdict) {
    case CoverageVerdict::kGood:
      return "good";
    case CoverageVerdict::kUsableWithWarnings:
      return "usable with warnings";
    case CoverageVerdict::kNotEnough:
      return "not enough";
  }
  return "unknown";
}

std::string CoverageOptions::Validate() const {
  if (!(near_deg > 0.0 && near_deg < 90.0)) return "near_deg must be in (0, 90)";
  if (!(distinct_deg >= 0.0 && distinct_deg < 90.0))
    return "distinct_deg must be in [0, 90)";
  if (!(hold_s > 0.0) || !std::isfinite(hold_s)) return "hold_s must be > 0";
  return "";
}

const std::vector<CanonicalDirection>& CanonicalDirections() {
  static const std::vector<CanonicalDirection> kDirections = MakeCanonical();
  return kDirections;
}

SphereFit FitSphere(std::span<const Eigen::Vector3d> means, AccelUnits units) {
  SphereFit fit;
  if (means.empty()) return fit;
  // Linear least squares |m|² = 2 m·c + d on means centred on their average
  // (counts near 32768 square to 1e9 and would swamp the noise otherwise),
  // scaled to unit RMS so that the conditioning test below is unit-free.
  Eigen::Vector3d avg = Eigen::Vector3d::Zero();
  for (const auto& m : means) avg += m;
  avg /= static_cast<double>(means.size());
  double spread = 0.0;
  for (const auto& m : means) spread += (m - avg).squaredNorm();
  spread = std::sqrt(spread / static_cast<double>(means.size()));

  bool fitted = false;
  Eigen::Vector3d centre = FallbackCentre(means, units);
  if (means.size() >= 4 && spread > 0.0) {
    const auto k = static_cast<Eigen::Index>(means.size());
    Eigen::MatrixXd design(k, 4);
    Eigen::VectorXd rhs(k);
    for (Eigen::Index i = 0; i < k; ++i) {
      const Eigen::Vector3d q = (means[static_cast<std::size_t>(i)] - avg) / spread;
      design.row(i) << 2 * q.x(), 2 * q.y(), 2 * q.z(), 1.0;
      rhs(i) = q.squaredNorm();
    }
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(design);
    const Eigen::VectorXd& s = svd.singularValues();
    if (s(3) > 1e-3 * s(0)) {
      const Eigen::Vector4d x = design.colPivHouseholderQr().solve(rhs);
      const Eigen::Vector3d c = avg + spread * x.head<3>();
      // A fit through positions that all sit on a small cap can put the
      // centre anywhere along the cap's axis: accept it only when the
      // directions about it spread out (their mean is short).
      Eigen::Vector3d mean_dir = Eigen::Vector3d::Zero();
      bool finite = c.allFinite();
      for (const auto& m : means) {
        const Eigen::Vector3d d = m - c;
        if (!(d.norm() > 0.0)) finite = false;
        mean_dir += d.normalized();
      }
      mean_dir /= static_cast<double>(means.size());
      // And only when the positions spread over a good part of the sphere
      // (their RMS distance from their average is r for the whole sphere,
      // 0.3 r for a cap of 17°), with a radius near 1 g when the unit says
      // what 1 g is.
      const double radius = (means.front() - c).norm();
      bool plausible = radius < 2.5 * spread;
      if (const auto per_unit = FixedMps2PerUnit(units)) {
        const double g_units = kStandardGravityMps2 / *per_unit;
        plausible = plausible && radius > 0.7 * g_units && radius < 1.3 * g_units;
      }
      if (finite && plausible && mean_dir.norm() < 0.8) {
        centre = c;
        fitted = true;
      }
    }
  }
  fit.centre = centre;
  fit.fitted = fitted;
  std::vector<double> r;
  for (const auto& m : means) r.push_back((m - centre).norm());
  double sum = 0.0;
  for (double v : r) sum += v;
  fit.radius = sum / static_cast<double>(r.size());
  double ss = 0.0;
  for (double v : r) ss += (v - fit.radius) * (v - fit.radius);
  fit.residual_rms = std::sqrt(ss / static_cast<double>(r.size()));
  return fit;
}

CoverageResult AssessCoverage(std::span<const Eigen::Vector3d> means,
                              const CoverageOptions& options) {
  if (const std::string bad = options.Validate(); !bad.empty()) {
    throw Error("coverage options: " + bad);
  }
  for (std::size_t k = 0; k < means.size(); ++k) {
    if (!means[k].allFinite()) {
      throw Error(fmt::format("coverage: the mean of position {} is not finite", k + 1));
    }
  }
  CoverageResult res;
  res.positions = static_cast<int>(means.size());
  res.normalisation = FitSphere(means, options.units);
  for (const auto& m : means) {
    const Eigen::Vector3d d = m - res.normalisation.centre;
    res.directions.push_back(d.norm() > 0.0 ? Eigen::Vector3d(d.normalized())
                                            : Eigen::Vector3d::UnitZ());
  }
  const auto& u = res.directions;
  for (std::size_t k = 0; k < u.size(); ++k) {
    res.angle_to_previous_deg.push_back(k == 0 ? std::numeric_limits<double>::quiet_NaN()
                                               : AngleDeg(u[k], u[k - 1]));
  }

  // Canonical directions covered.
  const auto& canon = CanonicalDirections();
  for (std::size_t c = 0; c < canon.size(); ++c) {
    const bool hit = std::any_of(u.begin(), u.end(), [&](const Eigen::Vector3d& v) {
      return AngleDeg(v, canon[c].direction) <= options.near_deg;
    });
    (hit ? res.covered : res.missing).push_back(static_cast<int>(c));
  }

  // Per axis: tilts visited.
  for (int i = 0; i < 3; ++i) {
    AxisCoverage& ax = res.axes[static_cast<std::size_t>(i)];
    std::vector<double> tilt{0.0, 180.0};
    for (const auto& v : u) {
      const double up = AngleDeg(v, Eigen::Vector3d::Unit(i));
      ax.closest_up_deg = std::min(ax.closest_up_deg, up);
      ax.closest_down_deg = std::min(ax.closest_down_deg, 180.0 - up);
      tilt.push_back(up);
    }
    ax.near_up = ax.closest_up_deg <= options.near_deg;
    ax.near_down = ax.closest_down_deg <= options.near_deg;
    std::sort(tilt.begin(), tilt.end());
    ax.largest_gap_deg = 0.0;
    for (std::size_t k = 1; k < tilt.size(); ++k) {
      ax.largest_gap_deg = std::max(ax.largest_gap_deg, tilt[k] - tilt[k - 1]);
    }
  }

  // Distinct orientations: greedy grouping within distinct_deg.
  std::vector<Eigen::Vector3d> distinct;
  for (const auto& v : u) {
    const bool seen = std::any_of(distinct.begin(), distinct.end(), [&](const auto& d) {
      return AngleDeg(v, d) < options.distinct_deg;
    });
    if (!seen) distinct.push_back(v);
  }
  res.distinct_positions = static_cast<int>(distinct.size());

  // Largest empty cap, over a Fibonacci lattice of ~2000 directions (about
  // 2.5° apart: fine enough for advice).
  {
    constexpr int kLattice = 2000;
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    res.largest_empty_cap_deg = u.empty() ? 180.0 : 0.0;
    for (int k = 0; k < kLattice && !u.empty(); ++k) {
      const double z = 1.0 - (2.0 * k + 1.0) / kLattice;
      const double r = std::sqrt(1.0 - z * z);
      const Eigen::Vector3d p(r * std::cos(golden * k), r * std::sin(golden * k), z);
      double nearest = 180.0;
      for (const auto& v : u) nearest = std::min(nearest, AngleDeg(p, v));
      if (nearest > res.largest_empty_cap_deg) {
        res.largest_empty_cap_deg = nearest;
        res.emptiest_direction = p;
      }
    }
  }

  res.observability = Observability(u, options.model);
  const bool nine = options.model == ModelKind::kShinElSheimy9;
  const int params = ParameterCount(options.model);
  // The paper's 10 for 9 unknowns; the six-position protocol is six poses.
  res.required_positions = nine ? params + 1 : params;
  res.recommended_positions = nine ? 19 : 7;
  const std::string model_name =
      nine ? "the 9-parameter model" : "the 6-parameter model (bias-scale-6)";
  const std::string hold = fmt::format("~{:g} s each, still", options.hold_s);

  // What to record: faces for the axes never up or down first, then missing
  // corners and edges (they tilt every axis at once), as many as needed.
  std::vector<std::string> faces_needed;
  for (int i = 0; i < 3; ++i) {
    const AxisCoverage& ax = res.axes[static_cast<std::size_t>(i)];
    const std::string name(1, static_cast<char>('x' + i));
    if (!ax.near_up) faces_needed.push_back("-" + name);  // +axis up: -face down
    if (!ax.near_down) faces_needed.push_back("+" + name);
  }
  std::vector<std::string> suggestions;
  for (const auto& f : faces_needed) suggestions.push_back(f + " face");
  for (const auto kind :
       {CanonicalDirection::Kind::kCorner, CanonicalDirection::Kind::kEdge}) {
    for (int c : res.missing) {
      if (canon[static_cast<std::size_t>(c)].kind == kind) {
        suggestions.push_back(canon[static_cast<std::size_t>(c)].down);
      }
    }
  }
  const int short_by = std::max(res.required_positions - res.positions,
                                res.recommended_positions - res.distinct_positions);
  auto pick = [&suggestions](int count) {
    std::vector<std::string> out(
        suggestions.begin(),
        suggestions.begin() +
            std::min<std::ptrdiff_t>(static_cast<std::ptrdiff_t>(suggestions.size()),
                                     count));
    return out;
  };
  auto record_advice = [&](int count) -> std::string {
    count = std::max<int>(count, static_cast<int>(faces_needed.size()));
    // Name at most 8: a longer list is not read.
    constexpr int kMaxNamed = 8;
    auto names = pick(std::min(count, kMaxNamed));
    if (names.empty()) {
      return fmt::format(
          "record {} more positions in new orientations ({})", count, hold);
    }
    if (count > kMaxNamed) names.push_back(fmt::format("{} more", count - kMaxNamed));
    return fmt::format("record {} more position{}, e.g. with the {} down ({})",
                       count,
                       count == 1 ? "" : "s",
                       JoinNames(names),
                       hold);
  };

  // Problems, worst first.
  bool not_enough = false;
  std::string headline;
  if (res.positions < res.required_positions) {
    not_enough = true;
    headline = fmt::format("session has {} static position{}, {} needs at least {}",
                           res.positions,
                           res.positions == 1 ? "" : "s",
                           model_name,
                           res.required_positions);
    res.problems.push_back(headline);
  } else if (res.observability < kNoObservability) {
    not_enough = true;
    headline =
        res.distinct_positions <= params
            ? fmt::format(
                  "the {} static positions are only {} distinct orientations, too few to "
                  "determine the {} parameters of {}",
                  res.positions,
                  res.distinct_positions,
                  params,
                  model_name)
            : fmt::format(
                  "the {} static positions ({} distinct orientations) do not determine "
                  "all "
                  "{} parameters of {}: they lie too close to one plane or cone",
                  res.positions,
                  res.distinct_positions,
                  params,
                  model_name);
    res.problems.push_back(headline);
  }
  if (nine && res.distinct_positions < res.recommended_positions) {
    res.problems.push_back(fmt::format(
        "{} distinct orientations; the paper recommends more than 18 spanning the sphere",
        res.distinct_positions));
  }
  if (!nine && res.positions == params) {
    res.problems.push_back(
        "six positions for six parameters fit exactly: nothing checks the fit (a seventh "
        "position would)");
  }
  for (int i = 0; i < 3; ++i) {
    const AxisCoverage& ax = res.axes[static_cast<std::size_t>(i)];
    const char name = static_cast<char>('x' + i);
    if (!ax.near_up) {
      res.problems.push_back(fmt::format(
          "+{} never pointed up (closest {:.0f} deg)", name, ax.closest_up_deg));
    }
    if (!ax.near_down) {
      res.problems.push_back(fmt::format(
          "+{} never pointed down (closest {:.0f} deg)", name, ax.closest_down_deg));
    }
  }
  if (!not_enough && res.observability < kWeakObservability) {
    res.problems.push_back(fmt::format(
        "the positions determine some parameters poorly (observability {:.3g})",
        res.observability));
  }
  if (nine && !u.empty() && res.largest_empty_cap_deg > 45.0) {
    // The canonical direction nearest the emptiest spot, for the advice.
    const auto nearest =
        std::min_element(canon.begin(), canon.end(), [&](const auto& l, const auto& r) {
          return AngleDeg(l.direction, res.emptiest_direction) <
                 AngleDeg(r.direction, res.emptiest_direction);
        });
    res.problems.push_back(
        fmt::format("no position within {:.0f} deg of the orientation with the {} down",
                    res.largest_empty_cap_deg,
                    nearest->down));
    // Suggested first after the faces: it fills the largest hole.
    const auto first =
        suggestions.begin() + static_cast<std::ptrdiff_t>(faces_needed.size());
    if (std::find(suggestions.begin(), first, nearest->down) == first) {
      const auto at = std::find(first, suggestions.end(), nearest->down);
      if (at != suggestions.end()) suggestions.erase(at);
      suggestions.insert(
          suggestions.begin() + static_cast<std::ptrdiff_t>(faces_needed.size()),
          nearest->down);
    }
  }

  if (not_enough) {
    res.verdict = CoverageVerdict::kNotEnough;
    const int more = std::max(1,
                              res.positions < res.required_positions
                                  ? res.required_positions - res.positions
                                  : short_by);
    res.advice.push_back(record_advice(more));
    if (nine && res.positions >= ParameterCount(ModelKind::kBiasScale6)) {
      res.advice.push_back(
          "or calibrate bias and scale only with --model bias-scale-6 (six-position "
          "protocol: each axis up and down)");
    }
    res.summary = NotEnoughSummary(res);
  } else if (!res.problems.empty()) {
    res.verdict = CoverageVerdict::kUsableWithWarnings;
    if (short_by > 0 || !faces_needed.empty() || !suggestions.empty()) {
      res.advice.push_back(record_advice(std::max(1, short_by)));
    }
    res.summary =
        fmt::format("usable with warnings: {}; to improve, {}",
                    res.problems.front(),
                    res.advice.empty() ? "record more orientations" : res.advice.front());
  } else {
    res.verdict = CoverageVerdict::kGood;
    res.summary = fmt::format(
        "good: {} static positions ({} distinct), {} of 26 cube directions covered, "
        "every "
        "axis near up and near down",
        res.positions,
        res.distinct_positions,
        res.covered.size());
  }
  return res;
}

CoverageResult AssessCoverage(const DetectResult& detection,
                              const CoverageOptions& options) {
  std::vector<Eigen::Vector3d> means;
  means.reserve(detection.intervals.size());
  for (const auto& iv : detection.intervals) means.push_back(iv.mean);
  CoverageResult res = AssessCoverage(means, options);
  // Positions that were held, but not long enough, are the first thing to
  // fix when they are most of them: recording more of them would be dropped
  // the same way. (A stray pause in a turn is dropped too, and is no advice.)
  if (!res.good_enough() && detection.dropped_short > 0 &&
      static_cast<std::size_t>(detection.dropped_short) >= detection.intervals.size()) {
    // First in the advice (push and rotate: GCC 12 warns of a null
    // dereference in its own code for an insert at the front).
    res.advice.push_back(fmt::format(
        "{} still stretch{} shorter than the minimum (--min-static) {} dropped: "
        "hold each position longer",
        detection.dropped_short,
        detection.dropped_short == 1 ? "" : "es",
        detection.dropped_short == 1 ? "was" : "were"));
    std::rotate(res.advice.rbegin(), res.advice.rbegin() + 1, res.advice.rend());
    res.summary = NotEnoughSummary(res);
  }
  return res;
}

}  // namespace mpcal
