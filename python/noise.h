// mpcal.noise's binding (noise.cc).
#pragma once

#include <pybind11/pybind11.h>

namespace mpcal::python {

void AddNoise(pybind11::module_& m);

}  // namespace mpcal::python
