// Findings that do not stop the work, as the plain data mpcal/__init__.py
// makes mpcal.Finding objects of (findings.cc): a kind, the sentence, the
// advice as keyword arguments and the figures in SI units.
#pragma once

#include <string>

#include <pybind11/pybind11.h>

#include "mpcal/advice.h"
#include "mpcal/calibrate.h"
#include "mpcal/detect.h"

namespace mpcal::python {

namespace py = pybind11;

/// {"kind", "message", "advice", "stage", "figures"}.
py::dict FindingOf(const std::string& kind,
                   const std::string& message,
                   const Advice& advice,
                   py::dict figures);

/// A detection's note ("clipped_position", "not_still") with its figures.
py::dict DetectNoteFinding(const DetectNote& note, const std::string& message);

/// Every finding of a calibration, in the order of its warnings: the
/// detection's notes, the solver's, the gyroscope's.
py::list CalibrateFindings(const CalibrateResult& result);

}  // namespace mpcal::python
