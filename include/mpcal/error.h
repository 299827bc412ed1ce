/// \file error.h
/// \brief The one exception type mpcal throws for bad input and I/O failures.
///
/// Every public function that can reject its input documents the condition
/// under which it throws `mpcal::Error`. The message is written for the user:
/// it names what was wrong, where (file, line, field) and, where there is one,
/// what to do about it. The command-line tool prints it verbatim after
/// `mpcal: error: `.
#pragma once

#include <stdexcept>
#include <string>

namespace mpcal {

/// Bad input (a malformed log, an unusable session, an invalid option value)
/// or an I/O failure. Non-convergence of the solver is *not* an Error: it is a
/// status in the solver's result.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace mpcal
