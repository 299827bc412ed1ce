/// \file error.h
/// \brief The one exception type mpcal throws for bad input and I/O failures.
///
/// Every public function that can reject its input documents the condition
/// under which it throws `mpcal::Error`. `what()` is a plain sentence for the
/// user: what was wrong and where (file, line, field). What would fix it is
/// carried as facts (`kind()`, `advice()`: the Options field to set, or the
/// stage to run), never as a command-line flag; the `mpcal` command adds the
/// flags when it prints the error (apps/mpcal/explain.cc).
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

#include "mpcal/advice.h"

namespace mpcal {

/// What kind of input was wrong, for callers that act on it.
enum class ErrorKind {
  kInput,    ///< malformed content (a log, a file of results)
  kIo,       ///< a file could not be opened, read or written
  kOption,   ///< an option value out of range or inconsistent
  kColumns,  ///< the log's columns could not be mapped to the quantities
  kUnits,    ///< the values do not fit the units given
  kTime,     ///< the time column (unit, order, rate) is unusable
  kFormat,   ///< a results file of another format or an unknown version
  kSession,  ///< a session that cannot give the result asked for
};

/// Bad input (a malformed log, an unusable session, an invalid option value)
/// or an I/O failure. Non-convergence of the solver is *not* an Error: it is a
/// status in the solver's result.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
  Error(ErrorKind kind, const std::string& what, Advice advice = {})
      : std::runtime_error(what), kind_(kind), advice_(std::move(advice)) {}

  ErrorKind kind() const { return kind_; }
  /// What would fix it; empty when the sentence says all there is.
  const Advice& advice() const { return advice_; }

 private:
  ErrorKind kind_ = ErrorKind::kInput;
  Advice advice_;
};

}  // namespace mpcal
