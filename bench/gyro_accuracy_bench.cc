// Gyroscope Monte Carlo: sessions of a consumer-grade IMU with
// random errors up to 6 % of scale, 0.03 rad of misalignment and 3 deg/s of
// bias, calibrated by the whole pipeline (detection, accelerometer, then the
// gyroscope from the turns). Per entry of M: the RMS over sessions of
// (estimate − truth) / Cramér-Rao bound of that session (bar: 1.2 over all
// entries), the RMS of z = (estimate − truth) / reported 1σ (bar: 0.8-1.25),
// and every session converged.
//
//   mpcal_gyro_accuracy_bench [SESSIONS=1000] [SEED=1]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <random>

#include <fmt/format.h>

#include "mpcal/calibrate.h"
#include "mpcal/gyro.h"
#include "mpcal/simulate.h"

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kMaxScale = 0.06;
constexpr double kMaxMisalignmentRad = 0.03;
constexpr double kMaxBiasDps = 3.0;

mpcal::SimulateStaticOptions Draw(std::mt19937_64& rng, std::uint64_t seed) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  mpcal::SimulateStaticOptions o;
  o.device = mpcal::FindPreset("colibri");
  o.device.range_mps2 = 0.0;  // no clipping in a study of the gyroscope
  o.seed = seed;
  o.gyro = true;
  o.dwell_s = 5.0;
  o.positions = 26;
  o.rate_hz = std::uniform_real_distribution<double>(100.0, 200.0)(rng);
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c)
      m(r, c) = r == c ? 1.0 + kMaxScale * u(rng) : kMaxMisalignmentRad * u(rng);
  }
  o.device.gyro_m = m;
  o.device.gyro_bias_radps = Eigen::Vector3d(u(rng), u(rng), u(rng)) * kMaxBiasDps * kDeg;
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace mpcal;
  const int sessions = argc > 1 ? std::atoi(argv[1]) : 1000;
  std::mt19937_64 rng(argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 1);
  fmt::print(
      "gyroscope accuracy: {} sessions, 26 positions, 2 s turns, 100-200 Hz, scale error "
      "<= {}, misalignment <= {} rad, bias <= {} deg/s, colibri noise\n",
      sessions,
      kMaxScale,
      kMaxMisalignmentRad,
      kMaxBiasDps);
  Eigen::Matrix<double, 9, 1> sum_bound = Eigen::Matrix<double, 9, 1>::Zero();
  Eigen::Matrix<double, 9, 1> sum_z = Eigen::Matrix<double, 9, 1>::Zero();
  int failures = 0;
  int done = 0;
  double after_deg = 0.0;
  for (int i = 0; i < sessions; ++i) {
    const SimulateStaticOptions o = Draw(rng, 1000 + static_cast<std::uint64_t>(i));
    const SimulatedSession s = SimulateStatic(o);
    CalibrateResult r;
    try {
      r = CalibrateRecording(s.recording, {});
    } catch (const std::exception& e) {
      fmt::print("session {}: {}\n", i, e.what());
      ++failures;
      continue;
    }
    if (!r.gyro || !r.gyro->converged()) {
      fmt::print(
          "session {}: gyroscope {}\n", i, r.gyro ? ToString(r.gyro->status) : "absent");
      ++failures;
      continue;
    }
    const GyroCalibration& est = r.gyro->calibration;
    const GyroCalibration& truth = *s.truth.gyroscope;
    const Eigen::Matrix<double, 9, 9> bound =
        GyroCramerRaoBound(s.recording, r.detection.intervals, r.calibration, truth);
    const Eigen::Matrix3d sigma = est.MStd();
    for (int p = 0; p < 9; ++p) {
      const double err = est.m(p / 3, p % 3) - truth.m(p / 3, p % 3);
      sum_bound[p] += err * err / bound(p, p);
      sum_z[p] += std::pow(err / sigma(p / 3, p % 3), 2);
    }
    after_deg += est.fit->residual_rms_after_rad / kDeg;
    ++done;
  }
  fmt::print("{:<8} {:>16} {:>10}\n", "entry", "RMS error/bound", "RMS z");
  for (int p = 0; p < 9; ++p) {
    fmt::print("{:<8} {:>16.3f} {:>10.3f}\n",
               kGyroParameterNames[p],
               std::sqrt(sum_bound[p] / done),
               std::sqrt(sum_z[p] / done));
  }
  const double overall = std::sqrt(sum_bound.sum() / (9.0 * done));
  const double z = std::sqrt(sum_z.sum() / (9.0 * done));
  const bool ok = failures == 0 && overall <= 1.2 && z >= 0.8 && z <= 1.25;
  fmt::print(
      "all entries: RMS error/bound {:.3f} (bar: <= 1.2), RMS z {:.3f} (bar: 0.8-1.25); "
      "mean turn residual after {:.3f} deg; converged {}/{}; {}\n",
      overall,
      z,
      after_deg / std::max(done, 1),
      done,
      sessions,
      ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
