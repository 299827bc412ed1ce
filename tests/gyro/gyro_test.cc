// The gyroscope from the turns: derivatives, frame convention, recovery of
// the truth at the Cramér-Rao bound, observability findings.
#include <cmath>
#include <numbers>
#include <vector>

#include <ceres/jet.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "gyro/rotation.h"
#include "gyro/turn_problem.h"
#include "gyro/turn_weights.h"
#include "mpcal/detect.h"
#include "mpcal/error.h"
#include "mpcal/gyro.h"
#include "mpcal/simulate.h"
#include "test_util.h"

namespace mpcal {
namespace {

using testing::kDeg;

SimulateStaticOptions GyroSession(std::uint64_t seed) {
  SimulateStaticOptions o;
  o.device = FindPreset("colibri");
  o.device.range_mps2 = 0.0;
  o.device.resolution_mps2 = 0.0;
  o.seed = seed;
  o.dwell_s = 5.0;
  o.gyro = true;
  return o;
}

struct Fitted {
  SimulatedSession session;
  DetectResult detection;
  GyroResult gyro;
};

Fitted Fit(const SimulateStaticOptions& options) {
  Fitted f;
  f.session = SimulateStatic(options);
  f.detection = DetectStatic(f.session.recording, {});
  f.gyro =
      CalibrateGyroscope(f.session.recording, f.detection.intervals, f.session.truth, {});
  return f;
}

TEST(GyroRotation, AnalyticJacobianMatchesAutomaticDifferentiation) {
  std::vector<internal::TurnStep> increments;
  for (int i = 0; i < 200; ++i) {
    increments.push_back(
        {Eigen::Vector3d(0.01 * std::sin(0.05 * i), 0.012 * std::cos(0.03 * i), 0.004),
         Eigen::Vector3d(0.01 * std::sin(0.05 * i + 0.05),
                         0.012 * std::cos(0.03 * i + 0.03),
                         -0.002)});
  }
  Eigen::Matrix3d m;
  m << 1.03, 0.01, -0.02, 0.015, 0.97, 0.03, -0.01, 0.02, 1.01;
  Eigen::Matrix<double, 3, 9> analytic;
  const Eigen::Matrix3d r = internal::RotationOverTurn(m, increments, &analytic);

  using Jet = ceres::Jet<double, 9>;
  Jet mj[9];
  for (int i = 0; i < 9; ++i) mj[i] = Jet(m(i / 3, i % 3), i);
  const Eigen::Matrix<Jet, 3, 3> rj = internal::RotationOverTurn<Jet>(
      mj, std::span<const internal::TurnStep>(increments));
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) EXPECT_NEAR(rj(a, b).a, r(a, b), 1e-12);
  }
  // The right perturbation δθ from dR: [δθ]× = Rᵀ dR.
  for (int p = 0; p < 9; ++p) {
    Eigen::Matrix3d dr;
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) dr(a, b) = rj(a, b).v[p];
    }
    const Eigen::Matrix3d hat = r.transpose() * dr;
    const Eigen::Vector3d d_theta(hat(2, 1), hat(0, 2), hat(1, 0));
    EXPECT_LT((d_theta - analytic.col(p)).norm(), 1e-9) << "entry " << p;
  }
}

// The weights hold what the turns' residuals are made of: at the true M the
// whitened residuals have χ²/(2n) = 1. Without the simulator's shake (3° at
// 3-9 Hz in every turn), whose integration error at 100 Hz the weights do
// not hold (χ²/(2n) 1.37 on seed 11; gone at 400 Hz): the fit's variance
// factor takes it (RecoversTheTruthWithHonestSigma keeps the shake).
TEST(GyroTurns, TrueModelCarriesGravityAtNoiseLevelAndIdentityDoesNot) {
  double truth_z2 = 0.0;
  double identity_rms = 0.0;
  double n = 0.0;
  for (std::uint64_t seed : {11, 12, 13}) {
    SimulateStaticOptions o = GyroSession(seed);
    o.shake_rotation_deg = 0.0;
    const SimulatedSession s = SimulateStatic(o);
    const DetectResult d = DetectStatic(s.recording, {});
    ASSERT_GE(d.intervals.size(), 20u);
    internal::TurnProblem p = internal::BuildTurnProblem(
        s.recording, d.intervals, s.truth, 1.0, GSensitivity::kOff, 5.0, 1.0);
    internal::WeighTurns(s.recording, d.intervals, s.truth, 1.0, &p);
    for (const internal::TurnData& t : p.turns) {
      Eigen::Vector2d r;
      internal::TurnResidual(t, s.truth.gyroscope->m, &r, nullptr);
      truth_z2 += (r / t.Sigma(1.0)).squaredNorm();
      const Eigen::Matrix3d ri =
          internal::TurnResidual(t, Eigen::Matrix3d::Identity(), nullptr, nullptr);
      identity_rms += std::pow(internal::TurnTilt(t, ri), 2);
      n += 1.0;
    }
  }
  // χ²/(2n) over about 78 turns: 1 ± 0.11 (1σ).
  EXPECT_NEAR(truth_z2 / (2.0 * n), 1.0, 0.3);
  EXPECT_GT(std::sqrt(identity_rms / n), 0.5 * kDeg);
}

TEST(CalibrateGyroscope, RecoversTheTruthWithHonestSigma) {
  const Fitted f = Fit(GyroSession(12));
  ASSERT_TRUE(f.gyro.converged()) << f.gyro.message;
  const GyroCalibration& truth = *f.session.truth.gyroscope;
  const Eigen::Matrix3d std = f.gyro.calibration.MStd();
  const Eigen::Matrix<double, 9, 9> crb = GyroCramerRaoBound(
      f.session.recording, f.detection.intervals, f.session.truth, truth);
  double z2 = 0.0;
  for (int i = 0; i < 9; ++i) {
    const double err = f.gyro.calibration.m(i / 3, i % 3) - truth.m(i / 3, i % 3);
    const double sigma = std(i / 3, i % 3);
    EXPECT_LT(std::abs(err), 4.0 * sigma) << kGyroParameterNames[i];
    // The reported 1σ is the bound (scaled up by at most the variance factor).
    EXPECT_NEAR(sigma / std::sqrt(crb(i, i)), 1.0, 0.3) << kGyroParameterNames[i];
    z2 += err * err / (sigma * sigma);
  }
  EXPECT_LT(std::sqrt(z2 / 9.0), 2.0);
  // Calibrated turns carry gravity to the noise level; the nominal do not.
  const GyroFitSummary& fit = *f.gyro.calibration.fit;
  EXPECT_LT(fit.residual_rms_after_rad, 0.3 * fit.residual_rms_before_rad);
  EXPECT_NEAR(fit.variance_factor, 1.0, 0.5);
  // The bias at every position is the truth's (no walk beyond its noise).
  EXPECT_LT((f.gyro.calibration.bias_radps - truth.bias_radps).norm(), 0.05 * kDeg);
}

TEST(CalibrateGyroscope, FindsTheScaleOfRawCounts) {
  SimulateStaticOptions o = GyroSession(13);
  o.gyro_units = GyroUnits::kCounts;
  const Fitted f = Fit(o);
  ASSERT_TRUE(f.gyro.converged()) << f.gyro.message;
  const GyroCalibration& truth = *f.session.truth.gyroscope;
  // The nominal scale is free; the product M·scale is what is determined.
  const Eigen::Matrix3d est = f.gyro.calibration.m * f.gyro.calibration.radps_per_unit;
  const Eigen::Matrix3d tru = truth.m * truth.radps_per_unit;
  EXPECT_LT((est - tru).norm() / tru.norm(), 2e-3);
  EXPECT_NEAR(f.gyro.calibration.radps_per_unit / truth.radps_per_unit, 1.0, 0.1);
}

// Turns about the body x axis only: the y and z columns of M never act.
Recording TurnsAboutX(std::vector<StaticInterval>* intervals) {
  Recording rec;
  const double rate = 100.0;
  const double dwell = 3.0;
  const double turn = 2.0;
  double angle = 0.0;
  std::uint64_t state = 1;
  auto noise = [&state]() {  // small deterministic jitter
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return (static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5) * 1e-3;
  };
  auto add = [&](double rate_x) {
    const double t = static_cast<double>(rec.size()) / rate;
    rec.time_s.push_back(t);
    const Eigen::Vector3d u(0.0, std::sin(angle), std::cos(angle));
    rec.accel.push_back(9.8 * u + Eigen::Vector3d(noise(), noise(), noise()) * 10.0);
    rec.gyro_radps.emplace_back(rate_x + noise(), noise(), noise());
  };
  for (int k = 0; k < 12; ++k) {
    const std::size_t begin = rec.size();
    for (int i = 0; i < dwell * rate; ++i) add(0.0);
    StaticInterval in;
    in.begin = begin;
    in.end = rec.size();
    in.start_s = rec.time_s[in.begin];
    in.end_s = rec.time_s[in.end - 1];
    for (std::size_t i = in.begin; i < in.end; ++i) in.mean += rec.accel[i];
    in.mean /= static_cast<double>(in.end - in.begin);
    in.std = Eigen::Vector3d::Constant(3e-3);
    intervals->push_back(in);
    const double w = 40.0 * kDeg / turn;
    for (int i = 0; i < turn * rate; ++i) {
      angle -= w / rate;
      add(w);
    }
  }
  return rec;
}

TEST(CalibrateGyroscope, TurnsAboutOneAxisNameTheColumnsAndTheAxesToAdd) {
  std::vector<StaticInterval> intervals;
  const Recording rec = TurnsAboutX(&intervals);
  Calibration accel;
  accel.gravity_mps2 = 9.8;
  const GyroResult r = CalibrateGyroscope(rec, intervals, accel, {});
  ASSERT_EQ(r.status, GyroStatus::kUndetermined);
  ASSERT_EQ(r.findings.size(), 1u);
  const GyroFinding& f = r.findings[0];
  EXPECT_EQ(f.kind, GyroFindingKind::kUndetermined);
  // Only the y and z columns (input axes) are named, and turns about y, z.
  for (int p : f.parameters) EXPECT_NE(p % 3, 0) << kGyroParameterNames[p];
  EXPECT_GE(f.parameters.size(), 4u);
  EXPECT_FALSE(f.turn_axes[0]);
  EXPECT_TRUE(f.turn_axes[1]);
  EXPECT_TRUE(f.turn_axes[2]);
}

TEST(CalibrateGyroscope, TooFewTurnsIsAFinding) {
  std::vector<StaticInterval> intervals;
  const Recording rec = TurnsAboutX(&intervals);
  intervals.resize(4);
  Calibration accel;
  accel.gravity_mps2 = 9.8;
  const GyroResult r = CalibrateGyroscope(rec, intervals, accel, {});
  ASSERT_EQ(r.status, GyroStatus::kUndetermined);
  ASSERT_EQ(r.findings.size(), 1u);
  EXPECT_EQ(r.findings[0].kind, GyroFindingKind::kTooFewTurns);
  EXPECT_EQ(r.findings[0].value, 3.0);
}

TEST(CalibrateGyroscope, RefusesALogWithoutGyroscope) {
  SimulateStaticOptions o = GyroSession(14);
  o.gyro = false;
  const SimulatedSession s = SimulateStatic(o);
  const DetectResult d = DetectStatic(s.recording, {});
  EXPECT_THROW(CalibrateGyroscope(s.recording, d.intervals, s.truth, {}), Error);
}

}  // namespace
}  // namespace mpcal
