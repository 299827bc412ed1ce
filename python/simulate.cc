// mpcal.simulate_static on arrays: a hand-held session with its truth.
#include "simulate.h"

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <pybind11/stl.h>

#include "arrays.h"
#include "errors.h"
#include "interrupt.h"
#include "mpcal/error.h"
#include "mpcal/gravity.h"
#include "mpcal/simulate.h"
#include "mpcal/simulate_noise.h"

namespace mpcal::python {
namespace {

py::dict SimulateStaticDefaults() {
  const SimulateStaticOptions o;
  py::dict d;
  d["preset"] = "mti-g";  // as `mpcal simulate static`
  d["seed"] = o.seed;
  d["positions"] = o.positions;
  d["tilt_deg"] = o.tilt_deg;
  d["dwell_s"] = o.dwell_s;
  d["turn_s"] = o.turn_s;
  d["initial_rest_s"] = o.initial_rest_s;
  d["rate_hz"] = o.rate_hz;
  d["units"] = std::string(ToString(o.units));
  d["counts_per_mps2"] = o.counts_per_mps2;
  d["counts_offset"] = o.counts_offset;
  d["gyro"] = o.gyro;
  d["gravity"] = kStandardGravityMps2;
  return d;
}

// (recording, truth, still ranges K×2 (rows, end excluded), directions K×3,
// per-axis noise σ (m/s²), rate (Hz)).
py::tuple SimulateStaticFrom(const py::dict& o) {
  SimulateStaticOptions s;
  s.device = FindPreset(o["preset"].cast<std::string>());
  s.seed = o["seed"].cast<std::uint64_t>();
  s.positions = o["positions"].cast<int>();
  s.tilt_deg = o["tilt_deg"].cast<double>();
  s.dwell_s = o["dwell_s"].cast<double>();
  s.turn_s = o["turn_s"].cast<double>();
  s.initial_rest_s = o["initial_rest_s"].cast<double>();
  s.rate_hz = o["rate_hz"].cast<double>();
  s.units = AccelUnitsArgument(o["units"].cast<std::string>(), "units");
  s.counts_per_mps2 = o["counts_per_mps2"].cast<double>();
  s.counts_offset = o["counts_offset"].cast<double>();
  s.gyro = o["gyro"].cast<bool>();
  const auto gravity = o["gravity"].cast<double>();
  if (const std::string bad = s.Validate(); !bad.empty()) {
    throw Error(ErrorKind::kOption, "simulate_static: " + bad);
  }
  SimulatedSession session =
      Interruptible([s, gravity] { return SimulateStatic(s, gravity); });
  const auto k = static_cast<py::ssize_t>(session.still_ranges.size());
  Rows ranges({k, py::ssize_t{2}});
  Rows directions({k, py::ssize_t{3}});
  for (py::ssize_t i = 0; i < k; ++i) {
    const auto& [begin, end] = session.still_ranges[static_cast<std::size_t>(i)];
    ranges.mutable_at(i, 0) = static_cast<double>(begin);
    ranges.mutable_at(i, 1) = static_cast<double>(end);
    for (py::ssize_t j = 0; j < 3; ++j) {
      directions.mutable_at(i, j) = session.directions[static_cast<std::size_t>(i)][j];
    }
  }
  const Eigen::Vector3d sigma = session.noise_std_mps2;
  const double rate = session.rate_hz;
  py::object truth = py::cast(std::move(session.truth));
  py::object recording = py::cast(std::move(session.recording));
  return py::make_tuple(recording,
                        truth,
                        ranges.attr("astype")("int64"),
                        directions,
                        std::vector<double>{sigma.x(), sigma.y(), sigma.z()},
                        rate);
}

py::dict TruthOf(const std::array<AxisNoiseTruth, 3>& axes,
                 const char* n,
                 const char* b,
                 const char* k) {
  py::dict d;
  std::vector<double> white, instability, walk;
  for (const AxisNoiseTruth& a : axes) {
    white.push_back(a.white_noise);
    instability.push_back(a.bias_instability);
    walk.push_back(a.random_walk);
  }
  d[n] = white;
  d[b] = instability;
  d[k] = walk;
  return d;
}

// (recording (m/s², rad/s), truth {accelerometer: {...}, gyroscope: {...}}).
py::tuple SimulateNoiseFrom(const std::string& preset,
                            double duration_s,
                            double rate_hz,
                            std::uint64_t seed) {
  std::optional<NoiseSimulationOptions> options = NoisePreset(preset);
  if (!options) {
    throw Error(ErrorKind::kOption,
                fmt::format("preset='{}' is not a noise preset: give one of {}",
                            preset,
                            fmt::join(NoisePresetNames(), ", ")));
  }
  options->duration_s = duration_s;
  options->rate_hz = rate_hz;
  options->seed = seed;
  if (const std::string bad = options->Validate(); !bad.empty()) {
    throw Error(ErrorKind::kOption, "simulate_noise: " + bad);
  }
  Recording recording = Interruptible([o = *options] {
    NoiseGenerator generator(o);
    Recording r;
    r.source = "<simulated>";
    r.time_s.resize(generator.rows());
    r.accel.resize(generator.rows());
    r.gyro_radps.resize(generator.rows());
    for (std::size_t i = 0; i < generator.rows(); ++i) {
      generator.Next(&r.time_s[i], &r.accel[i], &r.gyro_radps[i]);
    }
    return r;
  });
  py::dict truth;
  truth["accelerometer"] = TruthOf(options->accel_mps2,
                                   "white_noise_mps2_per_rthz",
                                   "bias_instability_mps2",
                                   "random_walk_mps3_per_rthz");
  truth["gyroscope"] = TruthOf(options->gyro_radps,
                               "white_noise_radps_per_rthz",
                               "bias_instability_radps",
                               "random_walk_radps2_per_rthz");
  return py::make_tuple(py::cast(std::move(recording)), truth);
}

}  // namespace

void AddSimulate(py::module_& m) {
  m.def("_simulate_noise", &SimulateNoiseFrom);
  m.def("_simulate_static", &SimulateStaticFrom);
  m.def("_simulate_static_defaults", &SimulateStaticDefaults);
  m.def("_presets", &PresetNames);
}

}  // namespace mpcal::python
