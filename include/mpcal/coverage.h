/// \file coverage.h
/// \brief How well a session's static positions cover the sphere of
/// orientations, and whether they are enough to calibrate a given model.
///
/// The reference is the 26 canonical directions of Syed et al. (2007)
/// (docs/method.md §3.9): the 6 faces, 12 edges and 8 corners of a cube. Directions
/// are those of the gravity reaction in the sensor frame, i.e. of the mean
/// reading: +z reads +1 g when the +z axis points up (the -z face is down).
///
/// Mean readings carry an offset (raw counts sit near 32768, a consumer part
/// has a bias of up to 0.3 g), so they are first normalised without any
/// knowledge of the units: the offset is the centre of the sphere fitted to
/// the means by linear least squares, |m_k|² = 2 m_k·c + d (Eigen's
/// column-pivoting QR), and each direction is (m_k − c)/|m_k − c|. The fit
/// needs at least 4 positions that span the sphere; otherwise the offset is
/// 0 for readings in g or m/s², and for counts the power of two nearest the
/// median reading (an unsigned ADC's mid-scale) or 0 when readings are
/// negative. Scale errors of a few per cent change the directions by well
/// under a degree, so a sphere (not an ellipsoid) is all this needs.
#pragma once

#include <array>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "mpcal/advice.h"
#include "mpcal/detect.h"
#include "mpcal/model.h"
#include "mpcal/sphere_fit.h"
#include "mpcal/units.h"

namespace mpcal {

/// One of the 26 canonical directions.
struct CanonicalDirection {
  enum class Kind { kFace, kEdge, kCorner };
  Kind kind = Kind::kFace;
  /// Unit vector of the gravity reaction (mean reading direction).
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
  /// How a user holds it: the face, edge or corner of the sensor's box that
  /// points down, e.g. "-z face", "-x-y edge", "+x-y-z corner".
  std::string down;
};

/// The 6 faces, then 12 edges, then 8 corners, in a fixed order.
const std::vector<CanonicalDirection>& CanonicalDirections();

/// Per sensor axis: was it ever near up, near down, and the largest range of
/// tilts never visited.
struct AxisCoverage {
  bool near_up = false;
  bool near_down = false;
  /// Smallest angle between the axis and up / down over the positions (deg).
  double closest_up_deg = 180.0;
  double closest_down_deg = 180.0;
  /// Largest gap (deg) in the sorted angles between this axis and up over the
  /// positions, with 0 and 180 as the ends: 45 for the 26 cube positions, 90
  /// for the six faces, 180 with no position at all.
  double largest_gap_deg = 180.0;
};

enum class CoverageVerdict { kGood, kUsableWithWarnings, kNotEnough };
/// "good", "usable with warnings", "not enough".
std::string_view ToString(CoverageVerdict verdict);

struct CoverageOptions {
  /// The model the session is meant to calibrate.
  ModelKind model = ModelKind::kShinElSheimy9;
  /// Units of the means (only used by the fallback offset, see above).
  AccelUnits units = AccelUnits::kMps2;
  /// A canonical direction (or an axis up/down) counts as covered when a
  /// position is within this angle (deg).
  double near_deg = 25.0;
  /// Positions closer than this (deg) count as one orientation.
  double distinct_deg = 10.0;
  /// Suggested hold time in the advice (s).
  double hold_s = 10.0;

  /// Empty string when valid, otherwise names the first bad field.
  std::string Validate() const;
};

/// What is wrong or weak about a session's positions, worst first.
enum class CoverageProblemKind {
  kTooFewPositions,     ///< fewer positions than the model needs
  kTooFewOrientations,  ///< enough positions, too few distinct orientations
  kNotDetermined,       ///< they lie too close to one plane or cone
  kBelowRecommended,    ///< fewer distinct orientations than recommended
  kExactFit,            ///< as many positions as parameters: nothing checks
  kNeverUp,             ///< an axis never pointed up
  kNeverDown,           ///< an axis never pointed down
  kWeak,                ///< determined, some parameters poorly
  kEmptyCap,            ///< a large part of the sphere has no position
};

struct CoverageProblem {
  CoverageProblemKind kind = CoverageProblemKind::kTooFewPositions;
  ModelKind model = ModelKind::kShinElSheimy9;
  int positions = 0;
  int distinct_positions = 0;
  int parameters = 0;
  int required_positions = 0;
  /// kNeverUp, kNeverDown: the axis (0 x, 1 y, 2 z) and its closest angle to
  /// up or down (deg); kEmptyCap: the cap's radius (deg) and the orientation
  /// nearest its centre (what points down, e.g. "+x-y-z corner").
  int axis = 0;
  double angle_deg = 0.0;
  std::string down;
  double observability = 0.0;
};

/// What to do next, in order.
enum class CoverageStepKind {
  kRecordPositions,    ///< record `count` more positions, e.g. `orientations`
  kSixParameterModel,  ///< or calibrate bias and scale only (advice: the model)
  kHoldLonger,         ///< hold each position longer (advice: the minimum)
};

struct CoverageStep {
  CoverageStepKind kind = CoverageStepKind::kRecordPositions;
  /// kRecordPositions: how many, the orientations named (what points down;
  /// empty when any new one does), how many more beyond those named, and
  /// the hold time (s).
  int count = 0;
  std::vector<std::string> orientations;
  int unnamed = 0;
  double hold_s = 0.0;
  /// kHoldLonger: the still stretches dropped as too short.
  int dropped_short = 0;
  /// The option that would change the outcome, when one would.
  Advice advice;
};

/// Plain sentences (no option names), e.g. "+x never pointed up (closest
/// 60 deg)", "record 3 more positions, e.g. with the -x-y-z corner down
/// (~10 s each, still)".
std::string Describe(const CoverageProblem& problem);
std::string Describe(const CoverageStep& step);

struct CoverageResult {
  SphereFit normalisation;
  /// Unit direction of each position, in input order, and the angle (deg)
  /// between each and the one before it (NaN for the first).
  std::vector<Eigen::Vector3d> directions;
  std::vector<double> angle_to_previous_deg;
  /// Indices into CanonicalDirections(): within near_deg of a position, or
  /// not.
  std::vector<int> covered;
  std::vector<int> missing;
  /// x, y, z.
  std::array<AxisCoverage, 3> axes;
  int positions = 0;
  /// Positions after grouping those within distinct_deg of each other.
  int distinct_positions = 0;
  /// Angular radius (deg) of the largest cap of the sphere with no position
  /// in it, and its centre: where the next position helps most.
  double largest_empty_cap_deg = 180.0;
  Eigen::Vector3d emptiest_direction = Eigen::Vector3d::UnitZ();
  /// How well the directions determine the model: the smallest non-trivial
  /// singular value over the largest of the design matrix of the quadric the
  /// model is (a general ellipsoid with a centre for 9 parameters, an
  /// axis-aligned one for 6), evaluated at the directions. 0 when the
  /// parameters are not all determined (e.g. every position in one plane).
  double observability = 0.0;
  /// Positions the model needs at least (parameters + 1) and the paper's
  /// recommendation (more than 18 for 9 parameters; 6 faces for 6).
  int required_positions = 0;
  int recommended_positions = 0;
  CoverageVerdict verdict = CoverageVerdict::kNotEnough;
  /// What is wrong or weak (empty when good), what to do next (empty when
  /// nothing is needed), both in order.
  std::vector<CoverageProblem> problems;
  std::vector<CoverageStep> advice;

  bool good_enough() const { return verdict != CoverageVerdict::kNotEnough; }
};

/// One plain line: the verdict and its main reason, e.g. "session has 7
/// static positions, the 9-parameter model needs at least 10: record 3 more,
/// e.g. with the -x-y-z corner down ...".
/// `word_step` words each step (Describe by default): a caller that names
/// the options its own way passes its wording.
std::string Summary(const CoverageResult& result);
std::string Summary(const CoverageResult& result,
                    const std::function<std::string(const CoverageStep&)>& word_step);

/// Assesses the positions whose mean readings are `means` (recording units).
/// \throws mpcal::Error if the options are invalid or a mean is not finite.
CoverageResult AssessCoverage(std::span<const Eigen::Vector3d> means,
                              const CoverageOptions& options);

/// Same, over the intervals of a detection.
CoverageResult AssessCoverage(const DetectResult& detection,
                              const CoverageOptions& options);

/// A detection and its coverage as JSON (`"format": "mpcal.detection/1"`):
/// the detection figures, every interval (sample range, times in the
/// recording's clock, mean and std in its units, direction, angle to the
/// previous) and the coverage (canonical directions covered and missing by
/// the name of what points down, per-axis figures, verdict, problems,
/// advice), and the turns between the positions when given (angle, axis,
/// duration, tilt). `source` and `units` describe the recording. The sentences are
/// `words` when given (a caller's wording of the findings), else Describe's.
/// Never throws.
struct DetectionWords {
  std::string message;
  std::vector<std::string> notes;
  std::vector<std::string> problems;
  std::vector<std::string> advice;
  std::string summary;
};
std::string DetectionReportJson(const DetectResult& detection,
                                const CoverageResult& coverage,
                                const CoverageOptions& options,
                                const std::string& source,
                                const DetectionWords* words = nullptr,
                                std::span<const Turn> turns = {});

}  // namespace mpcal
