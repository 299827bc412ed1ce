// The noise of a record as its rows arrive (NoiseStream): both sensors'
// Allan sums, the sample period and the gaps, and the stillness judgement.
#include <exception>
#include <memory>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "mpcal/error.h"
#include "mpcal/noise.h"

namespace mpcal {
namespace {

// Steps whose median is the reference of a gap.
constexpr std::size_t kGapReferenceSteps = 1024;
// A step this many times the reference is a gap (samples lost).
constexpr double kGapFactor = 1.5;
// Blocks this large run the gyroscope's sums on a second thread (below it,
// starting the thread costs more than it saves).
constexpr std::size_t kParallelRows = std::size_t{1} << 16;

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

void NoiseStream::AddSteps(const std::vector<double>& t,
                           std::size_t begin,
                           std::size_t end) {
  gaps_.Add(std::span<const double>(t.data() + begin, end - begin));
  for (std::size_t i = begin; i < end; ++i) {
    if (rows_ + (i - begin) > 0) steps_.Add(t[i] - last_time_s_);
    last_time_s_ = t[i];
  }
}

void NoiseStream::Add(const Recording& rows, std::size_t begin, std::size_t end) {
  if (end <= begin) return;
  if (rows_ == 0) {
    source_ = rows.source;
    has_gyro_ = rows.gyro_radps.size() == rows.size();
  }
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
  NoiseResult r;
  r.segment = segment;
  r.sample_period_s = steps_.Quantile(0.5);
  if (!(r.sample_period_s > 0.0))
    throw Error(ErrorKind::kTime, source_ + ": no sample spacing");
  r.rate_hz = 1.0 / r.sample_period_s;
  GapCounter gaps = gaps_;  // a copy: Finish counts the steps still held
  gaps.Finish();
  r.gaps = gaps.gaps();
  r.samples = rows_;
  r.record_s = static_cast<double>(r.samples) * r.sample_period_s;
  r.accel_mps2 =
      AnalyseSensorNoise(accel_, accel_mps2_per_unit, r.sample_period_s, options_);
  if (has_gyro_)
    r.gyro_radps = AnalyseSensorNoise(gyro_, 1.0, r.sample_period_s, options_);
  return r;
}

NoiseResult AnalyseNoise(const Recording& recording,
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
