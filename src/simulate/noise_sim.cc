// Still recordings with known white noise, flicker bias instability and
// random walk per axis (model and references in mpcal/simulate_noise.h).
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "mpcal/error.h"
#include "mpcal/simulate_noise.h"
#include "simulate/random.h"

namespace mpcal {
namespace {

constexpr double kFlickerSpacing = 3.1622776601683795;  // √10: two per decade
constexpr double kHoldPeriods = 100.0;                  // update a process every T/100

struct GaussMarkov {
  double phi = 0.0;    // exp(-hold/T)
  double drive = 0.0;  // σ of the innovation per update
  long every = 1;      // samples per update
  long left = 0;       // samples until the next update
  double x = 0.0;
};

struct Channel {
  double mean = 0.0;
  double white_sigma = 0.0;
  double walk_step = 0.0;
  double walk = 0.0;
  std::vector<GaussMarkov> flicker;

  double Next(internal::PortableRandom& rng) {
    double v = mean + walk;
    if (white_sigma > 0.0) v += white_sigma * rng.Normal();
    for (GaussMarkov& g : flicker) {
      if (--g.left <= 0) {
        g.x = g.phi * g.x + g.drive * rng.Normal();
        g.left = g.every;
      }
      v += g.x;
    }
    if (walk_step > 0.0) walk += walk_step * rng.Normal();
    return v;
  }
};

Channel MakeChannel(double mean,
                    const AxisNoiseTruth& truth,
                    const NoiseSimulationOptions& o,
                    internal::PortableRandom& rng) {
  Channel c;
  c.mean = mean;
  c.white_sigma = truth.white_noise * std::sqrt(o.rate_hz);
  c.walk_step = truth.random_walk / std::sqrt(o.rate_hz);
  if (truth.bias_instability > 0.0) {
    const double q = truth.bias_instability * truth.bias_instability *
                     std::log(kFlickerSpacing) / std::numbers::pi;
    const double dt = 1.0 / o.rate_hz;
    for (double tc = o.flicker_min_tau_s; tc <= 10.0 * o.duration_s * kFlickerSpacing;
         tc *= kFlickerSpacing) {
      GaussMarkov g;
      g.every = std::max(1L, static_cast<long>(tc / (kHoldPeriods * dt)));
      g.left = 0;
      g.phi = std::exp(-static_cast<double>(g.every) * dt / tc);
      g.drive = std::sqrt(q * (1.0 - g.phi * g.phi));
      g.x = std::sqrt(q) * rng.Normal();  // stationary from the start
      c.flicker.push_back(g);
    }
  }
  return c;
}

NoiseSimulationOptions Preset(
    double an, double ab, double ak, double gn, double gb, double gk) {
  NoiseSimulationOptions o;
  const double spread[3] = {1.0, 1.12, 0.9};  // the axes of one device differ
  for (int i = 0; i < 3; ++i) {
    o.accel_mps2[i] = {
        an * spread[i], ab * spread[(i + 1) % 3], ak * spread[(i + 2) % 3]};
    o.gyro_radps[i] = {
        gn * spread[(i + 2) % 3], gb * spread[i], gk * spread[(i + 1) % 3]};
  }
  return o;
}

}  // namespace

std::string NoiseSimulationOptions::Validate() const {
  if (!(duration_s > 0.0 && std::isfinite(duration_s)))
    return "duration_s must be positive";
  if (!(rate_hz > 0.0 && std::isfinite(rate_hz))) return "rate_hz must be positive";
  if (duration_s * rate_hz < 16.0)
    return "duration_s * rate_hz must be at least 16 samples";
  if (duration_s * rate_hz > 2e9)
    return "duration_s * rate_hz must be at most 2e9 samples";
  if (!(flicker_min_tau_s > 0.0)) return "flicker_min_tau_s must be positive";
  for (const auto* sensor : {&accel_mps2, &gyro_radps}) {
    for (const AxisNoiseTruth& a : *sensor) {
      for (double v : {a.white_noise, a.bias_instability, a.random_walk}) {
        if (!(v >= 0.0 && std::isfinite(v))) return "noise terms must be finite and >= 0";
      }
    }
  }
  return {};
}

std::optional<NoiseSimulationOptions> NoisePreset(std::string_view name) {
  if (name == "consumer") {
    // 150 µg/√Hz, 40 µg, 4e-5 m/s³/√Hz; 0.69 °/√h, 4.1 °/h, 2e-6 rad/s²/√Hz.
    return Preset(1.5e-3, 4e-4, 4e-5, 2e-4, 2e-5, 2e-6);
  }
  if (name == "industrial") {
    // 23 µg/√Hz, 3.5 µg, 1e-6 m/s³/√Hz; 0.15 °/√h, 2 °/h, 1e-7 rad/s²/√Hz.
    return Preset(2.3e-4, 3.5e-5, 1e-6, 4.4e-5, 1e-5, 1e-7);
  }
  return std::nullopt;
}

std::vector<std::string> NoisePresetNames() { return {"consumer", "industrial"}; }

struct NoiseGenerator::Impl {
  NoiseSimulationOptions options;
  internal::PortableRandom rng;
  std::array<Channel, 6> channels;
  std::size_t rows = 0;
  std::size_t next = 0;

  explicit Impl(const NoiseSimulationOptions& o)
      : options(o), rng(internal::SplitMix64(o.seed)) {}
};

NoiseGenerator::NoiseGenerator(const NoiseSimulationOptions& options) {
  if (const std::string bad = options.Validate(); !bad.empty()) {
    throw Error(ErrorKind::kOption, "noise simulation: " + bad);
  }
  impl_ = std::make_unique<Impl>(options);
  impl_->rows =
      static_cast<std::size_t>(std::llround(options.duration_s * options.rate_hz));
  for (int i = 0; i < 3; ++i) {
    impl_->channels[i] = MakeChannel(
        options.accel_mean_mps2[i], options.accel_mps2[i], options, impl_->rng);
    impl_->channels[3 + i] = MakeChannel(
        options.gyro_mean_radps[i], options.gyro_radps[i], options, impl_->rng);
  }
}

NoiseGenerator::~NoiseGenerator() = default;

std::size_t NoiseGenerator::rows() const { return impl_->rows; }

bool NoiseGenerator::Next(double* t_s,
                          Eigen::Vector3d* accel_mps2,
                          Eigen::Vector3d* gyro_radps) {
  if (impl_->next >= impl_->rows) return false;
  *t_s = static_cast<double>(impl_->next) / impl_->options.rate_hz;
  for (int i = 0; i < 3; ++i) {
    (*accel_mps2)[i] = impl_->channels[i].Next(impl_->rng);
    (*gyro_radps)[i] = impl_->channels[3 + i].Next(impl_->rng);
  }
  ++impl_->next;
  return true;
}

}  // namespace mpcal
