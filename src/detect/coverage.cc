#include "mpcal/coverage.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

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

// Unit direction of each mean about the fitted offset, and the angle from
// the one before.
void Directions(std::span<const Eigen::Vector3d> means, CoverageResult* res) {
  for (const auto& m : means) {
    const Eigen::Vector3d d = m - res->normalisation.centre;
    res->directions.push_back(d.norm() > 0.0 ? Eigen::Vector3d(d.normalized())
                                             : Eigen::Vector3d::UnitZ());
  }
  const auto& u = res->directions;
  for (std::size_t k = 0; k < u.size(); ++k) {
    res->angle_to_previous_deg.push_back(k == 0 ? std::numeric_limits<double>::quiet_NaN()
                                                : AngleDeg(u[k], u[k - 1]));
  }
}

// The canonical directions within near_deg of a position, and the others.
void CoverCanonical(const std::vector<Eigen::Vector3d>& u,
                    double near_deg,
                    CoverageResult* res) {
  const auto& canon = CanonicalDirections();
  for (std::size_t c = 0; c < canon.size(); ++c) {
    const bool hit = std::any_of(u.begin(), u.end(), [&](const Eigen::Vector3d& v) {
      return AngleDeg(v, canon[c].direction) <= near_deg;
    });
    (hit ? res->covered : res->missing).push_back(static_cast<int>(c));
  }
}

// Per axis: the tilts visited, the closest to up and down, the largest gap.
AxisCoverage AxisTilts(const std::vector<Eigen::Vector3d>& u, int i, double near_deg) {
  AxisCoverage ax;
  std::vector<double> tilt{0.0, 180.0};
  for (const auto& v : u) {
    const double up = AngleDeg(v, Eigen::Vector3d::Unit(i));
    ax.closest_up_deg = std::min(ax.closest_up_deg, up);
    ax.closest_down_deg = std::min(ax.closest_down_deg, 180.0 - up);
    tilt.push_back(up);
  }
  ax.near_up = ax.closest_up_deg <= near_deg;
  ax.near_down = ax.closest_down_deg <= near_deg;
  std::sort(tilt.begin(), tilt.end());
  ax.largest_gap_deg = 0.0;
  for (std::size_t k = 1; k < tilt.size(); ++k) {
    ax.largest_gap_deg = std::max(ax.largest_gap_deg, tilt[k] - tilt[k - 1]);
  }
  return ax;
}

// Distinct orientations: greedy grouping within distinct_deg.
int DistinctCount(const std::vector<Eigen::Vector3d>& u, double distinct_deg) {
  std::vector<Eigen::Vector3d> distinct;
  for (const auto& v : u) {
    const bool seen = std::any_of(distinct.begin(), distinct.end(), [&](const auto& d) {
      return AngleDeg(v, d) < distinct_deg;
    });
    if (!seen) distinct.push_back(v);
  }
  return static_cast<int>(distinct.size());
}

// Largest empty cap, over a Fibonacci lattice of ~2000 directions (about
// 2.5° apart: fine enough for advice).
void LargestEmptyCap(const std::vector<Eigen::Vector3d>& u, CoverageResult* res) {
  constexpr int kLattice = 2000;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  res->largest_empty_cap_deg = u.empty() ? 180.0 : 0.0;
  for (int k = 0; k < kLattice && !u.empty(); ++k) {
    const double z = 1.0 - (2.0 * k + 1.0) / kLattice;
    const double r = std::sqrt(1.0 - z * z);
    const Eigen::Vector3d p(r * std::cos(golden * k), r * std::sin(golden * k), z);
    double nearest = 180.0;
    for (const auto& v : u) nearest = std::min(nearest, AngleDeg(p, v));
    if (nearest > res->largest_empty_cap_deg) {
      res->largest_empty_cap_deg = nearest;
      res->emptiest_direction = p;
    }
  }
}

// What to record: faces for the axes never up or down first, then missing
// corners and edges (they tilt every axis at once). `faces` gets the number
// of faces at the front.
std::vector<std::string> Suggestions(const CoverageResult& res, std::size_t* faces) {
  std::vector<std::string> out;
  for (int i = 0; i < 3; ++i) {
    const AxisCoverage& ax = res.axes[static_cast<std::size_t>(i)];
    const std::string name(1, static_cast<char>('x' + i));
    if (!ax.near_up) out.push_back("-" + name + " face");  // +axis up: -face down
    if (!ax.near_down) out.push_back("+" + name + " face");
  }
  *faces = out.size();
  const auto& canon = CanonicalDirections();
  for (const auto kind :
       {CanonicalDirection::Kind::kCorner, CanonicalDirection::Kind::kEdge}) {
    for (int c : res.missing) {
      if (canon[static_cast<std::size_t>(c)].kind == kind) {
        out.push_back(canon[static_cast<std::size_t>(c)].down);
      }
    }
  }
  return out;
}

// The main problem when the positions cannot determine the model: too few,
// too few distinct, or too close to one plane or cone.
std::optional<CoverageProblem> NotEnoughProblem(const CoverageResult& res,
                                                ModelKind model) {
  CoverageProblem p;
  p.model = model;
  p.positions = res.positions;
  p.distinct_positions = res.distinct_positions;
  p.parameters = ParameterCount(model);
  p.required_positions = res.required_positions;
  if (res.positions < res.required_positions) {
    p.kind = CoverageProblemKind::kTooFewPositions;
  } else if (res.observability < kNoObservability) {
    p.kind = res.distinct_positions <= p.parameters
                 ? CoverageProblemKind::kTooFewOrientations
                 : CoverageProblemKind::kNotDetermined;
  } else {
    return std::nullopt;
  }
  return p;
}

// The weaker problems, in order, after the main one.
void WeakProblems(const CoverageResult& res,
                  ModelKind model,
                  bool not_enough,
                  std::vector<CoverageProblem>* problems) {
  const bool nine = model == ModelKind::kShinElSheimy9;
  CoverageProblem base;
  base.model = model;
  base.positions = res.positions;
  base.distinct_positions = res.distinct_positions;
  base.parameters = ParameterCount(model);
  base.required_positions = res.required_positions;
  auto add = [&](CoverageProblemKind kind, int axis = 0, double angle = 0.0) {
    CoverageProblem p = base;
    p.kind = kind;
    p.axis = axis;
    p.angle_deg = angle;
    p.observability = res.observability;
    problems->push_back(p);
  };
  if (nine && res.distinct_positions < res.recommended_positions) {
    add(CoverageProblemKind::kBelowRecommended);
  }
  if (!nine && res.positions == base.parameters) add(CoverageProblemKind::kExactFit);
  for (int i = 0; i < 3; ++i) {
    const AxisCoverage& ax = res.axes[static_cast<std::size_t>(i)];
    if (!ax.near_up) add(CoverageProblemKind::kNeverUp, i, ax.closest_up_deg);
    if (!ax.near_down) add(CoverageProblemKind::kNeverDown, i, ax.closest_down_deg);
  }
  if (!not_enough && res.observability < kWeakObservability) {
    add(CoverageProblemKind::kWeak);
  }
}

// The largest hole, when a 9-parameter session has one over 45°: a problem,
// and its nearest canonical direction moved to just after the faces in the
// suggestions, since it fills the hole best.
void EmptyCapProblem(const CoverageResult& res,
                     std::size_t faces,
                     std::vector<std::string>* suggestions,
                     std::vector<CoverageProblem>* problems) {
  const auto& canon = CanonicalDirections();
  const auto nearest =
      std::min_element(canon.begin(), canon.end(), [&](const auto& l, const auto& r) {
        return AngleDeg(l.direction, res.emptiest_direction) <
               AngleDeg(r.direction, res.emptiest_direction);
      });
  CoverageProblem p;
  p.kind = CoverageProblemKind::kEmptyCap;
  p.angle_deg = res.largest_empty_cap_deg;
  p.down = nearest->down;
  problems->push_back(p);
  const auto first = suggestions->begin() + static_cast<std::ptrdiff_t>(faces);
  if (std::find(suggestions->begin(), first, nearest->down) == first) {
    const auto at = std::find(first, suggestions->end(), nearest->down);
    if (at != suggestions->end()) suggestions->erase(at);
    suggestions->insert(suggestions->begin() + static_cast<std::ptrdiff_t>(faces),
                        nearest->down);
  }
}

// "Record `count` more positions", naming at most 8 of the suggestions (a
// longer list is not read), and at least every face needed.
CoverageStep RecordStep(const std::vector<std::string>& suggestions,
                        std::size_t faces,
                        int count,
                        double hold_s) {
  CoverageStep step;
  step.kind = CoverageStepKind::kRecordPositions;
  step.count = std::max<int>(count, static_cast<int>(faces));
  step.hold_s = hold_s;
  constexpr int kMaxNamed = 8;
  const auto named = std::min<std::ptrdiff_t>(
      static_cast<std::ptrdiff_t>(suggestions.size()), std::min(step.count, kMaxNamed));
  step.orientations.assign(suggestions.begin(), suggestions.begin() + named);
  if (!step.orientations.empty() && step.count > kMaxNamed) {
    step.unnamed = step.count - kMaxNamed;
  }
  return step;
}

// The verdict and what to do, from the problems found.
void Verdict(const CoverageOptions& options,
             bool not_enough,
             const std::vector<std::string>& suggestions,
             std::size_t faces,
             CoverageResult* res) {
  const bool nine = options.model == ModelKind::kShinElSheimy9;
  const int short_by = std::max(res->required_positions - res->positions,
                                res->recommended_positions - res->distinct_positions);
  if (not_enough) {
    res->verdict = CoverageVerdict::kNotEnough;
    const int more = std::max(1,
                              res->positions < res->required_positions
                                  ? res->required_positions - res->positions
                                  : short_by);
    res->advice.push_back(RecordStep(suggestions, faces, more, options.hold_s));
    if (nine && res->positions >= ParameterCount(ModelKind::kBiasScale6)) {
      CoverageStep six;
      six.kind = CoverageStepKind::kSixParameterModel;
      six.advice.settings.push_back(
          {Option::kModel, std::string(ToString(ModelKind::kBiasScale6))});
      res->advice.push_back(six);
    }
  } else if (!res->problems.empty()) {
    res->verdict = CoverageVerdict::kUsableWithWarnings;
    if (short_by > 0 || faces > 0 || !suggestions.empty()) {
      res->advice.push_back(
          RecordStep(suggestions, faces, std::max(1, short_by), options.hold_s));
    }
  } else {
    res->verdict = CoverageVerdict::kGood;
  }
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

CoverageResult AssessCoverage(std::span<const Eigen::Vector3d> means,
                              const CoverageOptions& options) {
  if (const std::string bad = options.Validate(); !bad.empty()) {
    throw Error(ErrorKind::kOption, "coverage options: " + bad);
  }
  for (std::size_t k = 0; k < means.size(); ++k) {
    if (!means[k].allFinite()) {
      throw Error(ErrorKind::kInput,
                  fmt::format("coverage: the mean of position {} is not finite", k + 1));
    }
  }
  CoverageResult res;
  res.positions = static_cast<int>(means.size());
  res.normalisation = FitSphere(means, options.units);
  Directions(means, &res);
  const auto& u = res.directions;
  CoverCanonical(u, options.near_deg, &res);
  for (int i = 0; i < 3; ++i) {
    res.axes[static_cast<std::size_t>(i)] = AxisTilts(u, i, options.near_deg);
  }
  res.distinct_positions = DistinctCount(u, options.distinct_deg);
  LargestEmptyCap(u, &res);
  res.observability = Observability(u, options.model);
  const bool nine = options.model == ModelKind::kShinElSheimy9;
  // The paper's 10 for 9 unknowns; the six-position protocol is six poses.
  res.required_positions =
      nine ? ParameterCount(options.model) + 1 : ParameterCount(options.model);
  res.recommended_positions = nine ? 19 : 7;

  std::size_t faces = 0;
  std::vector<std::string> suggestions = Suggestions(res, &faces);
  const std::optional<CoverageProblem> main = NotEnoughProblem(res, options.model);
  if (main) res.problems.push_back(*main);
  WeakProblems(res, options.model, main.has_value(), &res.problems);
  if (nine && !u.empty() && res.largest_empty_cap_deg > 45.0) {
    EmptyCapProblem(res, faces, &suggestions, &res.problems);
  }
  Verdict(options, main.has_value(), suggestions, faces, &res);
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
    CoverageStep hold;
    hold.kind = CoverageStepKind::kHoldLonger;
    hold.dropped_short = detection.dropped_short;
    hold.advice.settings.push_back({Option::kDetectMinStatic, ""});
    res.advice.insert(res.advice.begin(), hold);
  }
  return res;
}

}  // namespace mpcal
