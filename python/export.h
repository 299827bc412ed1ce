// mpcal.export and mpcal.import_calibration's binding (export.cc).
#pragma once

#include <pybind11/pybind11.h>

namespace mpcal::python {

void AddExport(pybind11::module_& m);

}  // namespace mpcal::python
