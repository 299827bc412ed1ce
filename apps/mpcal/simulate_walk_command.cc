// `mpcal simulate walk`: a synthetic field-verification walk with known
// truth: the IMU log, the GNSS reference (RTKLIB .pos), the true errors and,
// on request, the true path.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "cli_options.h"
#include "command.h"
#include "explain.h"
#include "mpcal/atomic_file.h"
#include "mpcal/calibration_file.h"
#include "mpcal/error.h"
#include "mpcal/gnss.h"
#include "mpcal/gravity.h"
#include "mpcal/log_writer.h"
#include "mpcal/simulate_walk.h"

namespace mpcal::cli {
namespace {

struct SimulateWalkFlags {
  std::string preset = "mti-g";
  std::uint64_t seed = 1;
  std::string output;
  std::string gnss;
  std::string truth;
  std::string path;
  SimulateWalkOptions options;
  GravityFlags gravity;
  std::optional<double> noise_density;
};

// No two outputs the same file, each writable, before anything is simulated.
void CheckOutputs(const SimulateWalkFlags& f) {
  const std::vector<std::pair<const char*, std::string>> outputs = {
      {"--output", f.output},
      {"--gnss", f.gnss},
      {"--truth", f.truth},
      {"--path", f.path}};
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    if (!outputs[i].second.empty()) CheckWritable(outputs[i].second);
    for (std::size_t j = i + 1; j < outputs.size(); ++j) {
      if (!outputs[i].second.empty() && outputs[i].second == outputs[j].second) {
        throw Error(fmt::format("{} and {} name the same file '{}'",
                                outputs[i].first,
                                outputs[j].first,
                                outputs[i].second));
      }
    }
  }
}

SimulateWalkOptions OptionsFor(const SimulateWalkFlags& f) {
  SimulateWalkOptions o = f.options;
  o.device = FindPreset(f.preset);
  o.seed = f.seed;
  if (f.noise_density) o.device.noise_density_mps2_per_sqrt_hz = *f.noise_density;
  o.gnss_noise_vertical_m = 2.0 * o.gnss_noise_horizontal_m;
  return o;
}

// Several files: when one cannot be written, take back those already
// written, so that no partial output is left.
void WriteOutputs(const SimulateWalkFlags& f, const SimulatedWalk& walk) {
  std::vector<std::string> written;
  try {
    WriteRecordingFile(f.output, walk.recording);
    written.push_back(f.output);
    WriteFileAtomically(
        f.gnss, FormatRtklibPos(walk.gnss, TimeSystem::kGpst, "mpcal simulate walk"));
    written.push_back(f.gnss);
    if (!f.truth.empty()) {
      WriteCalibrationFile(f.truth, walk.truth);
      written.push_back(f.truth);
    }
    if (!f.path.empty()) {
      WriteStreamAtomically(f.path, [&](std::ostream& out) {
        out << "t_s,e_m,n_m,u_m\n";
        for (std::size_t i = 0; i < walk.true_enu_m.size(); ++i) {
          const Eigen::Vector3d& p = walk.true_enu_m[i];
          out << fmt::format("{:.4f},{:.4f},{:.4f},{:.4f}\n",
                             walk.recording.time_s[i],
                             p.x(),
                             p.y(),
                             p.z());
        }
      });
    }
  } catch (const Error&) {
    std::error_code ec;
    for (const std::string& path : written) {
      if (path != "-") std::filesystem::remove(path, ec);
    }
    throw;
  }
}

void PrintSummary(const SimulateWalkFlags& f,
                  const SimulateWalkOptions& o,
                  const SimulatedWalk& walk,
                  double gravity) {
  const Recording& r = walk.recording;
  fmt::print(
      "{} walk of {:.1f} m around a {:.0f} m x {:.0f} m loop in {:.1f} s ({} samples at "
      "{:g} "
      "Hz{}), sensor {} with {:g} deg mount tilt; gravity {:.5f} m/s2\n",
      o.device.name,
      walk.true_path_length_m,
      o.length_m,
      o.width_m,
      r.time_s.back() - r.time_s.front(),
      r.size(),
      o.rate_hz > 0.0 ? o.rate_hz : o.device.rate_hz,
      r.gyro_radps.empty() ? "" : ", gyroscope",
      o.turn ? "turning 90 deg at each corner" : "never rotating",
      o.mount_tilt_deg,
      gravity);
  fmt::print("wrote {} (IMU), {} (RTKLIB .pos, {} epochs at {:g} Hz, GPST){}{}\n",
             f.output,
             f.gnss,
             walk.gnss.size(),
             o.gnss_rate_hz,
             f.truth.empty() ? "" : fmt::format(", {} (true errors)", f.truth),
             f.path.empty() ? "" : fmt::format(", {} (true path)", f.path));
}

void RunSimulateWalk(const SimulateWalkFlags& f) {
  CheckOutputs(f);
  const SimulateWalkOptions o = OptionsFor(f);
  // Gravity: as given; else normal gravity where the walk starts.
  const double gravity =
      f.gravity.gravity_mps2 || f.gravity.latitude_deg
          ? f.gravity.Resolve()
          : NormalGravityMps2(o.origin.latitude_deg, o.origin.height_m);
  const SimulatedWalk walk = SimulateWalk(o, gravity);
  WriteOutputs(f, walk);
  if (f.output == "-") return;
  PrintSummary(f, o, walk, gravity);
}

// The walk: its shape, pace and the sensor's mount.
void AddWalkOptions(CLI::App* app, SimulateWalkOptions& o) {
  app->add_flag("--turn",
                o.turn,
                "The walker turns the sensor 90 deg at each corner (gyroscope columns "
                "written); default: the sensor never rotates (the paper's setting)")
      ->group("Walk");
  app->add_option("--length", o.length_m, "Long side of the loop (m)")
      ->capture_default_str()
      ->group("Walk");
  app->add_option("--width", o.width_m, "Short side of the loop (m)")
      ->capture_default_str()
      ->group("Walk");
  app->add_option("--speed", o.speed_mps, "Walking speed (m/s)")
      ->capture_default_str()
      ->group("Walk");
  app->add_option("--rest", o.rest_s, "Still at the start and at the end (s)")
      ->capture_default_str()
      ->group("Walk");
  app->add_option("--corner-stop", o.corner_stop_s, "Still at each corner (s)")
      ->capture_default_str()
      ->group("Walk");
  app->add_option("--step-rate", o.step_hz, "Steps per second (Hz)")
      ->capture_default_str()
      ->group("Walk");
  app->add_option("--bob",
                  o.bob_vertical_mps2,
                  "Vertical acceleration amplitude of the steps (m/s2)")
      ->capture_default_str()
      ->group("Walk");
  app->add_option("--mount-tilt",
                  o.mount_tilt_deg,
                  "Tilt of the sensor's z axis from the vertical (deg)")
      ->capture_default_str()
      ->group("Walk");
}

// The IMU's rate and noise, and the GNSS reference's rate, noise and origin.
void AddSensorAndReferenceOptions(CLI::App* app, SimulateWalkFlags& flags) {
  SimulateWalkOptions& o = flags.options;
  SimulateWalkFlags* f = &flags;
  app->add_option(std::string(FlagName(Option::kLogRate)),
                  o.rate_hz,
                  "IMU rate (Hz); default the device's")
      ->check(PositiveNumber)
      ->group("Sensor");
  app->add_option("--noise-density",
                  f->noise_density,
                  "Accelerometer white-noise density (m/s2/√Hz); default the device's")
      ->check(NonNegativeNumber)
      ->group("Sensor");
  app->add_option("--gyro-noise-density",
                  o.gyro_noise_density_radps_per_sqrt_hz,
                  "Gyroscope white-noise density (rad/s/√Hz)")
      ->capture_default_str()
      ->check(NonNegativeNumber)
      ->group("Sensor");
  app->add_option("--gnss-rate", o.gnss_rate_hz, "GNSS epochs per second (Hz)")
      ->capture_default_str()
      ->group("Reference");
  app->add_option("--gnss-noise",
                  o.gnss_noise_horizontal_m,
                  "GNSS horizontal noise, 1 sigma (m); vertical is twice that")
      ->capture_default_str()
      ->check(NonNegativeNumber)
      ->group("Reference");
  app->add_option("--origin", o.origin.latitude_deg, "Latitude of the start (deg)")
      ->capture_default_str()
      ->group("Reference");
  app->add_option("--origin-lon", o.origin.longitude_deg, "Longitude of the start (deg)")
      ->capture_default_str()
      ->group("Reference");
}

}  // namespace

void AddSimulateWalkCommand(CLI::App& simulate) {
  auto f = std::make_shared<SimulateWalkFlags>();
  CLI::App* app = simulate.add_subcommand(
      "walk",
      "A field-verification walk with known errors: a closed, roughly rectangular loop "
      "with "
      "a sensor on a pole, its IMU log and a GNSS reference (RTKLIB .pos)");
  app->add_option("--preset",
                  f->preset,
                  fmt::format("Paper's device (docs/method.md §6): {}",
                              fmt::join(PresetNames(), ", ")))
      ->capture_default_str();
  app->add_option("--seed", f->seed, "Random seed; the same seed gives the same walk")
      ->capture_default_str();
  app->add_option(
         "-o,--output", f->output, "The IMU log (CSV: t,ax,ay,az[,gx,gy,gz]), m/s2")
      ->check(OutputPath)
      ->required();
  app->add_option("--gnss", f->gnss, "The GNSS reference (RTKLIB .pos, GPST)")
      ->check(OutputPath)
      ->required();
  app->add_option("--truth", f->truth, "The true errors as a calibration file (JSON)")
      ->check(OutputPath);
  app->add_option(
         "--path", f->path, "The true path (CSV t_s,e_m,n_m,u_m at the IMU samples)")
      ->check(OutputPath);
  AddWalkOptions(app, f->options);
  AddSensorAndReferenceOptions(app, *f);
  AddGravityOptions(*app, f->gravity);
  app->footer(
      "Gravity defaults to the WGS84 normal gravity at the start of the loop.\n"
      "Examples:\n"
      "  mpcal simulate walk --preset colibri --seed 3 -o walk.csv --gnss ref.pos "
      "--truth t.json\n"
      "  mpcal verify --imu walk.csv --gnss ref.pos --calib t.json --mount z-up -o "
      "result.json\n"
      "  mpcal simulate walk --preset mti-g --turn -o walk.csv --gnss ref.pos --truth "
      "t.json\n"
      "  mpcal verify --imu walk.csv --gnss ref.pos --calib t.json -o result.json");
  app->callback([f] { RunSimulateWalk(*f); });
}

}  // namespace mpcal::cli
