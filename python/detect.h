// mpcal.detect's binding (detect.cc).
#pragma once

#include <pybind11/pybind11.h>

namespace mpcal::python {

void AddDetect(pybind11::module_& m);

}  // namespace mpcal::python
