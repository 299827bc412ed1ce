// The library's errors and advice in Python's terms (errors.cc).
#pragma once

#include <string>
#include <string_view>

#include <pybind11/pybind11.h>

#include "mpcal/advice.h"

namespace mpcal::python {

namespace py = pybind11;

/// The keyword argument of the Python functions that sets `option`
/// ("window_s", "units", ...); empty for Option::kNone.
std::string_view KeywordOf(Option option);

/// Advice that sets `option`, to `value` ("": the user's to choose); or
/// either of two options.
Advice Suggest(Option option, std::string value = "");
Advice Suggest(Option option, Option alternative);

/// The settings of `advice` as {keyword: value}; a value of None is the
/// user's to choose, a number is the value the data suggest.
py::dict AdviceSettings(const Advice& advice);

/// The mpcal function to run to see more ("detect", ...), or None.
py::object StageOf(const Advice& advice);

/// mpcal::Error (and its kinds UnitsError, SessionError) raised as
/// mpcal.Error with kind, advice, stage and figures.
void RegisterErrorTranslator();

}  // namespace mpcal::python
