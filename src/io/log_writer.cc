// CSV logs from a Recording (log_writer.h).
#include "mpcal/log_writer.h"

#include <charconv>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "mpcal/atomic_file.h"
#include "mpcal/error.h"

namespace mpcal {
namespace {

// Rows are formatted into one buffer and handed to the stream in large
// blocks: std::to_chars is several times faster than iostream formatting,
// and a simulated session can have millions of rows.
constexpr std::size_t kFlushBytes = std::size_t{1} << 20;
// Whole numbers up to 2^53 are exact in a double.
constexpr double kLargestExactInteger = 9007199254740992.0;

class RowWriter {
 public:
  RowWriter(std::ostream& out, int digits) : out_(out), digits_(digits) {
    buffer_.reserve(kFlushBytes + 4096);
  }

  void Exact(double v) {
    char* end = std::to_chars(scratch_, scratch_ + sizeof scratch_, v).ptr;
    buffer_.append(scratch_, end);
  }
  void Value(double v) {
    if (digits_ == 0) return Exact(v);
    char* end =
        std::to_chars(
            scratch_, scratch_ + sizeof scratch_, v, std::chars_format::general, digits_)
            .ptr;
    buffer_.append(scratch_, end);
  }
  void Count(double v) {
    if (v == std::nearbyint(v) && std::abs(v) <= kLargestExactInteger) {
      char* end =
          std::to_chars(scratch_, scratch_ + sizeof scratch_, static_cast<long long>(v))
              .ptr;
      buffer_.append(scratch_, end);
    } else {
      Exact(v);
    }
  }
  void Char(char c) { buffer_.push_back(c); }
  void Text(const char* s) { buffer_.append(s); }
  void EndRow() {
    buffer_.push_back('\n');
    if (buffer_.size() >= kFlushBytes) Flush();
  }
  void Flush() {
    out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    buffer_.clear();
    if (!out_) throw Error("writing the log failed (disk full or closed output?)");
  }

 private:
  std::ostream& out_;
  int digits_;
  std::string buffer_;
  char scratch_[64];
};

void CheckFinite(const Eigen::Vector3d& v, std::size_t row, const char* what) {
  if (!v.allFinite()) {
    throw Error(
        fmt::format("cannot write the log: the {} reading of sample {} is not finite "
                    "({}, {}, {})",
                    what,
                    row,
                    v.x(),
                    v.y(),
                    v.z()));
  }
}

}  // namespace

std::string LogWriteOptions::Validate() const {
  if (significant_digits < 0 || significant_digits > 17) {
    return fmt::format("significant_digits must be between 0 (exact) and 17 (got {})",
                       significant_digits);
  }
  return "";
}

void WriteRecordingCsv(std::ostream& out,
                       const Recording& recording,
                       const LogWriteOptions& options) {
  if (const std::string problem = options.Validate(); !problem.empty()) {
    throw Error("invalid log-writing options: " + problem);
  }
  const std::size_t n = recording.time_s.size();
  if (recording.accel.size() != n) {
    throw Error(
        fmt::format("cannot write the log of {}: {} times but {} accelerometer readings",
                    recording.source,
                    n,
                    recording.accel.size()));
  }
  const bool gyro = !recording.gyro_radps.empty();
  if (gyro && recording.gyro_radps.size() != n) {
    throw Error(
        fmt::format("cannot write the log of {}: {} times but {} gyroscope readings",
                    recording.source,
                    n,
                    recording.gyro_radps.size()));
  }
  const bool counts = recording.units == AccelUnits::kCounts;
  RowWriter w(out, options.significant_digits);
  w.Text(gyro ? "t,ax,ay,az,gx,gy,gz" : "t,ax,ay,az");
  w.EndRow();
  for (std::size_t i = 0; i < n; ++i) {
    const double t = recording.time_s[i];
    if (!std::isfinite(t)) {
      throw Error(
          fmt::format("cannot write the log: the time of sample {} is not finite", i));
    }
    const Eigen::Vector3d& a = recording.accel[i];
    CheckFinite(a, i, "accelerometer");
    w.Exact(t);
    for (int k = 0; k < 3; ++k) {
      w.Char(',');
      if (counts) {
        w.Count(a[k]);
      } else {
        w.Value(a[k]);
      }
    }
    if (gyro) {
      const Eigen::Vector3d& g = recording.gyro_radps[i];
      CheckFinite(g, i, "gyroscope");
      for (int k = 0; k < 3; ++k) {
        w.Char(',');
        w.Value(g[k]);
      }
    }
    w.EndRow();
  }
  w.Flush();
}

void WriteRecordingFile(const std::string& path,
                        const Recording& recording,
                        const LogWriteOptions& options) {
  WriteStreamAtomically(
      path, [&](std::ostream& out) { WriteRecordingCsv(out, recording, options); });
}

}  // namespace mpcal
