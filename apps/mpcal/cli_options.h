// Flag groups shared by several subcommands, so that every subcommand spells
// the same option the same way (`--units`, `--columns`, `--gravity`, ...).
#pragma once

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "mpcal/calibrate.h"
#include "mpcal/log_reader.h"

namespace mpcal::cli {

/// --columns, --units, --time-unit, --rate, --gyro-units.
void AddLogOptions(CLI::App& app, LogOptions& options);

/// --gravity | --latitude [--height]: the local magnitude of gravity.
struct GravityFlags {
  std::optional<double> gravity_mps2;
  std::optional<double> latitude_deg;
  double height_m = 0.0;
  /// The value to use: the given one, WGS84 normal gravity at the site, or
  /// standard gravity (9.80665 m/s², the paper's) by default.
  double Resolve() const;
};
void AddGravityOptions(CLI::App& app, GravityFlags& flags);

/// --model, --robust, detection tuning (--window, --min-static, ...).
void AddCalibrateOptions(CLI::App& app, CalibrateOptions& options);

/// Checks for numeric flags: a finite number > 0 (>= 0). CLI11's own
/// PositiveNumber / NonNegativeNumber print their range up to DBL_MAX, digit
/// by digit, in the error; these say what is wrong ("--rate: must be a
/// positive number, got -1").
extern const CLI::Validator PositiveNumber;
extern const CLI::Validator NonNegativeNumber;

/// Throws mpcal::Error naming the option when `problem` is not empty.
void ThrowIfInvalid(const std::string& problem, const std::string& what);

}  // namespace mpcal::cli
