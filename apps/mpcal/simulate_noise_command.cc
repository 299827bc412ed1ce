// `mpcal simulate noise`: a still recording with known white noise, bias
// instability and random walk per axis, and its truth.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "cli_options.h"
#include "command.h"
#include "explain.h"
#include "mpcal/atomic_file.h"
#include "mpcal/error.h"
#include "mpcal/noise_file.h"
#include "mpcal/noise_units.h"
#include "mpcal/simulate_noise.h"
#include "progress.h"

namespace mpcal::cli {
namespace {

struct SimulateNoiseFlags {
  std::string preset = "consumer";
  double hours = 1.0;
  double rate_hz = 100.0;
  std::uint64_t seed = 1;
  int digits = 9;
  std::string output;
  std::string truth;
};

void RunSimulateNoise(const SimulateNoiseFlags& f) {
  if (f.output == f.truth) {
    throw Error(fmt::format("-o and --truth name the same file '{}'", f.output));
  }
  if (f.truth == "-")
    throw Error("--truth needs a file name ('-' is only for the record, -o -)");
  CheckWritable(f.output);
  CheckWritable(f.truth);
  std::optional<NoiseSimulationOptions> o = NoisePreset(f.preset);
  if (!o) {
    throw Error(fmt::format("--preset: '{}' is not one of: {}",
                            f.preset,
                            fmt::join(NoisePresetNames(), ", ")));
  }
  o->duration_s = f.hours * 3600.0;
  o->rate_hz = f.rate_hz;
  o->seed = f.seed;
  ThrowIfInvalid(o->Validate(), "simulate noise");

  NoiseGenerator gen(*o);
  TerminalProgress progress("writing " + f.output);
  WriteStreamAtomically(f.output, [&](std::ostream& out) {
    WriteImuCsv(
        out,
        [&](double* t, Eigen::Vector3d* a, Eigen::Vector3d* g) {
          return gen.Next(t, a, g);
        },
        f.digits,
        gen.rows(),
        progress.Callback());
  });
  progress.Done();
  try {
    WriteFileAtomically(f.truth, NoiseTruthJson(*o));
  } catch (const Error&) {
    std::error_code ec;
    if (f.output != "-")
      std::filesystem::remove(f.output, ec);  // no record without truth
    throw;
  }
  if (f.output == "-") return;
  namespace nu = noise_units;
  const AxisNoiseTruth& a = o->accel_mps2[0];
  const AxisNoiseTruth& g = o->gyro_radps[0];
  fmt::print(
      "Simulated a still {} IMU (seed {}): {} rows over {:.2f} h at {:g} Hz.\n"
      "  accelerometer x: white noise {:.3g} m/s2/√Hz ({:.0f} µg/√Hz), bias instability "
      "{:.3g} m/s2 ({:.1f} µg), random walk {:.3g} m/s3/√Hz\n"
      "  gyroscope x:     white noise {:.3g} rad/s/√Hz ({:.3g} °/√h), bias instability "
      "{:.3g} rad/s ({:.3g} °/h), random walk {:.3g} rad/s2/√Hz\n"
      "  (y and z differ a little; all in {}). Bias instability: flicker noise as a sum "
      "of "
      "Gauss-Markov processes.\n"
      "wrote {} and {}\nAnalyse it with: mpcal noise {} --json noise.json\n",
      f.preset,
      f.seed,
      gen.rows(),
      o->duration_s / 3600.0,
      o->rate_hz,
      a.white_noise,
      nu::MicroGPerRtHz(a.white_noise),
      a.bias_instability,
      nu::MicroG(a.bias_instability),
      a.random_walk,
      g.white_noise,
      nu::DegPerRtHour(g.white_noise),
      g.bias_instability,
      nu::DegPerHour(g.bias_instability),
      g.random_walk,
      f.truth,
      f.output,
      f.truth,
      f.output);
}

}  // namespace

void AddSimulateNoiseCommand(CLI::App& simulate) {
  auto f = std::make_shared<SimulateNoiseFlags>();
  CLI::App* app = simulate.add_subcommand(
      "noise",
      "A still IMU recording (accelerometer and gyroscope) with known white noise, bias "
      "instability and random walk per axis, to learn and test 'mpcal noise'");
  app->add_option("--preset",
                  f->preset,
                  fmt::format("Device class: {}", fmt::join(NoisePresetNames(), ", ")))
      ->capture_default_str();
  app->add_option("--hours", f->hours, "Length of the record (h)")
      ->capture_default_str()
      ->check(PositiveNumber);
  app->add_option(std::string(FlagName(Option::kLogRate)), f->rate_hz, "Sample rate (Hz)")
      ->capture_default_str()
      ->check(PositiveNumber);
  app->add_option("--seed", f->seed, "Random seed; the same seed gives the same record")
      ->capture_default_str();
  app->add_option("--digits", f->digits, "Significant digits of each reading")
      ->capture_default_str()
      ->check(CLI::Range(3, 17));
  app->add_option("-o,--output",
                  f->output,
                  "The record (CSV t,ax,ay,az,gx,gy,gz in s, m/s2, rad/s; '-': stdout)")
      ->check(OutputPath)
      ->required();
  app->add_option("--truth", f->truth, "The true terms (JSON, mpcal.noise_truth/1)")
      ->check(OutputPath)
      ->required();
  app->footer(
      "Example:\n"
      "  mpcal simulate noise --hours 2 --rate 200 --preset consumer --seed 1 -o "
      "still.csv "
      "--truth truth.json\n"
      "  mpcal noise still.csv --json noise.json --kalibr imu.yaml");
  app->callback([f] { RunSimulateNoise(*f); });
}

}  // namespace mpcal::cli
