// The steps of ApplyCalibration (apply_steps.h).
#include "apply/apply_steps.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>

#include <fmt/format.h>

#include "mpcal/units.h"

namespace mpcal::internal {
namespace {

// Rows per block of the magnitude-at-rest check, and the blocks kept.
constexpr std::size_t kRestBlockRows = 32;
constexpr std::size_t kRestMaxBlocks = 8192;
// Raw readings within this fraction of 1/9.81 or 9.81 times gravity are a
// g/m/s² mix-up.
constexpr double kUnitsMixUpTolerance = 0.2;

// The unit in brackets of an accelerometer column's name, as written for
// `units`: "m/s^2" (phyphox's spelling), "g"; empty for counts.
bool IsUnitLabelOf(std::string_view label, AccelUnits units) {
  std::string l;
  for (char c : label) {
    if (c != ' ')
      l.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  }
  if (units == AccelUnits::kG) return l == "g";
  if (units == AccelUnits::kMps2) {
    return l == "m/s^2" || l == "m/s2" || l == "m/s\xc2\xb2" || l == "ms^-2" ||
           l == "ms-2" || l == "mps2";
  }
  return false;
}

// One header field with its unit label rewritten when it is `from`'s.
void Relabel(std::string& field, AccelUnits from, std::string_view label) {
  const std::size_t open = field.find_first_of("([");
  if (open == std::string::npos) return;
  const char close = field[open] == '(' ? ')' : ']';
  const std::size_t end = field.find(close, open + 1);
  if (end != std::string::npos &&
      IsUnitLabelOf(std::string_view(field).substr(open + 1, end - open - 1), from)) {
    field.replace(open + 1, end - open - 1, label);
  }
}

}  // namespace

// Magnitudes are averaged sample by sample, so that a block spanning two
// orientations still measures |a|; such a block moves more than a still one
// and is not among the quietest anyway.
void RestSummary::Add(const Eigen::Vector3d& a_mps2, const Eigen::Vector3d& raw) {
  if (blocks_.size() >= kRestMaxBlocks) return;
  sum_ += a_mps2;
  const double sq = a_mps2.squaredNorm();
  sum_sq_ += sq;
  sum_norm_ += std::sqrt(sq);
  raw_sum_norm_ += raw.norm();
  ++n_;
  if (n_ == kRestBlockRows) Close();
}

void RestSummary::Close() {
  const double count = static_cast<double>(n_);
  const Eigen::Vector3d mean = sum_ / count;
  blocks_.push_back({sum_norm_ / count,
                     raw_mps2_per_unit_ * raw_sum_norm_ / count,
                     std::max(0.0, sum_sq_ / count - mean.squaredNorm())});
  sum_.setZero();
  sum_norm_ = raw_sum_norm_ = sum_sq_ = 0.0;
  n_ = 0;
}

std::optional<Rest> RestSummary::Finish() {
  if (n_ > 0 && blocks_.size() < kRestMaxBlocks) Close();
  if (blocks_.empty()) return std::nullopt;
  // The quietest quarter: at rest, or as close to it as the log comes.
  std::sort(blocks_.begin(), blocks_.end(), [](const Block& a, const Block& b) {
    return a.motion < b.motion;
  });
  const std::size_t quiet = std::max<std::size_t>(1, blocks_.size() / 4);
  std::vector<double> magnitudes;
  std::vector<double> raw;
  for (std::size_t i = 0; i < quiet; ++i) {
    magnitudes.push_back(blocks_[i].magnitude);
    raw.push_back(blocks_[i].raw_magnitude);
  }
  const auto mid = static_cast<std::ptrdiff_t>(quiet / 2);
  std::nth_element(magnitudes.begin(), magnitudes.begin() + mid, magnitudes.end());
  std::nth_element(raw.begin(), raw.begin() + mid, raw.end());
  return Rest{magnitudes[quiet / 2], raw[quiet / 2]};
}

std::optional<RestMismatch> CheckRestMagnitude(const Rest& rest,
                                               double gravity_mps2,
                                               double tolerance,
                                               AccelUnits log_units,
                                               std::string_view source) {
  const double g = gravity_mps2;
  const double m = rest.magnitude_mps2;
  if (!(std::abs(m - g) > tolerance * g)) return std::nullopt;
  RestMismatch mismatch;
  mismatch.magnitude_mps2 = m;
  mismatch.gravity_mps2 = g;
  mismatch.what = fmt::format(
      "{}: the corrected magnitude at rest is {:.4g} m/s², {:.1f}% from the "
      "calibration's gravity {:.6g} m/s²",
      source,
      m,
      100.0 * (m - g) / g,
      g);
  // The raw readings tell a units mix-up (a factor 9.8) from a sensor mix-up
  // (errors of a few percent).
  const double raw_ratio = rest.raw_magnitude_mps2 / g;
  mismatch.advice.settings = {{Option::kLogUnits, ""}};
  if (log_units == AccelUnits::kCounts) return mismatch;
  if (std::abs(raw_ratio * kStandardGravityMps2 - 1.0) < kUnitsMixUpTolerance) {
    mismatch.kind = RestMismatchKind::kLooksLikeG;
    mismatch.advice.settings = {{Option::kLogUnits, "g"}};
  } else if (std::abs(raw_ratio / kStandardGravityMps2 - 1.0) < kUnitsMixUpTolerance) {
    mismatch.kind = RestMismatchKind::kLooksLikeMps2;
    mismatch.advice.settings = {{Option::kLogUnits, "mps2"}};
  }
  return mismatch;
}

std::string RelabelHeader(std::string_view header,
                          const LogLayout& layout,
                          AccelUnits from,
                          AccelUnits to) {
  if (from == to || layout.delimiter == ' ') return std::string(header);
  const std::string_view label = to == AccelUnits::kG ? "g" : "m/s^2";
  std::string out;
  int column = 0;
  std::size_t start = 0;
  while (start <= header.size()) {
    std::size_t stop = header.find(layout.delimiter, start);
    if (stop == std::string_view::npos) stop = header.size();
    std::string field(header.substr(start, stop - start));
    const bool accel =
        std::find(layout.accel_columns.begin(), layout.accel_columns.end(), column) !=
        layout.accel_columns.end();
    if (accel) Relabel(field, from, label);
    out += field;
    if (stop == header.size()) break;
    out += layout.delimiter;
    start = stop + 1;
    ++column;
  }
  return out;
}

void AppendCorrectedRow(const LogLine& line,
                        const Eigen::Matrix<double, 6, 1>& values,
                        int count,
                        char decimal_point,
                        std::string& out) {
  const auto span = [&](int i) {
    return i < 3 ? line.accel_span[static_cast<std::size_t>(i)]
                 : line.gyro_span[static_cast<std::size_t>(i - 3)];
  };
  std::array<int, 6> order = {0, 1, 2, 3, 4, 5};
  // The numbers replaced first, in the order they lie on the line; the
  // others after them (a fixed size keeps the sort in bounds).
  std::sort(order.begin(), order.end(), [&](int i, int j) {
    if ((i < count) != (j < count)) return i < count;
    return span(i).first < span(j).first;
  });
  std::size_t copied = 0;
  for (int k = 0; k < count; ++k) {
    const int axis = order[static_cast<std::size_t>(k)];
    const auto [begin, end] = span(axis);
    out.append(line.text.substr(copied, begin - copied));
    std::array<char, 32> number{};
    const auto r =
        std::to_chars(number.data(), number.data() + number.size(), values[axis]);
    if (decimal_point != '.') std::replace(number.data(), r.ptr, '.', decimal_point);
    out.append(number.data(), r.ptr);
    copied = end;
  }
  out.append(line.text.substr(copied));
  out.append(line.eol);
}

}  // namespace mpcal::internal
