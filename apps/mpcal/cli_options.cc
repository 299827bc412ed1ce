#include "cli_options.h"

#include <map>

#include <fmt/format.h>

#include "mpcal/error.h"
#include "mpcal/gravity.h"

namespace mpcal::cli {

void AddLogOptions(CLI::App& app, LogOptions& options) {
  const std::map<std::string, AccelUnits> units{
      {"mps2", AccelUnits::kMps2}, {"g", AccelUnits::kG}, {"counts", AccelUnits::kCounts}};
  const std::map<std::string, TimeUnit> time_units{
      {"auto", TimeUnit::kAuto},          {"s", TimeUnit::kSeconds},
      {"ms", TimeUnit::kMilliseconds},    {"us", TimeUnit::kMicroseconds},
      {"ns", TimeUnit::kNanoseconds},     {"index", TimeUnit::kSampleIndex}};
  app.add_option("--columns", options.columns,
                 "Column mapping t=NAME|INDEX,ax=..,ay=..,az=..[,gx=..,gy=..,gz=..] "
                 "(0-based indices); default: from the header, else t,ax,ay,az")
      ->group("Input log");
  app.add_option("--units", options.units,
                 "Accelerometer units in the log: mps2, g (9.80665 m/s2) or counts "
                 "(raw ADC; offset and scale found from the positions)")
      ->transform(CLI::CheckedTransformer(units, CLI::ignore_case))
      ->default_str("mps2")
      ->group("Input log");
  app.add_option("--time-unit", options.time_unit,
                 "Unit of the time column: s, ms, us, ns, index (sample number, "
                 "needs --rate) or auto (integers: detected from the spacing)")
      ->transform(CLI::CheckedTransformer(time_units, CLI::ignore_case))
      ->default_str("auto")
      ->group("Input log");
  app.add_option("--rate", options.rate_hz,
                 "Sample rate (Hz) when the time column is a sample index or absent")
      ->check(CLI::PositiveNumber)
      ->group("Input log");
  app.add_flag_function(
         "--gyro-dps", [&options](std::int64_t) { options.gyro_in_dps = true; },
         "Gyroscope columns are in deg/s (default rad/s)")
      ->group("Input log");
}

double GravityFlags::Resolve() const {
  if (gravity_mps2) return *gravity_mps2;
  if (latitude_deg) return NormalGravityMps2(*latitude_deg, height_m);
  return kStandardGravityMps2;
}

void AddGravityOptions(CLI::App& app, GravityFlags& flags) {
  auto* g = app.add_option("--gravity", flags.gravity_mps2,
                           "Local magnitude of gravity (m/s2); default 9.80665, "
                           "the standard value the paper uses")
                ->check(CLI::Range(9.7, 9.9))
                ->group("Gravity");
  auto* lat = app.add_option("--latitude", flags.latitude_deg,
                             "Geodetic latitude of the site (deg): use the WGS84 "
                             "normal gravity there")
                  ->check(CLI::Range(-90.0, 90.0))
                  ->group("Gravity");
  app.add_option("--height", flags.height_m,
                 "Ellipsoidal height of the site (m), with --latitude")
      ->needs(lat)
      ->group("Gravity");
  g->excludes(lat);
}

void AddCalibrateOptions(CLI::App& app, CalibrateOptions& options) {
  const std::map<std::string, ModelKind> models{
      {"shin-el-sheimy-9", ModelKind::kShinElSheimy9},
      {"bias-scale-6", ModelKind::kBiasScale6}};
  const std::map<std::string, RobustLoss> losses{
      {"none", RobustLoss::kNone}, {"huber", RobustLoss::kHuber},
      {"cauchy", RobustLoss::kCauchy}};
  app.add_option("--model", options.solve.model,
                 "Error model: shin-el-sheimy-9 (bias, scale, 3 non-orthogonality "
                 "angles; >= 10 positions) or bias-scale-6 (six-position protocol)")
      ->transform(CLI::CheckedTransformer(models, CLI::ignore_case))
      ->default_str("shin-el-sheimy-9")
      ->group("Estimation");
  app.add_option("--robust", options.solve.robust,
                 "Robust loss on the position residuals: none, huber or cauchy")
      ->transform(CLI::CheckedTransformer(losses, CLI::ignore_case))
      ->default_str("none")
      ->group("Estimation");
  app.add_option("--window", options.detect.window_s,
                 "Static detection: moving window of the motion statistic (s)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber)
      ->group("Static detection");
  app.add_option("--min-static", options.detect.min_static_s,
                 "Static detection: shortest still position kept (s)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber)
      ->group("Static detection");
  app.add_option("--settle", options.detect.settle_s,
                 "Static detection: trimmed from each end of a position (s)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber)
      ->group("Static detection");
  app.add_option("--threshold", options.detect.threshold_factor,
                 "Static detection: threshold as a multiple of the quiet level")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 100.0))
      ->group("Static detection");
}

void ThrowIfInvalid(const std::string& problem, const std::string& what) {
  if (!problem.empty()) throw Error(fmt::format("{}: {}", what, problem));
}

}  // namespace mpcal::cli
