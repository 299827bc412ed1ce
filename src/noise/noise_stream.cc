// The noise of a record as its rows arrive (NoiseStream): both sensors'
// Allan sums, the sample period and the gaps, and the stillness judgement.
#include <cmath>
#include <exception>
#include <memory>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "mpcal/not_finite.h"

#include "mpcal/error.h"
#include "mpcal/noise.h"
#include "mpcal/plausible.h"

namespace mpcal {
namespace {

// Steps whose median is the reference of a gap.
constexpr std::size_t kGapReferenceSteps = 1024;
// A step this many times the reference is a gap (samples lost).
constexpr double kGapFactor = 1.5;
// Blocks this large run the gyroscope's sums on a second thread (below it,
// starting the thread costs more than it saves).
constexpr std::size_t kParallelRows = std::size_t{1} << 16;

// The faults in one sentence, one clause per axis.
std::string DescribeFaults(const std::vector<AxisSignalFault>& faults) {
  std::string out =
      "not producing noise, so no Allan deviation of it measures the sensor:";
  for (std::size_t i = 0; i < faults.size(); ++i) {
    const AxisSignalFault& f = faults[i];
    const char* unit = f.gyroscope ? "rad/s" : "m/s²";
    out += fmt::format("{} {} {}: ",
                       i == 0 ? "" : ";",
                       f.gyroscope ? "gyroscope" : "accelerometer",
                       static_cast<char>('x' + f.axis));
    switch (f.fault) {
      case SignalFault::kStuck:
        out += fmt::format("stuck at {:.6g} {} (one value throughout)", f.value_si, unit);
        break;
      case SignalFault::kTwoValued:
        out += fmt::format("two values only, {:.6g} {} apart", f.resolution_si, unit);
        break;
      case SignalFault::kBelowResolution:
        out += fmt::format(
            "quantised beyond use (scatter {:.3g} {} per sample, below its "
            "resolution {:.3g} {})",
            f.adev_tau0_si,
            unit,
            f.resolution_si,
            unit);
        break;
    }
  }
  return out;
}

}  // namespace

NoiseStream::NoiseStream(const NoiseOptions& options,
                         const DetectOptions* stillness,
                         AccelUnits accel_units)
    : options_(options),
      accel_(options.allan),
      gyro_(options.allan),
      gaps_(kGapReferenceSteps, kGapFactor) {
  if (const std::string bad = options.Validate(); !bad.empty()) {
    throw Error(ErrorKind::kOption, "noise options: " + bad);
  }
  if (stillness != nullptr) {
    stillness_ = std::make_unique<StillnessMonitor>(*stillness, accel_units);
  }
}

NoiseStream::~NoiseStream() = default;

void NoiseStream::NoteBlock(double step_s, double at_s) {
  if (!shortest_ || step_s < shortest_->step_s) shortest_ = BlockStep{step_s, at_s};
  if (!longest_ || step_s > longest_->step_s) longest_ = BlockStep{step_s, at_s};
}

// The mean step of each block is a difference of two times a block apart:
// it keeps its digits where a single step of a large time stamp does not.
void NoiseStream::AddSteps(std::span<const double> t,
                           std::size_t begin,
                           std::size_t end) {
  gaps_.Add(t.subspan(begin, end - begin));
  if (rows_ == 0) first_time_s_ = block_begin_s_ = t[begin];
  for (std::size_t i = begin; i < end; ++i) {
    if (rows_ + (i - begin) == 0) continue;
    if (++block_steps_ == kUniformBlockSteps) {
      NoteBlock((t[i] - block_begin_s_) / static_cast<double>(kUniformBlockSteps),
                block_begin_s_);
      block_begin_s_ = t[i];
      block_steps_ = 0;
    }
  }
  last_time_s_ = t[end - 1];
}

void NoiseStream::Add(const RecordingView& rows, std::size_t begin, std::size_t end) {
  if (end <= begin) return;
  if (rows_ == 0) {
    source_ = rows.source;
    has_gyro_ = rows.gyro_radps.size() == rows.size();
  }
  // The first read of these rows: a view of the caller's memory may hold
  // what no log reader gives, which the sums would carry into every figure.
  RefuseNotFinite(rows, begin, end);
  AddSteps(rows.time_s, begin, end);
  std::exception_ptr gyro_error;
  std::thread gyro_thread;
  auto gyro_sums = [&] {
    try {
      gyro_.Add(rows.gyro_radps.data() + begin, end - begin);
    } catch (...) {
      gyro_error = std::current_exception();
    }
  };
  if (has_gyro_ && end - begin >= kParallelRows) {
    gyro_thread = std::thread(gyro_sums);
  } else if (has_gyro_) {
    gyro_sums();
  }
  accel_.Add(rows.accel.data() + begin, end - begin);
  if (stillness_) {
    stillness_->Add(
        std::span<const double>(rows.time_s.data() + begin, end - begin),
        std::span<const Eigen::Vector3d>(rows.accel.data() + begin, end - begin));
  }
  if (gyro_thread.joinable()) gyro_thread.join();
  if (gyro_error) std::rethrow_exception(gyro_error);
  rows_ += end - begin;
}

std::vector<AxisSignalFault> NoiseStream::Faults(double accel_mps2_per_unit) const {
  std::vector<AxisSignalFault> out = SignalFaults(accel_, accel_mps2_per_unit, false);
  if (has_gyro_) {
    const std::vector<AxisSignalFault> g = SignalFaults(gyro_, 1.0, true);
    out.insert(out.end(), g.begin(), g.end());
  }
  return out;
}

std::optional<StillVerdict> NoiseStream::Stillness() const {
  if (!stillness_) return std::nullopt;
  return stillness_->Verdict();
}

NoiseResult NoiseStream::Finish(double accel_mps2_per_unit,
                                const NoiseSegment& segment) const {
  if (rows_ < 9) {
    throw Error(
        ErrorKind::kInput,
        fmt::format("{}: {} samples are too few for an Allan deviation (at least 9)",
                    source_,
                    rows_));
  }
  const double span_s = last_time_s_ - first_time_s_;
  const double rate_hz = static_cast<double>(rows_ - 1) / span_s;
  if (!(span_s > 0.0) || !std::isfinite(rate_hz) || rate_hz > kMaxSampleRateHz) {
    throw Error(ErrorKind::kTime,
                fmt::format("{}: {} samples over {:.6g} s is not a sample rate (above "
                            "{:g} Hz): the time column is not a time in the unit it "
                            "is read in",
                            source_,
                            rows_,
                            span_s,
                            kMaxSampleRateHz));
  }
  std::optional<BlockStep> shortest = shortest_, longest = longest_;
  if (block_steps_ >= kUniformBlockSteps / 4 && (shortest || longest)) {
    const BlockStep tail{
        (last_time_s_ - block_begin_s_) / static_cast<double>(block_steps_),
        block_begin_s_};
    if (tail.step_s < shortest->step_s) shortest = tail;
    if (tail.step_s > longest->step_s) longest = tail;
  }
  GapCounter gaps = gaps_;  // a copy: Finish counts the steps still held
  gaps.Finish();
  if (shortest && longest->step_s > (1.0 + kUniformTolerance) * shortest->step_s) {
    // A gap long enough to break uniformity on its own is named.
    const bool long_gap =
        gaps.largest_s() >
        kUniformTolerance * static_cast<double>(kUniformBlockSteps) * gaps.typical_s();
    throw Error(
        ErrorKind::kTime,
        fmt::format("{}: the sample rate is not uniform: {:.6g} Hz near t = {:.1f} s, "
                    "{:.6g} Hz near t = {:.1f} s ({}); the Allan deviation needs one "
                    "rate: analyse a stretch of one rate",
                    source_,
                    1.0 / shortest->step_s,
                    shortest->at_s - first_time_s_,
                    1.0 / longest->step_s,
                    longest->at_s - first_time_s_,
                    long_gap ? fmt::format("no samples for {:.3g} s after t = {:.1f} s",
                                           gaps.largest_s(),
                                           gaps.largest_at_s() - first_time_s_)
                             : std::string("the rate changes, or samples were lost")));
  }
  if (const std::vector<AxisSignalFault> faults = Faults(accel_mps2_per_unit);
      !faults.empty()) {
    throw Error(ErrorKind::kInput, source_ + ": " + DescribeFaults(faults));
  }
  NoiseResult r;
  r.segment = segment;
  r.rate_hz = rate_hz;
  r.sample_period_s = 1.0 / rate_hz;
  r.gaps = gaps.gaps();
  r.samples = rows_;
  r.record_s = static_cast<double>(r.samples) * r.sample_period_s;
  r.accel_mps2 =
      AnalyseSensorNoise(accel_, accel_mps2_per_unit, r.sample_period_s, options_);
  if (has_gyro_)
    r.gyro_radps = AnalyseSensorNoise(gyro_, 1.0, r.sample_period_s, options_);
  return r;
}

NoiseResult AnalyseNoise(const RecordingView& recording,
                         const NoiseSegment& segment,
                         double accel_mps2_per_unit,
                         const NoiseOptions& options) {
  if (segment.end > recording.size() || segment.begin + 9 > segment.end) {
    throw Error(
        ErrorKind::kInput,
        fmt::format("{}: {} samples are too few for an Allan deviation (at least 9)",
                    recording.source,
                    segment.end > segment.begin ? segment.end - segment.begin : 0));
  }
  NoiseStream stream(options, nullptr, recording.units);
  stream.Add(recording, segment.begin, segment.end);
  return stream.Finish(accel_mps2_per_unit, segment);
}

}  // namespace mpcal
