// Between numpy arrays and the library's rows (arrays.cc).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <Eigen/Core>

#include "mpcal/recording.h"
#include "mpcal/recording_view.h"

namespace mpcal::python {

namespace py = pybind11;

/// float64, C order: what the Python layer (mpcal/__init__.py) hands over
/// once it has checked shape and dtype.
using Rows = py::array_t<double, py::array::c_style>;

/// A read-only numpy view of `values` (N×3 when `columns` is 3, else N)
/// that keeps `owner` alive: no copy.
py::array ViewOf(const double* values, std::size_t rows, int columns, py::handle owner);

/// The arrays of calibrate, detect and noise as the library reads them:
/// views of the caller's memory (float64, C order, as mpcal/__init__.py
/// hands them over); no copy, and no pass over them here: the library
/// refuses a value that is NaN or infinite where it first reads the rows
/// (NotFiniteError, which the module raises naming the argument). A
/// gyroscope in deg/s is converted to rad/s into rows of its own, and
/// memory not aligned as a double is copied. The view reads the arrays in
/// place: they must stay alive, and unchanged, while the library reads them
/// (Interruptible's `in_use`): these very objects, `gyro` already cast (a
/// cast may convert into an array of its own). `gyro` as the caller gave
/// it: when it is a Recording's own array, that Recording's gyroscope
/// samples recorded apart are seen too.
struct ArraysView {
  RecordingView rows;
  /// The rows that had to be converted or copied (empty when viewed).
  std::vector<double> own_time;
  std::vector<double> own_accel;
  std::vector<double> own_gyro;
  /// A Recording's own gyroscope samples, converted (see KeepGyroSamples).
  std::vector<Eigen::Vector3d> own_gyro_samples;
};
/// Held by a shared pointer: `rows` may point into the object's own vectors.
std::shared_ptr<const ArraysView> ViewArrays(const Rows& t,
                                             const Rows& accel,
                                             const std::optional<Rows>& gyro_rows,
                                             const py::object& gyro,
                                             const std::string& units,
                                             const std::string& gyro_units);

/// "mps2", "g", "counts" (as ParseAccelUnits) or throws mpcal::Error
/// (kOption) naming `argument`.
AccelUnits AccelUnitsArgument(const std::string& name, const char* argument);
GyroUnits GyroUnitsArgument(const std::string& name, const char* argument);

}  // namespace mpcal::python
