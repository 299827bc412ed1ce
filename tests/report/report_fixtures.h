// Inputs for the report's tests: a calibration with its positions, the
// session it came from, a repeatability table and a verification, all made
// here from known values so that every section has something to show.
#pragma once

#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Core>

#include "mpcal/calibration.h"
#include "mpcal/report.h"

namespace mpcal::testing {

inline constexpr double kG = 9.80665;

/// The 26 cube directions (faces, edges, corners), unit vectors.
inline std::vector<Eigen::Vector3d> CubeDirections() {
  std::vector<Eigen::Vector3d> out;
  for (int nonzero = 1; nonzero <= 3; ++nonzero) {
    for (int i = -1; i <= 1; ++i) {
      for (int j = -1; j <= 1; ++j) {
        for (int k = -1; k <= 1; ++k) {
          if (std::abs(i) + std::abs(j) + std::abs(k) == nonzero) {
            out.push_back(Eigen::Vector3d(i, j, k).normalized());
          }
        }
      }
    }
  }
  return out;
}

inline ErrorModel FixtureModel() {
  ErrorModel m;
  m.bias_mps2 = Eigen::Vector3d(12.61, 10.99, -13.92) * kG / 1000.0;  // mg → m/s²
  m.scale_factor_error = Eigen::Vector3d(1250e-6, -990e-6, -995e-6);
  m.theta_yz_rad = 0.18e-3;
  m.theta_zx_rad = 1.82e-3;
  m.theta_zy_rad = -1.67e-3;
  return m;
}

/// Positions at `directions`, held `dwell_s` each after a 10 s rest with
/// 2 s turns between them, as a session at 50 Hz would have them.
inline Calibration FixtureCalibration(const std::vector<Eigen::Vector3d>& directions,
                                      double dwell_s = 6.0) {
  Calibration c;
  c.model = FixtureModel();
  ErrorModel s;
  s.bias_mps2 = Eigen::Vector3d::Constant(0.05 * kG / 1000.0);  // 0.05 mg
  s.scale_factor_error = Eigen::Vector3d::Constant(2e-6);
  s.theta_yz_rad = s.theta_zx_rad = s.theta_zy_rad = 0.01e-3;
  c.std = s;
  double t = 1000.0 + 10.0;
  for (std::size_t k = 0; k < directions.size(); ++k) {
    PositionSummary p;
    p.start_s = t;
    p.end_s = t + dwell_s;
    p.samples = static_cast<std::size_t>(dwell_s * 50);
    p.mean_mps2 = c.model.Forward(directions[k] * kG);
    p.residual_before_mps2 = p.mean_mps2.norm() - kG;
    p.residual_after_mps2 = 4e-4 * std::sin(1.7 * static_cast<double>(k));
    p.cross_validation_residual_mps2 = 1.3 * p.residual_after_mps2;
    p.used = k != 6;
    c.positions.push_back(p);
    t += dwell_s + 2.0;
  }
  FitSummary f;
  f.positions = static_cast<int>(directions.size()) - 1;
  f.excluded_positions = 1;
  f.residual_rms_before_mps2 = 0.15;
  f.residual_rms_after_mps2 = 2.8e-4;
  f.iterations = 6;
  f.converged = true;
  f.variance_factor = 1.04;
  f.cross_validation_rms_mps2 = 3.6e-4;
  c.fit = f;
  c.warnings = {"position 7 excluded as an outlier (residual > 5 <sigma>)"};
  c.provenance = Provenance{"0.1.0", "session.csv", "--model shin-el-sheimy-9"};
  return c;
}

/// The recording behind FixtureCalibration: rest, then each position with a
/// smooth turn before it, deterministic noise of 2 mg.
inline ReportSession FixtureSession(const Calibration& c) {
  ReportSession s;
  Recording& r = s.recording;
  r.source = "session.csv";
  r.units = AccelUnits::kMps2;
  const double rate = 50.0;
  const double t_end = c.positions.back().end_s + 5.0;
  std::uint32_t lcg = 12345;
  auto noise = [&lcg] {
    lcg = lcg * 1664525u + 1013904223u;
    return (static_cast<double>(lcg >> 8) / 16777216.0 - 0.5) * 2 * 0.02;
  };
  std::size_t next = 0;
  Eigen::Vector3d previous = c.model.Forward(Eigen::Vector3d(0, 0, kG));
  for (double t = 1000.0; t < t_end; t += 1.0 / rate) {
    while (next < c.positions.size() && t > c.positions[next].end_s) {
      previous = c.positions[next].mean_mps2;
      ++next;
    }
    Eigen::Vector3d a = previous;
    if (next < c.positions.size()) {
      const PositionSummary& p = c.positions[next];
      const double w = std::clamp((t - (p.start_s - 2.0)) / 2.0, 0.0, 1.0);
      a = (1 - w) * previous + w * p.mean_mps2;
      if (w > 0 && w < 1) a *= 1.0 + 0.3 * std::sin(std::numbers::pi * w);
    }
    r.time_s.push_back(t);
    r.accel.push_back(a + Eigen::Vector3d(noise(), noise(), noise()));
  }
  for (const PositionSummary& p : c.positions) {
    StaticInterval i;
    i.start_s = p.start_s;
    i.end_s = p.end_s;
    i.begin = static_cast<std::size_t>((p.start_s - 1000.0) * rate);
    i.end = static_cast<std::size_t>((p.end_s - 1000.0) * rate);
    i.mean = p.mean_mps2;
    s.detection.intervals.push_back(i);
  }
  s.detection.quiet_level = 0.035;
  s.detection.threshold = 0.105;
  return s;
}

/// Three trials: the bias moved between them, the rest did not.
inline RepeatabilityResult FixtureRepeatability(bool with_trial_std) {
  RepeatabilityResult r;
  r.trials = 3;
  r.trial_names = {"trial 1", "trial 2", "trial 3"};
  const ErrorModel m = FixtureModel();
  Eigen::Matrix<double, 9, 1> base = ToVector(m);
  for (int p = 0; p < kNumModelParameters; ++p) {
    ParameterRepeatability& row = r.parameters[static_cast<std::size_t>(p)];
    const double sigma = p < 3 ? 0.05e-3 * kG : p < 6 ? 2e-6 : 0.01e-3;
    const double spread = p < 3 ? 8e-3 * kG : 0.5 * sigma;  // bias: 8 mg
    row.values = {base[p] - spread, base[p] + 0.2 * spread, base[p] + 0.8 * spread};
    if (with_trial_std) row.trial_std = {sigma, sigma, sigma};
    row.mean = base[p];
    double ss = 0;
    for (double v : row.values) ss += (v - row.mean) * (v - row.mean);
    row.std_population = std::sqrt(ss / 3);
    row.std_sample = std::sqrt(ss / 2);
    if (with_trial_std) {
      row.changed = p < 3;
    } else {
      row.no_verdict_reason = "no uncertainty given";
    }
  }
  return r;
}

/// A 40 m × 25 m loop walked at 1.2 m/s, reference at 5 Hz; the raw path
/// drifts quadratically, the corrected one much less.
inline VerificationSummary FixtureVerification(bool with_paths) {
  VerificationSummary v;
  v.reference = {0.05, std::nullopt, std::nullopt, 130.0};
  v.raw = {15.3, 6.1, 15.3, 133.2};
  v.corrected = VerificationSummary::Metrics{1.6, 0.7, 1.6, 130.4};
  if (!with_paths) return v;
  EastNorthPath ref;
  EastNorthPath raw;
  EastNorthPath cor;
  const double perimeter = 130.0;
  const double duration = perimeter / 1.2;
  for (double t = 0; t <= duration; t += 0.2) {
    double d = t * 1.2;
    double e = 0;
    double n = 0;
    if (d < 40) {
      e = d;
    } else if (d < 65) {
      e = 40;
      n = d - 40;
    } else if (d < 105) {
      e = 40 - (d - 65);
      n = 25;
    } else {
      n = 25 - (d - 105);
    }
    const double tt = t / duration;
    for (auto* p : {&ref, &raw, &cor}) p->time_s.push_back(500.0 + t);
    ref.east_m.push_back(e);
    ref.north_m.push_back(n);
    raw.east_m.push_back(e + 12.0 * tt * tt);
    raw.north_m.push_back(n - 9.2 * tt * tt);
    cor.east_m.push_back(e + 1.2 * tt * tt);
    cor.north_m.push_back(n + 1.0 * tt * tt);
  }
  v.reference_path = ref;
  v.raw_path = raw;
  v.corrected_path = cor;
  v.details = {{"integration.mount", "z-up"}};
  return v;
}

/// Every section present.
inline ReportInputs FullInputs() {
  ReportInputs in;
  in.calibration = FixtureCalibration(CubeDirections());
  in.session = FixtureSession(*in.calibration);
  in.repeatability = FixtureRepeatability(true);
  in.verification = FixtureVerification(true);
  in.input_files = {{"Calibration file", "calib.json"}, {"Session log", "session.csv"}};
  in.generated_at = "2024-01-01 00:00:00 UTC";
  return in;
}

}  // namespace mpcal::testing
