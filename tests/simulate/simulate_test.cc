// Tests of the hand-held session simulator: truth, noise, geometry, units,
// presets, trials and the rejection of bad options.
#include "mpcal/simulate.h"

#include <cmath>
#include <numbers>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "mpcal/error.h"
#include "mpcal/units.h"

namespace mpcal {
namespace {

using ::testing::HasSubstr;

// A sample statistic is within this many standard errors of its expectation.
constexpr double kSigmas = 5.0;
constexpr double kDegToRad = std::numbers::pi / 180.0;

SimulateStaticOptions ShortSession(const std::string& preset = "mti-g") {
  SimulateStaticOptions options;
  options.device = FindPreset(preset);
  options.positions = 26;
  options.dwell_s = 2.0;
  options.turn_s = 1.5;
  options.initial_rest_s = 1.0;
  options.seed = 7;
  return options;
}

Eigen::Vector3d Mean(const std::vector<Eigen::Vector3d>& v,
                     std::size_t begin,
                     std::size_t end) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = begin; i < end; ++i) sum += v[i];
  return sum / static_cast<double>(end - begin);
}

Eigen::Vector3d Std(const std::vector<Eigen::Vector3d>& v,
                    std::size_t begin,
                    std::size_t end) {
  const Eigen::Vector3d mean = Mean(v, begin, end);
  Eigen::Vector3d ss = Eigen::Vector3d::Zero();
  for (std::size_t i = begin; i < end; ++i) ss += (v[i] - mean).cwiseAbs2();
  return (ss / static_cast<double>(end - begin - 1)).cwiseSqrt();
}

TEST(SimulateStatic, DefaultOptionsWithAPresetAreValid) {
  SimulateStaticOptions options;
  options.device = FindPreset("mti-g");
  EXPECT_EQ(options.Validate(), "");
}

TEST(SimulateStatic, SameSeedGivesTheSameSessionAnotherSeedADifferentOne) {
  const SimulateStaticOptions options = ShortSession();
  const SimulatedSession a = SimulateStatic(options);
  const SimulatedSession b = SimulateStatic(options);
  ASSERT_EQ(a.recording.size(), b.recording.size());
  for (std::size_t i = 0; i < a.recording.size(); ++i) {
    ASSERT_EQ(a.recording.accel[i], b.recording.accel[i]) << "sample " << i;
  }
  SimulateStaticOptions other = options;
  other.seed = 8;
  const SimulatedSession c = SimulateStatic(other);
  ASSERT_EQ(c.recording.size(), a.recording.size());
  EXPECT_NE(c.recording.accel[10], a.recording.accel[10]);
  EXPECT_NE(c.directions[0], a.directions[0]);
}

TEST(SimulateStatic, LayoutFollowsRestTurnsAndDwells) {
  const SimulateStaticOptions options = ShortSession();
  const SimulatedSession s = SimulateStatic(options);
  const double rate = options.device.rate_hz;
  const auto rest_n =
      static_cast<std::size_t>(std::llround(options.initial_rest_s * rate));
  const auto turn_n = static_cast<std::size_t>(std::llround(options.turn_s * rate));
  const auto dwell_n = static_cast<std::size_t>(std::llround(options.dwell_s * rate));
  ASSERT_EQ(s.recording.size(), rest_n + 26 * (turn_n + dwell_n));
  EXPECT_EQ(s.rate_hz, rate);
  EXPECT_EQ(s.recording.units, AccelUnits::kMps2);
  EXPECT_TRUE(s.recording.gyro_radps.empty());
  ASSERT_EQ(s.still_ranges.size(), 26u);
  ASSERT_EQ(s.directions.size(), 26u);
  for (std::size_t k = 0; k < 26; ++k) {
    EXPECT_EQ(s.still_ranges[k].first, rest_n + k * (turn_n + dwell_n) + turn_n);
    EXPECT_EQ(s.still_ranges[k].second - s.still_ranges[k].first, dwell_n);
  }
  for (std::size_t i = 1; i < s.recording.size(); ++i) {
    ASSERT_NEAR(s.recording.time_s[i] - s.recording.time_s[i - 1], 1.0 / rate, 1e-12);
  }
  EXPECT_EQ(s.recording.time_s.front(), 0.0);
}

TEST(SimulateStatic, DirectionsAreTheCubeTiltedByAtMostTheTilt) {
  SimulateStaticOptions options = ShortSession();
  options.tilt_deg = 4.0;
  const SimulatedSession s = SimulateStatic(options);
  const std::vector<Eigen::Vector3d> cube = CubeDirections26();
  double largest_deg = 0.0;
  for (std::size_t k = 0; k < 26; ++k) {
    EXPECT_NEAR(s.directions[k].norm(), 1.0, 1e-12);
    const double angle_deg =
        std::acos(std::clamp(s.directions[k].dot(cube[k]), -1.0, 1.0)) / kDegToRad;
    EXPECT_LE(angle_deg, 4.0 + 1e-9) << "position " << k;
    largest_deg = std::max(largest_deg, angle_deg);
  }
  // Uniform in [0, 4°]: 26 draws all below 1° has probability 4^-26.
  EXPECT_GT(largest_deg, 1.0);
}

TEST(SimulateStatic, CubeDirectionsAreFacesEdgesCornersAllDistinct) {
  const std::vector<Eigen::Vector3d> d = CubeDirections26();
  ASSERT_EQ(d.size(), 26u);
  for (std::size_t k = 0; k < 26; ++k) {
    EXPECT_NEAR(d[k].norm(), 1.0, 1e-15);
    const int nonzero = static_cast<int>((d[k].array().abs() > 0.1).count());
    EXPECT_EQ(nonzero, k < 6 ? 1 : (k < 18 ? 2 : 3)) << "direction " << k;
    for (std::size_t j = 0; j < k; ++j) EXPECT_LT(d[k].dot(d[j]), 0.99);
  }
  EXPECT_EQ(d[0], Eigen::Vector3d::UnitX());
  EXPECT_EQ(d[5], -Eigen::Vector3d::UnitZ());
}

TEST(SimulateStatic, FewerPositionsTakeTheFacesMoreAddRandomDirections) {
  SimulateStaticOptions options = ShortSession();
  options.positions = 6;
  const SimulatedSession six = SimulateStatic(options);
  ASSERT_EQ(six.directions.size(), 6u);
  const std::vector<Eigen::Vector3d> cube = CubeDirections26();
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_GT(six.directions[k].dot(cube[k]),
              std::cos(options.tilt_deg * kDegToRad) - 1e-12);
  }
  options.positions = 40;
  const SimulatedSession forty = SimulateStatic(options);
  ASSERT_EQ(forty.directions.size(), 40u);
  ASSERT_EQ(forty.still_ranges.size(), 40u);
  for (std::size_t k = 26; k < 40; ++k) {
    EXPECT_NEAR(forty.directions[k].norm(), 1.0, 1e-12);
  }
}

// The heart of it: the still parts read Forward(g·u) plus white noise of the
// stated σ, whatever the preset.
void ExpectStillMeansMatchTruth(const std::string& preset) {
  SCOPED_TRACE(preset);
  const SimulateStaticOptions options = ShortSession(preset);
  const double g = 9.79;
  const SimulatedSession s = SimulateStatic(options, g);
  const double sigma = options.device.noise_density_mps2_per_sqrt_hz *
                       std::sqrt(options.device.rate_hz / 2.0);
  EXPECT_NEAR(s.noise_std_mps2.x(), sigma, 1e-15);
  // Quantisation adds up to step²/12 of variance per sample.
  const double per_sample = std::hypot(sigma, s.quantisation_step_mps2 / std::sqrt(12.0));
  EXPECT_EQ(s.truth.gravity_mps2, g);
  for (std::size_t k = 0; k < s.still_ranges.size(); ++k) {
    const auto [begin, end] = s.still_ranges[k];
    const double n = static_cast<double>(end - begin);
    const Eigen::Vector3d expected = options.device.truth.Forward(g * s.directions[k]);
    const Eigen::Vector3d mean = Mean(s.recording.accel, begin, end);
    const double tolerance = kSigmas * per_sample / std::sqrt(n);
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(mean[a], expected[a], tolerance) << "position " << k << " axis " << a;
    }
    // Corrected with the truth, the still mean has the magnitude of gravity.
    EXPECT_NEAR(s.truth.Correct(mean).norm(), g, 2 * tolerance) << "position " << k;
  }
}

TEST(SimulateStatic, StillMeansAreTheForwardModelOfGravityWithinNoiseMtiG) {
  ExpectStillMeansMatchTruth("mti-g");
}
TEST(SimulateStatic, StillMeansAreTheForwardModelOfGravityWithinNoiseColibri) {
  ExpectStillMeansMatchTruth("colibri");
}
TEST(SimulateStatic, StillMeansAreTheForwardModelOfGravityWithinNoiseInertiaCube3) {
  ExpectStillMeansMatchTruth("inertiacube3");
}

TEST(SimulateStatic, StillNoiseHasTheStatedStandardDeviation) {
  const SimulateStaticOptions options = ShortSession("mti-g");
  const SimulatedSession s = SimulateStatic(options);
  // Pool the per-position sample variances: n·(positions) samples in all.
  Eigen::Vector3d pooled = Eigen::Vector3d::Zero();
  double samples = 0;
  for (const auto& [begin, end] : s.still_ranges) {
    pooled +=
        Std(s.recording.accel, begin, end).cwiseAbs2() * static_cast<double>(end - begin);
    samples += static_cast<double>(end - begin);
  }
  const Eigen::Vector3d std = (pooled / samples).cwiseSqrt();
  // The sample σ of Gaussian noise has relative standard error 1/√(2n).
  const double tolerance = kSigmas / std::sqrt(2.0 * samples);
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(std[a] / s.noise_std_mps2[a], 1.0, tolerance) << "axis " << a;
  }
}

TEST(SimulateStatic, ZeroNoiseStillSamplesAreExactlyTheForwardModel) {
  SimulateStaticOptions options = ShortSession("mti-g");
  options.device.noise_density_mps2_per_sqrt_hz = 0.0;
  const SimulatedSession s = SimulateStatic(options);
  EXPECT_EQ(s.noise_std_mps2, Eigen::Vector3d::Zero());
  for (std::size_t k = 0; k < s.still_ranges.size(); ++k) {
    const Eigen::Vector3d expected =
        options.device.truth.Forward(kStandardGravityMps2 * s.directions[k]);
    for (std::size_t i = s.still_ranges[k].first; i < s.still_ranges[k].second; ++i) {
      ASSERT_LT((s.recording.accel[i] - expected).norm(), 1e-12) << "sample " << i;
    }
  }
}

TEST(SimulateStatic, TurnsMoveWellAboveTheNoise) {
  const SimulateStaticOptions options = ShortSession("mti-g");
  const SimulatedSession s = SimulateStatic(options);
  const double sigma = s.noise_std_mps2.x();
  const auto quarter = static_cast<std::size_t>(options.turn_s * s.rate_hz / 4);
  for (std::size_t k = 0; k < s.still_ranges.size(); ++k) {
    // The middle half of the turn before position k: a 0.75 s window where a
    // static detector must see motion on at least one axis.
    const std::size_t turn_begin = s.still_ranges[k].first - 4 * quarter;
    const Eigen::Vector3d moving =
        Std(s.recording.accel, turn_begin + quarter, turn_begin + 3 * quarter);
    EXPECT_GT(moving.maxCoeff(), 10 * sigma) << "turn before position " << k;
  }
}

TEST(SimulateStatic, ShakeAloneMakesATurnBetweenEqualOrientationsMove) {
  SimulateStaticOptions options = ShortSession("mti-g");
  options.positions = 1;
  options.tilt_deg = 0.0;
  options.device.noise_density_mps2_per_sqrt_hz = 0.0;
  const SimulatedSession s = SimulateStatic(options);
  const std::size_t end = s.still_ranges[0].first;
  const std::size_t begin =
      end - static_cast<std::size_t>(std::llround(options.turn_s * s.rate_hz));
  EXPECT_GT(Std(s.recording.accel, begin, end).maxCoeff(), 0.1);
  // And the initial rest is perfectly still.
  EXPECT_LT(Std(s.recording.accel, 0, begin).maxCoeff(), 1e-12);
}

TEST(SimulateStatic, GUnitsAreMetresPerSecondSquaredOverStandardGravity) {
  SimulateStaticOptions options = ShortSession("mti-g");
  const SimulatedSession mps2 = SimulateStatic(options);
  options.units = AccelUnits::kG;
  const SimulatedSession g = SimulateStatic(options);
  EXPECT_EQ(g.recording.units, AccelUnits::kG);
  EXPECT_EQ(g.truth.input_units, AccelUnits::kG);
  EXPECT_EQ(g.truth.mps2_per_unit, kStandardGravityMps2);
  ASSERT_EQ(g.recording.size(), mps2.recording.size());
  for (std::size_t i = 0; i < g.recording.size(); i += 97) {
    EXPECT_LT(
        (g.recording.accel[i] * kStandardGravityMps2 - mps2.recording.accel[i]).norm(),
        1e-12);
  }
  EXPECT_EQ(g.truth.model.bias_mps2, mps2.truth.model.bias_mps2);
}

TEST(SimulateStatic, CountsAreIntegersAndTheTruthAbsorbsTheOffset) {
  SimulateStaticOptions options = ShortSession("mti-g");
  const SimulatedSession mps2 = SimulateStatic(options);
  options.units = AccelUnits::kCounts;
  options.counts_offset = 2048;
  options.counts_per_mps2 = 100;
  const SimulatedSession counts = SimulateStatic(options);
  EXPECT_EQ(counts.truth.input_units, AccelUnits::kCounts);
  EXPECT_DOUBLE_EQ(counts.truth.mps2_per_unit, 0.01);
  EXPECT_DOUBLE_EQ(counts.quantisation_step_mps2, 0.01);
  EXPECT_TRUE(counts.truth.model.bias_mps2.isApprox(
      mps2.truth.model.bias_mps2 + Eigen::Vector3d::Constant(20.48), 1e-12));
  for (std::size_t i = 0; i < counts.recording.size(); ++i) {
    const Eigen::Vector3d& c = counts.recording.accel[i];
    ASSERT_EQ(c, c.array().round().matrix()) << "sample " << i;
    const Eigen::Vector3d expected =
        (Eigen::Vector3d::Constant(2048) + 100 * mps2.recording.accel[i])
            .array()
            .round()
            .matrix();
    ASSERT_EQ(c, expected) << "sample " << i;
  }
  // truth.Correct(counts) is the specific force: magnitude g at rest.
  const double per_sample = std::hypot(counts.noise_std_mps2.x(), 0.01 / std::sqrt(12.0));
  for (const auto& [begin, end] : counts.still_ranges) {
    const Eigen::Vector3d mean = Mean(counts.recording.accel, begin, end);
    EXPECT_NEAR(counts.truth.Correct(mean).norm(),
                kStandardGravityMps2,
                2 * kSigmas * per_sample / std::sqrt(static_cast<double>(end - begin)));
  }
}

TEST(SimulateStatic, ColibriReadingsAreWholeMultiplesOfItsResolution) {
  const SimulatedSession s = SimulateStatic(ShortSession("colibri"));
  const double step = 32.0 * kStandardGravityMps2 / 8192.0;
  EXPECT_DOUBLE_EQ(s.quantisation_step_mps2, step);
  for (std::size_t i = 0; i < s.recording.size(); ++i) {
    const Eigen::Vector3d lsb = s.recording.accel[i] / step;
    ASSERT_LT((lsb - lsb.array().round().matrix()).cwiseAbs().maxCoeff(), 1e-9)
        << "sample " << i;
  }
}

TEST(SimulateStatic, ReadingsBeyondTheRangeAreClipped) {
  SimulateStaticOptions options = ShortSession("mti-g");
  options.device.range_mps2 = 7.0;  // below g: every face position saturates
  const SimulatedSession s = SimulateStatic(options);
  double largest = 0.0;
  for (const Eigen::Vector3d& y : s.recording.accel)
    largest = std::max(largest, y.cwiseAbs().maxCoeff());
  EXPECT_EQ(largest, 7.0);
  const auto [begin, end] = s.still_ranges[0];  // +x face: x reads about +g
  for (std::size_t i = begin; i < end; ++i) EXPECT_EQ(s.recording.accel[i].x(), 7.0);
}

TEST(SimulateStatic, GyroIntegratesToTheTurnBetweenPositions) {
  SimulateStaticOptions options = ShortSession("mti-g");
  options.gyro = true;
  options.gyro_noise_density_radps_per_sqrt_hz = 0.0;
  // An ideal gyroscope: the true rate (the preset's errors are tested in
  // tests/gyro/).
  options.device.gyro_m = Eigen::Matrix3d::Identity();
  options.device.gyro_bias_radps.setZero();
  options.device.gyro_bias_walk_radps_per_sqrt_s = 0.0;
  options.positions = 8;
  const SimulatedSession s = SimulateStatic(options);
  ASSERT_EQ(s.recording.gyro_radps.size(), s.recording.size());
  const double dt = 1.0 / s.rate_hz;
  for (std::size_t k = 1; k < s.still_ranges.size(); ++k) {
    // Body-frame increments q ← q·exp(ω dt) carry the "up" direction as
    // u ← Δ⁻¹ u: from position k−1 to position k.
    Eigen::Quaterniond delta = Eigen::Quaterniond::Identity();
    for (std::size_t i = s.still_ranges[k - 1].second; i < s.still_ranges[k].first; ++i) {
      const Eigen::Vector3d w = s.recording.gyro_radps[i];
      if (w.norm() > 0)
        delta =
            delta * Eigen::Quaterniond(Eigen::AngleAxisd(w.norm() * dt, w.normalized()));
    }
    const Eigen::Vector3d predicted = delta.conjugate() * s.directions[k - 1];
    const double error_deg =
        std::acos(std::clamp(predicted.dot(s.directions[k]), -1.0, 1.0)) / kDegToRad;
    EXPECT_LT(error_deg, 0.5) << "turn to position " << k;
  }
  // Still: no rotation at all.
  const auto [begin, end] = s.still_ranges[3];
  for (std::size_t i = begin + 1; i < end - 1; ++i)
    EXPECT_EQ(s.recording.gyro_radps[i].norm(), 0.0);
}

TEST(SimulateStatic, GyroDoesNotChangeTheAccelerometerReadings) {
  SimulateStaticOptions options = ShortSession("mti-g");
  const SimulatedSession without = SimulateStatic(options);
  options.gyro = true;
  const SimulatedSession with = SimulateStatic(options);
  ASSERT_EQ(with.recording.size(), without.recording.size());
  for (std::size_t i = 0; i < with.recording.size(); i += 101) {
    EXPECT_EQ(with.recording.accel[i], without.recording.accel[i]);
  }
}

TEST(SimulateStatic, TruthRecordsTheDeviceModelAndProvenance) {
  const SimulateStaticOptions options = ShortSession("inertiacube3");
  const SimulatedSession s = SimulateStatic(options);
  EXPECT_EQ(s.truth.model_kind, ModelKind::kShinElSheimy9);
  EXPECT_EQ(ToVector(s.truth.model), ToVector(options.device.truth));
  EXPECT_FALSE(s.truth.std.has_value());
  ASSERT_TRUE(s.truth.provenance.has_value());
  EXPECT_THAT(s.truth.provenance->options, HasSubstr("inertiacube3"));
  EXPECT_EQ(s.recording.source, "<simulated>");
}

TEST(DevicePresets, EveryPresetLoadsAndSimulates) {
  const std::vector<std::string> names = PresetNames();
  ASSERT_EQ(names, (std::vector<std::string>{"colibri", "inertiacube3", "mti-g"}));
  for (const std::string& name : names) {
    const DevicePreset p = FindPreset(name);
    EXPECT_EQ(p.name, name);
    EXPECT_GT(p.rate_hz, 0);
    EXPECT_GT(p.noise_density_mps2_per_sqrt_hz, 0);
    EXPECT_TRUE((p.turn_on_bias_std_mps2.array() > 0).all());
    SimulateStaticOptions options;
    options.device = p;
    options.positions = 3;
    options.dwell_s = 0.5;
    options.turn_s = 0.5;
    EXPECT_NO_THROW(SimulateStatic(options)) << name;
  }
  EXPECT_EQ(FindPreset("MTi-G").name, "mti-g");
}

TEST(DevicePresets, MtiGIsThePapersTrialOneInSi) {
  // The calibration-file example (Table 6, trial 1).
  const DevicePreset p = FindPreset("mti-g");
  EXPECT_NEAR(p.truth.bias_mps2.x(), 0.1236, 1e-4);
  EXPECT_NEAR(p.truth.bias_mps2.y(), 0.1078, 1e-4);
  EXPECT_NEAR(p.truth.bias_mps2.z(), -0.1365, 1e-4);
  EXPECT_NEAR(p.truth.scale_factor_error.x(), -0.0019998, 1e-7);
  EXPECT_NEAR(p.truth.scale_factor_error.y(), -0.0009909, 1e-7);
  EXPECT_NEAR(p.truth.scale_factor_error.z(), -0.0009957, 1e-7);
  EXPECT_DOUBLE_EQ(p.truth.theta_yz_rad, 1e-5);
  EXPECT_DOUBLE_EQ(p.truth.theta_zx_rad, 1.8e-4);
  EXPECT_DOUBLE_EQ(p.truth.theta_zy_rad, 1.7e-4);
  EXPECT_DOUBLE_EQ(p.noise_density_mps2_per_sqrt_hz, 0.002);
  EXPECT_DOUBLE_EQ(p.rate_hz, 512.0);
  EXPECT_NEAR(p.turn_on_bias_std_mps2.x(), 0.0074 * kStandardGravityMps2, 1e-12);
}

TEST(DevicePresets, ColibriHasSixteenGRangeAndThirteenBits) {
  const DevicePreset p = FindPreset("colibri");
  EXPECT_DOUBLE_EQ(p.range_mps2, 16 * kStandardGravityMps2);
  EXPECT_DOUBLE_EQ(p.resolution_mps2, 2 * p.range_mps2 / 8192);
  EXPECT_DOUBLE_EQ(p.rate_hz, 100.0);
  EXPECT_NEAR(p.truth.bias_mps2.z(), 0.05925 * kStandardGravityMps2, 1e-12);
  EXPECT_DOUBLE_EQ(p.truth.theta_zx_rad, 0.00182);
}

TEST(DevicePresets, UnknownNameListsTheKnownOnes) {
  try {
    FindPreset("adxl999");
    FAIL() << "no exception";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("adxl999"));
    EXPECT_THAT(e.what(), HasSubstr("colibri, inertiacube3, mti-g"));
  }
}

TEST(SimulateStatic, BadOptionsThrowNamingTheField) {
  const SimulateStaticOptions good = ShortSession();
  auto expect_rejected = [&](SimulateStaticOptions o, const std::string& field) {
    SCOPED_TRACE(field);
    EXPECT_THAT(o.Validate(), HasSubstr(field));
    EXPECT_THROW(SimulateStatic(o), Error);
  };
  SimulateStaticOptions o = good;
  o.positions = 0;
  expect_rejected(o, "positions");
  o = good;
  o.positions = -3;
  expect_rejected(o, "positions");
  o = good;
  o.dwell_s = 0;
  expect_rejected(o, "dwell_s");
  o = good;
  o.dwell_s = -1;
  expect_rejected(o, "dwell_s");
  o = good;
  o.dwell_s = std::nan("");
  expect_rejected(o, "dwell_s");
  o = good;
  o.dwell_s = 0.001;  // less than one sample
  expect_rejected(o, "dwell_s");
  o = good;
  o.turn_s = 0;
  expect_rejected(o, "turn_s");
  o = good;
  o.initial_rest_s = -1;
  expect_rejected(o, "initial_rest_s");
  o = good;
  o.rate_hz = -5;
  expect_rejected(o, "rate_hz");
  o = good;
  o.device.rate_hz = 0;
  expect_rejected(o, "rate");
  o = good;
  o.device.noise_density_mps2_per_sqrt_hz = -1;
  expect_rejected(o, "noise density");
  o = good;
  o.tilt_deg = 120;
  expect_rejected(o, "tilt_deg");
  o = good;
  o.counts_per_mps2 = 0;
  expect_rejected(o, "counts_per_mps2");
  o = good;
  o.device.truth.scale_factor_error.x() = -1.0;
  expect_rejected(o, "scale_factor_error");
  o = good;
  o.device.turn_on_bias_std_mps2.y() = -0.1;
  expect_rejected(o, "turn_on_bias_std_mps2");
  o = good;
  o.positions = 1000000;
  o.dwell_s = 60;
  expect_rejected(o, "limit");
  EXPECT_THROW(SimulateStatic(good, 0.0), Error);
  EXPECT_THROW(SimulateStatic(good, std::nan("")), Error);
}

TEST(SimulateTrials, ShareScaleAndAnglesAndDrawBiasWithTheTurnOnSpread) {
  SimulateStaticOptions options;
  options.device = FindPreset("colibri");
  options.positions = 1;
  options.dwell_s = 0.05;
  options.turn_s = 0.05;
  options.initial_rest_s = 0;
  options.seed = 3;
  constexpr int kTrials = 400;
  const std::vector<SimulatedSession> trials = SimulateTrials(options, kTrials);
  ASSERT_EQ(trials.size(), static_cast<std::size_t>(kTrials));
  const ErrorModel& nominal = options.device.truth;
  const Eigen::Vector3d spread = options.device.turn_on_bias_std_mps2;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Vector3d sum_sq = Eigen::Vector3d::Zero();
  for (const SimulatedSession& s : trials) {
    EXPECT_EQ(s.truth.model.scale_factor_error, nominal.scale_factor_error);
    EXPECT_EQ(s.truth.model.theta_yz_rad, nominal.theta_yz_rad);
    EXPECT_EQ(s.truth.model.theta_zx_rad, nominal.theta_zx_rad);
    EXPECT_EQ(s.truth.model.theta_zy_rad, nominal.theta_zy_rad);
    const Eigen::Vector3d z =
        (s.truth.model.bias_mps2 - nominal.bias_mps2).cwiseQuotient(spread);
    sum += z;
    sum_sq += z.cwiseAbs2();
  }
  const double n = kTrials;
  const Eigen::Vector3d mean = sum / n;
  const Eigen::Vector3d std = ((sum_sq - n * mean.cwiseAbs2()) / (n - 1)).cwiseSqrt();
  for (int a = 0; a < 3; ++a) {
    // Standardised draws: mean 0 ± 1/√n, σ 1 ± 1/√(2n).
    EXPECT_NEAR(mean[a], 0.0, kSigmas / std::sqrt(n)) << "axis " << a;
    EXPECT_NEAR(std[a], 1.0, kSigmas / std::sqrt(2 * n)) << "axis " << a;
  }
  EXPECT_NE(trials[0].directions[0], trials[1].directions[0]);
  EXPECT_NE(trials[0].truth.model.bias_mps2, trials[1].truth.model.bias_mps2);
}

TEST(SimulateTrials, EachTrialIsTheStaticSessionOfItsSeedAndBias) {
  SimulateStaticOptions options = ShortSession("mti-g");
  options.positions = 4;
  const std::vector<SimulatedSession> trials = SimulateTrials(options, 3);
  ASSERT_EQ(trials.size(), 3u);
  for (int i = 1; i <= 3; ++i) {
    SimulateStaticOptions single = options;
    single.seed = TrialSeed(options.seed, i);
    single.device.truth.bias_mps2 = trials[i - 1].truth.model.bias_mps2;
    const SimulatedSession s = SimulateStatic(single);
    EXPECT_EQ(s.recording.accel, trials[i - 1].recording.accel) << "trial " << i;
  }
  EXPECT_NE(TrialSeed(1, 1), TrialSeed(1, 2));
  EXPECT_NE(TrialSeed(1, 1), TrialSeed(2, 1));
}

TEST(SimulateTrials, ZeroSpreadKeepsTheBiasAndBadCountsThrow) {
  SimulateStaticOptions options = ShortSession("mti-g");
  options.positions = 2;
  options.device.turn_on_bias_std_mps2.setZero();
  for (const SimulatedSession& s : SimulateTrials(options, 2)) {
    EXPECT_EQ(s.truth.model.bias_mps2, options.device.truth.bias_mps2);
  }
  EXPECT_THROW(SimulateTrials(options, 0), Error);
  options.dwell_s = -1;
  EXPECT_THROW(SimulateTrials(options, 2), Error);
}

}  // namespace
}  // namespace mpcal
