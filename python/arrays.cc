#include "arrays.h"

#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

#include <fmt/format.h>

#include "errors.h"
#include "mpcal/advice.h"
#include "mpcal/error.h"
#include "mpcal/units.h"

namespace mpcal::python {

// A Vector3d is three doubles with no padding, so a vector of them is an
// N×3 C-order array and numpy can look at it in place.
static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double));

py::array ViewOf(const double* values, std::size_t rows, int columns, py::handle owner) {
  const auto n = static_cast<py::ssize_t>(rows);
  py::array view;
  if (columns == 1) {
    view = py::array_t<double>(
        {n}, {static_cast<py::ssize_t>(sizeof(double))}, values, owner);
  } else {
    const auto c = static_cast<py::ssize_t>(columns);
    view = py::array_t<double>({n, c},
                               {static_cast<py::ssize_t>(sizeof(double)) * c,
                                static_cast<py::ssize_t>(sizeof(double))},
                               values,
                               owner);
  }
  view.attr("setflags")(py::arg("write") = false);
  return view;
}

namespace {

// Fresh memory is mapped by the kernel page by page as it is first written:
// for the 54 MB of a 1.7 M-row session, 13,000 faults of 4 KiB pages, which
// cost more than the copy itself. Where the kernel gives huge pages (2 MiB)
// on request, asking for them leaves a few dozen. Only a hint: without it
// the copy is the same, slower.
void AdviseHugePages(const void* data, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kHuge = std::uintptr_t{2} << 20;
  const auto begin = (reinterpret_cast<std::uintptr_t>(data) + kHuge - 1) & ~(kHuge - 1);
  const auto end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(kHuge - 1);
  if (end > begin) {
    // NOLINTNEXTLINE(performance-no-int-to-ptr): the address of our own block
    madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
  }
#else
  (void)data;
  (void)bytes;
#endif
}

// `count` doubles of `in` copied into the empty vector `out`. Reserved, not
// resized (which would write every value twice, zeros first).
void CopyRows(const double* in, std::size_t count, std::vector<double>& out) {
  out.reserve(count);
  AdviseHugePages(out.data(), count * sizeof(double));
  out.insert(out.end(), in, in + count);
}

// Whether `data` may be seen as doubles in place (numpy's arrays are,
// unless made from a packed buffer).
bool AlignedForDoubles(const double* data) {
  return reinterpret_cast<std::uintptr_t>(data) % alignof(double) == 0;
}

// The caller's `count` doubles at `data` as the library reads them: in
// place when aligned as doubles, else copied into `own`.
std::span<const double> SeeOrCopy(const double* data,
                                  std::size_t count,
                                  std::vector<double>& own) {
  if (AlignedForDoubles(data)) return {data, count};
  CopyRows(data, count, own);
  return own;
}

}  // namespace

AccelUnits AccelUnitsArgument(const std::string& name, const char* argument) {
  const auto units = ParseAccelUnits(name);
  if (!units) {
    throw Error(ErrorKind::kOption,
                fmt::format("{}='{}' is not a unit of acceleration: give 'mps2', 'g' or "
                            "'counts'",
                            argument,
                            name),
                Suggest(Option::kLogUnits, ""));
  }
  return *units;
}

GyroUnits GyroUnitsArgument(const std::string& name, const char* argument) {
  const auto units = ParseGyroUnits(name);
  if (!units) {
    throw Error(
        ErrorKind::kOption,
        fmt::format("{}='{}' is not a unit of angular rate: give 'rads', 'dps' or "
                    "'counts'",
                    argument,
                    name),
        Suggest(Option::kLogGyroUnits, ""));
  }
  return *units;
}

namespace {

// A gyroscope recorded apart (read_log with gyro_log or gyro_topic) keeps its
// own samples beside the rows (Recording::gyro_samples), over which the
// turns are integrated. Rows given back as that Recording's own arrays, not
// copies, carry them, so that calibrate gives the command's numbers; the
// arrays hold the Recording, so the samples live as long as they do.
void KeepGyroSamples(const Rows& t,
                     const py::object& gyro,
                     const Rows& gyro_rows,
                     double radps_per_unit,
                     ArraysView* out) {
  if (!py::hasattr(gyro, "base")) return;
  const py::object base = gyro.attr("base");
  if (!py::isinstance<Recording>(base)) return;
  const auto& source = base.cast<const Recording&>();
  if (source.gyro_samples.empty() || source.empty() ||
      source.size() != static_cast<std::size_t>(t.shape(0)) ||
      t.data() != source.time_s.data() ||
      gyro_rows.data() != source.gyro_radps.front().data()) {
    return;
  }
  out->rows.gyro_samples_time_s = source.gyro_samples_time_s;
  if (radps_per_unit == 1.0) {
    out->rows.gyro_samples = source.gyro_samples;
    return;
  }
  out->own_gyro_samples = source.gyro_samples;
  for (Eigen::Vector3d& w : out->own_gyro_samples) w *= radps_per_unit;
  out->rows.gyro_samples = out->own_gyro_samples;
}

}  // namespace

std::shared_ptr<const ArraysView> ViewArrays(const Rows& t,
                                             const Rows& accel,
                                             const std::optional<Rows>& gyro_rows,
                                             const py::object& gyro,
                                             const std::string& units,
                                             const std::string& gyro_units) {
  auto out = std::make_shared<ArraysView>();
  RecordingView& rows = out->rows;
  rows.source = "<arrays>";  // a literal: the view outlives no string of ours
  rows.units = AccelUnitsArgument(units, "units");
  GyroUnits given = GyroUnits::kRadps;
  if (gyro_rows) {
    given = GyroUnitsArgument(gyro_units, "gyro_units");
    rows.gyro_log_units = given;
    rows.gyro_units =
        given == GyroUnits::kCounts ? GyroUnits::kCounts : GyroUnits::kRadps;
  }
  const auto n = static_cast<std::size_t>(t.shape(0));
  const double radps = FixedRadpsPerUnit(given).value_or(1.0);
  if (gyro_rows) KeepGyroSamples(t, gyro, *gyro_rows, radps, out.get());
  const py::gil_scoped_release unlocked;
  rows.time_s = SeeOrCopy(t.data(), n, out->own_time);
  rows.accel = XyzRows(SeeOrCopy(accel.data(), 3 * n, out->own_accel).data(), n);
  if (gyro_rows) {
    std::span<const double> seen;
    if (radps != 1.0) {
      // deg/s: converted into rows of its own, as the log reader does.
      CopyRows(gyro_rows->data(), 3 * n, out->own_gyro);
      for (double& w : out->own_gyro) w *= radps;
      seen = out->own_gyro;
    } else {
      seen = SeeOrCopy(gyro_rows->data(), 3 * n, out->own_gyro);
    }
    rows.gyro_radps = XyzRows(seen.data(), n);
  }
  return out;
}

}  // namespace mpcal::python
