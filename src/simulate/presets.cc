// The paper's three devices (Souza & Machado 2016, docs/method.md §6) as presets.
//
// Sources, per figure:
// - Errors: trial 1 ("Ensaio 1") of the paper's Tables 4 (Colibri),
//   5 (InertiaCube3) and 6 (MTi-G). Bias printed in g, converted with the
//   paper's own g = 9.80665 m/s². Scale-factor error printed in "10³ ppm":
//   -1.99985 means -1999.85 ppm, s = -0.00199985 (the JSON example has
//   the MTi-G value -0.0019998). Non-orthogonality printed in rad for rows
//   x, y, z, which are θyz, θzx, θzy of the model (the example:
//   yz 1e-5, zx 1.8e-4, zy 1.7e-4 for the MTi-G).
// - Turn-on bias spread: the paper's "Desvio Padrão" of the bias over its
//   three trials (same tables), taken as the 1σ of a power-up.
// - Rates: the paper's Tables 1-3 ("Frequência de operação" > 100, > 180,
//   > 512 Hz); we use the lower bounds.
// - Colibri range and resolution: Table 1, ±16 g and 13 bits, so one LSB is
//   32 g / 2¹³ = 3.90625 mg.
// - MTi-G noise density 0.002 m/s²/√Hz: Table 3. Its range, ±50 m/s² (the
//   standard ±5 g accelerometer of the MTi/MTi-G family), is from Xsens'
//   MTi/MTx manual (MT0100P), not from the paper; the output is floating
//   point (no quantisation).
// - Colibri and InertiaCube3 noise densities are not in the paper. Colibri:
//   ±16 g at 13 bits is the full-resolution mode of an ADXL345-class part,
//   whose datasheet gives about 0.75 LSB RMS at 100 Hz output (50 Hz band),
//   i.e. ~0.4 mg/√Hz ≈ 0.004 m/s²/√Hz. InertiaCube3: a plausible value for a
//   2000s consumer MEMS triad, 0.003 m/s²/√Hz (~300 µg/√Hz); no range or
//   resolution is published, so none is simulated.
// - Gyroscopes (none is in the paper; plausible figures for each class):
//   MTi-G from Xsens' MTi-G datasheet (rate gyroscope: bias stability
//   1 deg/s, noise 0.05 deg/s/√Hz, alignment error 0.1 deg, scale
//   non-linearity 0.1 %); Colibri and InertiaCube3 as consumer MEMS gyros of
//   their time (ITG-3200 class: scale tolerance ±6 %, cross-axis 2 %, zero
//   rate offset ±40 deg/s before trimming, noise 0.03 deg/s/√Hz), with
//   smaller draws inside those tolerances.
#include <algorithm>
#include <cctype>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "mpcal/error.h"
#include "mpcal/simulate.h"
#include "mpcal/units.h"

namespace mpcal {
namespace {

constexpr double kG = kStandardGravityMps2;

DevicePreset MakePreset(const std::string& name,
                        const Eigen::Vector3d& bias_g,
                        const Eigen::Vector3d& scale_kppm,
                        const Eigen::Vector3d& theta_rad,
                        const Eigen::Vector3d& bias_std_g) {
  DevicePreset p;
  p.name = name;
  p.truth.bias_mps2 = bias_g * kG;
  p.truth.scale_factor_error = scale_kppm * 1e-3;  // 10³ ppm = 1e-3
  p.truth.theta_yz_rad = theta_rad.x();
  p.truth.theta_zx_rad = theta_rad.y();
  p.truth.theta_zy_rad = theta_rad.z();
  p.turn_on_bias_std_mps2 = bias_std_g * kG;
  return p;
}

// ω = M (reading − b): M = diag(1 + scale) + the misalignment matrix (rad).
void SetGyro(DevicePreset& p,
             const Eigen::Vector3d& scale,
             const Eigen::Matrix3d& misalignment,
             const Eigen::Vector3d& bias_dps,
             double noise_dps_per_sqrt_hz,
             double walk) {
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  p.gyro_m =
      Eigen::Matrix3d::Identity() + Eigen::Matrix3d(scale.asDiagonal()) + misalignment;
  p.gyro_bias_radps = bias_dps * kDeg;
  p.gyro_noise_density_radps_per_sqrt_hz = noise_dps_per_sqrt_hz * kDeg;
  p.gyro_bias_walk_radps_per_sqrt_s = walk;
}

Eigen::Matrix3d Misalignment(
    double xy, double xz, double yx, double yz, double zx, double zy) {
  Eigen::Matrix3d m;
  m << 0.0, xy, xz, yx, 0.0, yz, zx, zy, 0.0;
  return m;
}

std::vector<DevicePreset> AllPresets() {
  std::vector<DevicePreset> presets;

  // Table 4, trial 1; spread from its last column.
  DevicePreset colibri = MakePreset("colibri",
                                    {-0.06996, 0.03056, 0.05925},
                                    {-1.99803, -1.01161, -1.00643},
                                    {0.00018, 0.00182, 0.00167},
                                    {0.008, 0.077, 0.16432});
  colibri.rate_hz = 100.0;
  colibri.noise_density_mps2_per_sqrt_hz = 0.004;
  colibri.range_mps2 = 16.0 * kG;
  colibri.resolution_mps2 = 32.0 * kG / 8192.0;
  SetGyro(colibri,
          {0.021, -0.016, 0.012},
          Misalignment(0.008, -0.012, 0.010, 0.006, -0.009, 0.011),
          {0.9, -1.4, 0.6},
          0.03,
          2e-5);
  presets.push_back(colibri);

  // Table 5, trial 1.
  DevicePreset cube = MakePreset("inertiacube3",
                                 {-0.05158, -0.00809, -0.04434},
                                 {-1.99638, -0.99057, -0.99456},
                                 {0.00018, 0.00182, 0.00167},
                                 {0.0068, 0.0095, 0.011});
  cube.rate_hz = 180.0;
  cube.noise_density_mps2_per_sqrt_hz = 0.003;
  SetGyro(cube,
          {0.006, -0.004, 0.005},
          Misalignment(0.004, -0.003, 0.005, 0.002, -0.004, 0.003),
          {0.2, -0.3, 0.1},
          0.02,
          1e-5);
  presets.push_back(cube);

  // Table 6, trial 1.
  DevicePreset mtig = MakePreset("mti-g",
                                 {0.0126, 0.01099, -0.01392},
                                 {-1.99985, -0.99094, -0.99568},
                                 {0.00001, 0.00018, 0.00017},
                                 {0.0074, 0.0017, 0.016});
  mtig.rate_hz = 512.0;
  mtig.noise_density_mps2_per_sqrt_hz = 0.002;
  mtig.range_mps2 = 50.0;
  SetGyro(mtig,
          {0.001, -0.0008, 0.0006},
          Misalignment(0.0017, -0.0012, 0.0009, 0.0015, -0.0011, 0.0013),
          {0.3, -0.5, 0.2},
          0.05,
          5e-6);
  presets.push_back(mtig);
  return presets;
}

}  // namespace

std::vector<std::string> PresetNames() {
  std::vector<std::string> names;
  for (const DevicePreset& p : AllPresets()) names.push_back(p.name);
  return names;
}

DevicePreset FindPreset(const std::string& name) {
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) {
    return static_cast<char>(std::tolower(c));
  });
  for (const DevicePreset& p : AllPresets()) {
    if (p.name == lower) return p;
  }
  throw Error(fmt::format("unknown device preset '{}'; known presets: {}",
                          name,
                          fmt::join(PresetNames(), ", ")));
}

}  // namespace mpcal
