/// \file noise.h
/// \brief Noise of a still inertial sensor: overlapping Allan deviation with
/// confidence intervals, the IEEE noise terms it supports, and how long to
/// record to see the ones it does not.
///
/// Method (IEEE Std 952-1997 Annex C, IEEE Std 1293-2018; NIST SP 1065,
/// Riley 2008): the overlapping Allan variance of a rate signal y sampled
/// every τ0 at cluster time τ = mτ0, from its cumulative sums θ_k = Σ_{i<k} y_i,
///
///     σ²(τ) = Σ_k (θ_{k+2m} − 2θ_{k+m} + θ_k)² / (2 m² K),
///
/// summed over K start indices k: all of them for m < 2·min_overlaps, else
/// every d-th, d = ⌊m / min_overlaps⌋, so at least `min_overlaps` starts per
/// cluster width (beyond a few, more overlap adds next to no information:
/// the EDF of the overlapping estimator is reached; Riley 2008 §5.2.4). The
/// cluster times are log-spaced, `points_per_octave` a factor of two, up to
/// `max_tau_fraction` of the record.
///
/// Confidence intervals are χ² intervals with the equivalent degrees of
/// freedom of the overlapping estimator from the approximations of Howe,
/// Allan & Barnes (1981) as tabulated in NIST SP 1065 Table 5 (also
/// Greenhall & Riley 2003 for their derivation), for the noise type that the
/// fitted terms say dominates at that τ (white PM for quantisation, white FM
/// for white noise, flicker FM for bias instability, random-walk FM for rate
/// random walk and rate ramp).
///
/// The terms, in the variance domain (IEEE 952 Table C.2):
///
///     σ²(τ) = 3Q²/τ² + N²/τ + (2 ln 2/π) B² + K²τ/3 + R²τ²/2,
///
/// fitted by non-negative weighted least squares (weights from each point's
/// EDF, iterated with the model's own variance; the covariance inflated for
/// the correlation of nearby τ), each term reported as measured only where
/// it carries most of the fitted variance at NoiseOptions::min_region_points
/// cluster times and is significantly above zero. B is the flat floor of
/// the curve: min σ ≈ 0.664 B when the other terms are far below it; the fit
/// separates it from the white noise and random walk around the minimum.
///
/// Units: a channel in unit u (m/s² for accelerometers, rad/s for
/// gyroscopes) gives Q in u·s, N in u/√Hz, B in u, K in u/s/√Hz, R in u/s.
/// These are continuous-time (two-sided) densities: a white noise of density
/// N sampled at f_s Hz has σ = N·√f_s per sample, and a random walk of
/// density K steps by K/√f_s per sample (as Kalibr defines them).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "mpcal/calibration.h"
#include "mpcal/detect.h"
#include "mpcal/gap_counter.h"
#include "mpcal/recording.h"
#include "mpcal/recording_view.h"

namespace mpcal {

/// The IEEE 952 noise terms, in the order of their slope.
enum class NoiseTerm {
  kQuantisation,     ///< ADEV slope −1, Q
  kWhiteNoise,       ///< slope −½, N (angle / velocity random walk)
  kBiasInstability,  ///< slope 0, B (flicker)
  kRandomWalk,       ///< slope +½, K (rate / acceleration random walk)
  kRateRamp,         ///< slope +1, R
};
inline constexpr int kNoiseTermCount = 5;
/// "quantisation", "white_noise", "bias_instability", "random_walk", "rate_ramp".
std::string_view ToString(NoiseTerm term);

/// Options of the Allan deviation.
struct AllanOptions {
  /// Cluster times per factor of two in τ (log-spaced, rounded to whole
  /// samples, duplicates dropped). More: a smoother plot, same information.
  double points_per_octave = 4.0;
  /// Largest cluster time as a fraction of the record (the last τ has about
  /// 2 degrees of freedom at 0.25; larger is mostly noise).
  double max_tau_fraction = 0.25;
  /// Start indices per cluster width for large m (see the file comment);
  /// the estimator is fully overlapping for m < 2 × this.
  int min_overlaps = 16;
  /// Two-sided confidence level of every interval (curve and terms).
  double confidence = 0.95;

  /// Empty string when valid, otherwise names the first bad field.
  std::string Validate() const;
};

/// One cluster time of an Allan curve.
struct AllanPoint {
  double tau_s = 0.0;
  std::int64_t m = 0;       ///< τ / τ0
  std::int64_t stride = 1;  ///< step between start indices
  std::int64_t terms = 0;   ///< squared differences averaged
  double avar = 0.0;        ///< Allan variance, u²
  double adev = 0.0;        ///< √avar, u
  double edf = 0.0;         ///< equivalent degrees of freedom
  double adev_lo = 0.0;     ///< confidence interval of adev
  double adev_hi = 0.0;
  NoiseTerm dominant = NoiseTerm::kWhiteNoise;  ///< noise type used for the EDF
};

/// The overlapping Allan variance of a 3-axis rate signal, summed as its
/// samples arrive (in time order, split anyhow): a record of any length is
/// analysed without holding it. The cumulative sums θ_k = Σ_{i<k} (y_i − y_0)
/// (about the first sample, so that they stay small and keep their digits;
/// the running sum in long double) feed the squared second differences of
/// every cluster size whose stride is below kFarStride at once, from the
/// last 2 m sums; the sums at multiples of kFarStride are kept (1/64 of the
/// samples), which is all the larger cluster sizes read: their strides are
/// powers of two of at least kFarStride and their m multiples of them.
/// Memory: 3 doubles per 64 samples. The result does not depend on how the
/// samples were split (up to rounding).
class AllanSums {
 public:
  /// Cluster sizes whose stride is at least this are summed at the end.
  static constexpr std::int64_t kFarStride = 64;

  /// \throws mpcal::Error (kOption) for invalid options.
  explicit AllanSums(const AllanOptions& options);
  /// Adds `count` samples, in the signal's own unit.
  void Add(const Eigen::Vector3d* samples, std::size_t count);
  /// Samples added.
  std::size_t samples() const { return samples_; }
  /// Their mean, in their unit.
  Eigen::Vector3d Mean() const;
  /// What the values of one axis (0, 1, 2) look like, in their unit: how a
  /// sensor that is not producing noise shows.
  struct AxisValues {
    int distinct = 0;         ///< distinct values, counted up to 3 (3: three or more)
    double first = 0.0;       ///< the first value
    double resolution = 0.0;  ///< smallest non-zero change between consecutive
                              ///< samples (0: none changed)
    double adev_tau0 = 0.0;   ///< Allan deviation at one sample period
  };
  AxisValues Values(int axis) const;
  /// The Allan variance of each axis at the log-spaced cluster times of the
  /// samples added (AllanOptions), scaled to SI by `si_per_unit`, τ = m ×
  /// `sample_period_s` (EDF and intervals still at their white-noise
  /// defaults; AnalyseSensorNoise sets them from the fitted terms).
  /// \throws mpcal::Error when fewer than 8 samples.
  std::array<std::vector<AllanPoint>, 3> Curves(double si_per_unit,
                                                double sample_period_s) const;

 private:
  struct Near {
    std::int64_t m = 0;
    std::int64_t stride = 1;
    std::int64_t next_start = 0;  // the first start index not summed yet
    std::array<long double, 3> total{};
  };
  void SumNear();
  void TrackValues(const Eigen::Vector3d* samples, std::size_t count);

  AllanOptions options_;
  std::size_t samples_ = 0;
  std::array<int, 3> distinct_{};
  std::array<std::array<double, 2>, 3> values_{};  // the first two distinct values
  Eigen::Vector3d previous_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d resolution_ = Eigen::Vector3d::Zero();  // 0: no change yet
  Eigen::Vector3d first_ = Eigen::Vector3d::Zero();
  std::array<long double, 3> run_{};  // θ of the last sample added
  std::vector<Near> near_;
  std::int64_t history_ = 0;    // sums kept before the new ones: 2 × largest near m
  std::vector<double> recent_;  // θ_{base_} ... θ_{samples_}, 3 doubles each
  std::int64_t base_ = 0;       // index of recent_'s first sum
  std::vector<double> far_;     // θ_0, θ_64, θ_128, ...
};

/// EDF of the overlapping Allan variance at m for N phase points and the
/// given dominant term (NIST SP 1065 Table 5, Howe, Allan & Barnes 1981).
double OverlappingAllanEdf(double n_phase, double m, NoiseTerm dominant);

/// Quantile of the χ² distribution with `dof` > 0 (non-integer) degrees of
/// freedom at probability p in (0, 1).
double ChiSquareQuantile(double p, double dof);

/// What was found about one term of one axis.
enum class TermStatus {
  kMeasured,   ///< the curve shows it: value and interval
  kNotSeen,    ///< no region of the curve where it dominates: upper bound
  kMasked,     ///< the neighbouring terms meet above it: a longer record
               ///< will not show it
  kDisagrees,  ///< the fitted model lies outside the curve's interval where
               ///< this term dominates (ModelCheck::disagree): the fit's value
               ///< is not a measurement; the curve's upper bound stands
};
std::string_view ToString(TermStatus status);

/// One noise term of one axis, in the units of the file comment.
struct TermEstimate {
  TermStatus status = TermStatus::kNotSeen;
  /// Fitted value; set only when measured.
  std::optional<double> value;
  /// Confidence interval (AllanOptions::confidence); measured only.
  double lo = 0.0;
  double hi = 0.0;
  /// Not measured: the largest value the curve allows (the smallest upper
  /// confidence limit over τ of the term alone); 0 when none.
  double upper_bound = 0.0;
  /// The τ range where it carries most of the fitted variance (measured).
  double tau_lo_s = 0.0;
  double tau_hi_s = 0.0;
  /// Not measured (bias instability and random walk): the shortest record
  /// (s) in which a term at its upper bound would be measured in 9 records
  /// of 10, with the other terms as fitted: it carries NoiseOptions::
  /// dominance of the fitted variance at min_region_points cluster times
  /// (the last at most max_tau_fraction of the record) and its coefficient
  /// is above zero by the interval with 90 % power, its standard deviation
  /// forecast by the same weighted fit on the cluster times of that record.
  /// The data say only that the term is below the bound, so this is the
  /// shortest record that could show it; `record_needed_half_s` is the
  /// same for a term half the bound. Unset when no record up to 10⁹ s would
  /// show it (kMasked) or there is no bound.
  std::optional<double> record_needed_s;
  std::optional<double> record_needed_half_s;
};

/// A stretch of cluster times, s.
struct TauRange {
  double lo_s = 0.0;
  double hi_s = 0.0;
};

/// The fitted model held against the curve of one axis: where the fitted
/// σ(τ) lies outside the curve's confidence interval (AllanOptions::
/// confidence). With only the modelled terms in the record a few cluster
/// times fall outside by chance, in runs (nearby τ are correlated); an
/// effect the model lacks (a low-pass filter, a Gauss-Markov bump, a
/// sinusoid, a temperature ramp) puts a whole stretch outside.
struct ModelCheck {
  /// Cluster times compared (those from `from_tau_s` on); 0: not checked.
  int points = 0;
  /// Of them, those where the fitted σ(τ) lies outside the interval.
  int outside = 0;
  double share_outside = 0.0;  ///< outside / points
  /// The runs of consecutive cluster times outside: τ of the first and last.
  std::vector<TauRange> disagree;
  /// share_outside ≤ NoiseOptions::max_misfit_share.
  bool fits = true;
  /// The shortest cluster time fitted and checked. Above the first one when
  /// the curve's short-τ end lies below the model with a slope nowhere
  /// steeper than −½ (a low-pass filter's roll-off: the −½ slope of the
  /// white noise begins here) and the model fits the curve from here on.
  double from_tau_s = 0.0;
  /// Cluster times below from_tau_s, left out of the fit and the check.
  int excluded = 0;
};

/// A first-order Gauss-Markov process of one axis (exponentially correlated
/// noise, dx/dt = −x/τc + w, stationary standard deviation σ): a bump in the
/// Allan deviation, rising as √τ below τc, peaking at 0.62 σ near 1.89 τc,
/// falling as 1/√τ above (GaussMarkovAvar). In the model only when the
/// curve shows it (the information criterion of docs/method.md).
struct GaussMarkovTerm {
  /// kMeasured: the values below; kNotSeen: no bump the criterion accepts
  /// (or the term left out of the model: `modelled` false); kDisagrees: the
  /// model misses the curve where it dominates.
  TermStatus status = TermStatus::kNotSeen;
  /// NoiseOptions::model_gauss_markov: whether the model could include it.
  bool modelled = true;
  /// Stationary standard deviation σ (u) and its interval; measured only.
  std::optional<double> sigma;
  double sigma_lo = 0.0;
  double sigma_hi = 0.0;
  /// Correlation time τc (s) and its interval; measured only.
  double tau_c_s = 0.0;
  double tau_c_lo_s = 0.0;
  double tau_c_hi_s = 0.0;
  /// The τ range it was read from: where it carries most of the fitted
  /// variance (measured).
  double tau_lo_s = 0.0;
  double tau_hi_s = 0.0;
};

/// A sinusoid of one axis, A sin(2πt/P + φ) (a vibration, a control loop):
/// a hump in the Allan deviation peaking near τ ≈ 0.37 P and falling as 1/τ
/// with ripples at multiples of P (SinusoidAvar). In the model only when
/// the curve shows it.
struct SinusoidTerm {
  /// As GaussMarkovTerm::status.
  TermStatus status = TermStatus::kNotSeen;
  /// NoiseOptions::model_sinusoid.
  bool modelled = true;
  /// Amplitude A (u) and its interval; measured only.
  std::optional<double> amplitude;
  double amplitude_lo = 0.0;
  double amplitude_hi = 0.0;
  /// Period P (s) and its interval; measured only.
  double period_s = 0.0;
  double period_lo_s = 0.0;
  double period_hi_s = 0.0;
  /// The τ range it was read from (measured).
  double tau_lo_s = 0.0;
  double tau_hi_s = 0.0;
};

/// Allan variance (u²) at τ of a first-order Gauss-Markov process of
/// stationary variance σ² and correlation time τc (IEEE Std 952-1997
/// Annex C; El-Sheimy, Hou & Niu 2008, with q² = 2σ²/τc):
///   σ²(τ) = (2σ²τc/τ) [1 − (τc/2τ)(3 − 4e^{−τ/τc} + e^{−2τ/τc})],
/// → 2σ²τ/(3τc) (a random walk) for τ ≪ τc, → 2σ²τc/τ (white) for τ ≫ τc.
double GaussMarkovAvar(double sigma2, double tau_c_s, double tau_s);
/// Allan variance (u²) at τ of A sin(2πt/P + φ) (IEEE Std 952-1997
/// Annex C): σ²(τ) = A² sin⁴(πτ/P) / (πτ/P)².
double SinusoidAvar(double amplitude2, double period_s, double tau_s);

/// One axis: its Allan curve, the five IEEE terms (index: NoiseTerm), and
/// the Gauss-Markov process and sinusoid that real sensors add.
struct AxisNoise {
  std::vector<AllanPoint> curve;
  std::array<TermEstimate, kNoiseTermCount> terms;
  GaussMarkovTerm gauss_markov;
  SinusoidTerm sinusoid;
  /// The fitted model against the curve.
  ModelCheck check;
  /// The fitted model in the variance domain, every term included (Q², N²,
  /// B², K², R²), to draw the fitted curve: a term not measured may carry a
  /// little of it, but is never reported as a value.
  std::array<double, kNoiseTermCount> fit_avar_coefficients{};
  /// The Gauss-Markov process and sinusoid in the fitted model (σ² = 0,
  /// A² = 0: not in it).
  struct FittedGaussMarkov {
    double sigma2 = 0.0;  ///< σ², u²
    double tau_c_s = 0.0;
  } fit_gauss_markov;
  struct FittedSinusoid {
    double amplitude2 = 0.0;  ///< A², u²
    double period_s = 0.0;
  } fit_sinusoid;
  const TermEstimate& term(NoiseTerm t) const { return terms[static_cast<int>(t)]; }
  /// The fitted σ²(τ) (u²): fit_avar_coefficients, fit_gauss_markov and
  /// fit_sinusoid.
  double FittedAvar(double tau_s) const;
};

/// Options of the noise analysis.
struct NoiseOptions {
  AllanOptions allan;
  /// A term counts as seen at a τ where it is at least this fraction of the
  /// fitted variance.
  double dominance = 0.5;
  /// Cluster times at which it must be seen (at 4 per octave, 5 = an
  /// octave).
  int min_region_points = 5;
  /// Iterations of the reweighted fit (weights from the model's variance).
  int fit_iterations = 4;
  /// Overlapping estimates at nearby τ are strongly correlated; the fit's
  /// covariance counts this many independent points per octave (it is
  /// inflated by points_per_octave / this). Set by simulation (tests and
  /// bench/noise_study): with 0.5, the intervals of N and K cover the truth
  /// at about their nominal rate.
  double independent_points_per_octave = 0.5;
  /// The model fits the curve when at most this share of the cluster times
  /// lie outside the curve's interval. Set by simulation (bench/independent
  /// records with only the modelled terms: at most 0.21 of 61 cluster times
  /// on 90 axes of 1 h at 100 Hz; with a low-pass filter or a Gauss-Markov
  /// bump left out of the model, 0.8 to 1).
  double max_misfit_share = 0.25;
  /// Whether the model may include a first-order Gauss-Markov process and a
  /// sinusoid (each only when the curve shows it). Off: the model has the
  /// IEEE terms alone, and the check flags a bump or a sinusoid it lacks.
  bool model_gauss_markov = true;
  bool model_sinusoid = true;

  std::string Validate() const;
};

/// One 3-axis sensor: its three axes.
struct SensorNoise {
  std::array<AxisNoise, 3> axes;
  /// Mean removed per axis (u): the bias over the record.
  Eigen::Vector3d mean_si = Eigen::Vector3d::Zero();
  /// Per term (index: NoiseTerm), how long to record to measure it: the
  /// longest TermEstimate::record_needed_s (and record_needed_half_s) of the
  /// axes where it was not seen, so that a record of that length shows it on
  /// every one of them; unset when none of them has one. The one figure of
  /// "how long must I record" (SetRecordNeeded).
  std::array<std::optional<double>, kNoiseTermCount> record_needed_s{};
  std::array<std::optional<double>, kNoiseTermCount> record_needed_half_s{};
};

/// Sets `sensor.record_needed_s` and `record_needed_half_s` from its axes.
void SetRecordNeeded(SensorNoise& sensor);

/// A record length in words: "40 s", "46 min", "2.3 h" (the one format of
/// record lengths in tables, warnings and file comments).
std::string FormatRecordLength(double seconds);

/// Cluster-time ranges in words, the longest `max_ranges` of them in τ
/// order: "0.0025–1.2 s, 40–90 s" (and "+ 2 more" when some are left out;
/// one τ: "0.5 s").
std::string FormatTauRanges(const std::vector<TauRange>& ranges, int max_ranges);

/// Allan curves and terms of a sensor from its sums (AllanSums::Curves
/// with the same `si_per_unit` and `sample_period_s`).
/// \throws mpcal::Error as AllanSums::Curves, or for invalid options.
SensorNoise AnalyseSensorNoise(const AllanSums& sums,
                               double si_per_unit,
                               double sample_period_s,
                               const NoiseOptions& options);

/// Which samples of a recording were analysed.
enum class NoiseSegmentKind {
  kWholeRecord,   ///< detection found no motion
  kLongestStill,  ///< the longest static interval (the sensor moved)
};
std::string_view ToString(NoiseSegmentKind kind);

struct NoiseSegment {
  NoiseSegmentKind kind = NoiseSegmentKind::kWholeRecord;
  std::size_t begin = 0;
  std::size_t end = 0;
  std::size_t static_intervals = 0;  ///< found by detection
};

/// The whole record when detection found it all still (one interval from
/// within a settle time of its start to its end), else the longest static
/// interval. std::nullopt when detection found none.
std::optional<NoiseSegment> ChooseNoiseSegment(const RecordingView& recording,
                                               const DetectResult& detection);

/// The analysis of a recording.
struct NoiseResult {
  NoiseSegment segment;
  /// The rate: samples over the span, (n − 1) / (t_last − t_first)
  /// (NoiseStream); the period its inverse.
  double sample_period_s = 0.0;
  double rate_hz = 0.0;
  double record_s = 0.0;    ///< duration analysed
  std::size_t samples = 0;  ///< samples analysed
  /// Samples spaced more than 1.5 τ0 from the previous one (lost data; the
  /// analysis treats the samples as evenly spaced).
  std::size_t gaps = 0;
  /// Accelerometer (u = m/s²) and gyroscope (u = rad/s; unset without one).
  SensorNoise accel_mps2;
  std::optional<SensorNoise> gyro_radps;
};

/// How an axis shows that its sensor is not producing noise: an Allan
/// deviation of it would measure the logger or the quantiser, not the sensor.
enum class SignalFault {
  kStuck,            ///< one value throughout (stuck, or clipped at a limit)
  kTwoValued,        ///< two values only (a toggling bit)
  kBelowResolution,  ///< its scatter from sample to sample (the Allan
                     ///< deviation at τ0) is below its resolution (the
                     ///< smallest change): the quantiser, not the noise
};
/// "stuck", "two_valued", "below_resolution".
std::string_view ToString(SignalFault fault);

/// One axis that is not producing noise, with the figures that say so (in
/// the sensor's SI unit: m/s² or rad/s).
struct AxisSignalFault {
  bool gyroscope = false;
  int axis = 0;  ///< 0, 1, 2: x, y, z
  SignalFault fault = SignalFault::kStuck;
  double value_si = 0.0;       ///< its first value (stuck: the value)
  double resolution_si = 0.0;  ///< the smallest change between samples
  double adev_tau0_si = 0.0;   ///< the Allan deviation at one sample period
};

/// The axes of a sensor that are not producing noise, from its sums (empty
/// when all three are). `si_per_unit`: the factor to the SI unit.
std::vector<AxisSignalFault> SignalFaults(const AllanSums& sums,
                                          double si_per_unit,
                                          bool gyroscope);

/// The noise of a record analysed as its rows arrive (in time order, split
/// anyhow), none of them held: the Allan sums of both sensors (AllanSums),
/// the sample rate and the gaps, and, when asked, whether the sensor stayed
/// still throughout by detection's rule (StillnessMonitor). Memory: a few
/// MB for a record of any length.
///
/// The sample rate is the count of samples over the span, (n − 1) /
/// (t_last − t_first): a clock of coarse resolution (a millisecond clock at
/// 300 Hz steps 3, 3, 4 ms) and time stamps too large for a double to
/// resolve one step (1e11 s) both give the rate the logger ran at, which
/// the median of the steps does not. The rate must be the same throughout: the mean
/// step of every block of kUniformBlockSteps steps (and of the last, shorter
/// one when it has a quarter of that) lies within kUniformTolerance of every
/// other; a change of rate or a large gap (more than about 50 samples lost
/// at once) is refused, as the Allan deviation assumes one sample period. A
/// gap is a step longer than 1.5 times the median of the first 1,024 steps
/// (known before the record ends); a few short gaps are counted, and the
/// samples treated as evenly spaced.
class NoiseStream {
 public:
  /// Steps per block of the uniformity test.
  static constexpr std::size_t kUniformBlockSteps = 1024;
  /// Largest spread of the blocks' mean steps, as a fraction of the smallest.
  static constexpr double kUniformTolerance = 0.05;

  /// `stillness`: judge stillness with these detection options (nullptr:
  /// not judged). `accel_units`: the accelerometer's units (for the range
  /// limits of the stillness judgement).
  NoiseStream(const NoiseOptions& options,
              const DetectOptions* stillness,
              AccelUnits accel_units);
  ~NoiseStream();
  NoiseStream(const NoiseStream&) = delete;
  NoiseStream& operator=(const NoiseStream&) = delete;

  /// Adds rows [begin, end) of `rows` (its gyroscope empty, or one reading
  /// per row, the same in every call; times strictly increasing), read
  /// where they are. Large blocks run the gyroscope's sums on a second
  /// thread.
  /// \throws NotFiniteError for a row holding a NaN or an infinity.
  void Add(const RecordingView& rows, std::size_t begin, std::size_t end);
  void Add(const RecordingView& rows) { Add(rows, 0, rows.size()); }
  std::size_t rows() const { return rows_; }
  bool has_gyro() const { return has_gyro_; }
  /// Unset when stillness is not judged.
  std::optional<StillVerdict> Stillness() const;
  /// The axes of both sensors that are not producing noise (SignalFaults).
  std::vector<AxisSignalFault> Faults(double accel_mps2_per_unit) const;
  /// The analysis of the rows added, as `segment` of the recording.
  /// `accel_mps2_per_unit`: the factor from the log's units to m/s².
  /// \throws mpcal::Error for fewer than 9 rows; (kTime) for a span that is
  ///   not a positive time, a rate above kMaxSampleRateHz, or a rate that
  ///   is not uniform (see the class comment), naming the rates and where;
  ///   for an axis that is not producing noise (Faults), naming each; or
  ///   invalid options.
  NoiseResult Finish(double accel_mps2_per_unit, const NoiseSegment& segment) const;

 private:
  // The mean step of a block of steps and the time it began.
  struct BlockStep {
    double step_s = 0.0;
    double at_s = 0.0;
  };
  void AddSteps(std::span<const double> t, std::size_t begin, std::size_t end);
  void NoteBlock(double step_s, double at_s);

  NoiseOptions options_;
  std::string source_;
  std::size_t rows_ = 0;
  bool has_gyro_ = false;
  AllanSums accel_;
  AllanSums gyro_;
  std::unique_ptr<StillnessMonitor> stillness_;
  double first_time_s_ = 0.0;
  double last_time_s_ = 0.0;
  double block_begin_s_ = 0.0;  // the time the current block began
  std::size_t block_steps_ = 0;
  std::optional<BlockStep> shortest_, longest_;  // of the full blocks
  GapCounter gaps_;
};

/// Analyses recording[segment] (a NoiseStream over it, not judging
/// stillness). `accel_mps2_per_unit`: the factor from the log's units to
/// m/s².
/// \throws mpcal::Error for invalid options, fewer than 9 samples, or a
///   segment outside the recording; as NoiseStream::Finish (a rate that is
///   not uniform, an axis that produces no noise).
NoiseResult AnalyseNoise(const RecordingView& recording,
                         const NoiseSegment& segment,
                         double accel_mps2_per_unit,
                         const NoiseOptions& options);

/// The white noise density of each axis (m/s²/√Hz, the N of this file)
/// from the scatter of the static positions of a calibration: the pooled
/// within-position variance s² (each position's sample_std_mps2, weighted by
/// its samples − 1) over its sample rate, N² = s²/f_s. Over positions of a
/// few seconds it is the white noise, as `AnalyseNoise` finds it at short τ
/// (it includes the little the other terms add over a position). nullopt
/// without a position of at least 2 samples and a positive duration.
std::optional<Eigen::Vector3d> WhiteNoiseFromPositions(
    const std::vector<PositionSummary>& positions);

}  // namespace mpcal
