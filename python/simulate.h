// mpcal.simulate_static's binding (simulate.cc).
#pragma once

#include <pybind11/pybind11.h>

namespace mpcal::python {

void AddSimulate(pybind11::module_& m);

}  // namespace mpcal::python
