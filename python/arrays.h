// Between numpy arrays and the library's rows (arrays.cc).
#pragma once

#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <Eigen/Core>

#include "mpcal/recording.h"

namespace mpcal::python {

namespace py = pybind11;

/// float64, C order: what the Python layer (mpcal/__init__.py) hands over
/// once it has checked shape, dtype and finiteness.
using Rows = py::array_t<double, py::array::c_style>;

/// A read-only numpy view of `values` (N×3 when `columns` is 3, else N)
/// that keeps `owner` alive: no copy.
py::array ViewOf(const double* values, std::size_t rows, int columns, py::handle owner);

/// The rows of an N×3 array as the library holds them (one copy).
std::vector<Eigen::Vector3d> ToVectors(const Rows& rows);

/// The arrays of calibrate, detect and noise, shape and dtype checked by
/// mpcal/__init__.py but not their values: copied into a Recording with
/// every value checked finite in the same pass, without the GIL (one read
/// of the caller's memory, not a check and then a copy).
struct CheckedRecording {
  Recording recording;
  /// The argument ("t", "accel", "gyro") holding a value that is NaN or
  /// infinite; empty when all are finite (then `recording` holds the rows).
  std::string not_finite;
};
CheckedRecording ToRecordingChecked(const Rows& t,
                                    const Rows& accel,
                                    const py::object& gyro,
                                    const std::string& units,
                                    const std::string& gyro_units);

/// A Recording from arrays (t: N seconds; accel: N×3 in `units`; gyro: N×3
/// or None, in `gyro_units`: deg/s converted to rad/s as the log reader
/// does, counts kept).
Recording ToRecording(const Rows& t,
                      const Rows& accel,
                      const py::object& gyro,
                      const std::string& units,
                      const std::string& gyro_units);

/// "mps2", "g", "counts" (as ParseAccelUnits) or throws mpcal::Error
/// (kOption) naming `argument`.
AccelUnits AccelUnitsArgument(const std::string& name, const char* argument);
GyroUnits GyroUnitsArgument(const std::string& name, const char* argument);

}  // namespace mpcal::python
