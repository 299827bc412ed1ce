// The whole calibration (detect → solve → Calibration) on simulated
// sessions with known truth and on the team's real recordings.
#include "mpcal/calibrate.h"

#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <Eigen/QR>

#include "mpcal/error.h"
#include "mpcal/log_reader.h"
#include "mpcal/not_finite.h"
#include "mpcal/simulate.h"
#include "simulated_bound.h"
#include "test_util.h"

namespace mpcal {
namespace {

using ::testing::AnyOf;
using ::testing::HasSubstr;
using ::testing::Not;

// Whether the coverage's advice offers the 6-parameter model (bias-scale-6).
bool OffersSixParameterModel(const CoverageResult& coverage) {
  for (const CoverageStep& step : coverage.advice) {
    if (step.kind == CoverageStepKind::kSixParameterModel &&
        step.advice.settings.at(0).option == Option::kModel &&
        step.advice.settings.at(0).value == "bias-scale-6") {
      return true;
    }
  }
  return false;
}

// A Gaussian error beyond 4.5σ happens once in 150 000 draws: with 9
// parameters × 3 presets a failure means a real defect, not bad luck.
constexpr double kBoundSigmas = 4.5;

SimulateStaticOptions Session(const std::string& preset, std::uint64_t seed) {
  SimulateStaticOptions o;
  o.device = FindPreset(preset);
  o.seed = seed;
  return o;
}

class PerPreset : public ::testing::TestWithParam<std::string> {};

TEST_P(PerPreset, RecoversTheTruthWithinTheCramerRaoBound) {
  const SimulateStaticOptions options = Session(GetParam(), 3);
  const SimulatedSession s = SimulateStatic(options);
  const CalibrateResult r = CalibrateRecording(s.recording, CalibrateOptions{});
  ASSERT_TRUE(r.solve.converged()) << r.solve.message;
  EXPECT_EQ(r.positions.size(), s.directions.size() + 1);  // + the initial rest
  const Eigen::Matrix<double, 9, 1> bound =
      SimulatedBoundSigma(s, options.initial_rest_s);
  const Eigen::Matrix<double, 9, 1> error =
      ToVector(r.calibration.model) - ToVector(s.truth.model);
  const Eigen::Matrix<double, 9, 1> reported = ToVector(*r.calibration.std);
  for (int i = 0; i < 9; ++i) {
    EXPECT_LT(std::abs(error[i]), kBoundSigmas * bound[i]) << kParameterNames[i];
    EXPECT_GT(reported[i], 0.5 * bound[i]) << kParameterNames[i];
    EXPECT_LT(reported[i], 2.0 * bound[i]) << kParameterNames[i];
  }
}

INSTANTIATE_TEST_SUITE_P(Presets,
                         PerPreset,
                         ::testing::Values("colibri", "inertiacube3", "mti-g"));

// In counts the nominal scale is mpcal's own choice, so parameters are not
// comparable one by one: the correction they make is.
TEST(CalibrateRecording, RawCountsNeedNoInitialGuess) {
  SimulateStaticOptions options = Session("mti-g", 4);
  options.units = AccelUnits::kCounts;
  const SimulatedSession s = SimulateStatic(options);
  const CalibrateResult r = CalibrateRecording(s.recording, CalibrateOptions{});
  ASSERT_TRUE(r.solve.converged());
  EXPECT_EQ(r.calibration.input_units, AccelUnits::kCounts);
  const Eigen::Matrix<double, 9, 1> bound =
      SimulatedBoundSigma(s, options.initial_rest_s);
  // A reading maps to within (bias σ + g · scale σ) per axis of the truth.
  const double tolerance =
      kBoundSigmas * (bound.head<3>().maxCoeff() +
                      kStandardGravityMps2 * bound.segment<3>(3).maxCoeff());
  for (const Eigen::Vector3d& u : CubeDirections26()) {
    const Eigen::Vector3d counts =
        s.truth.model.Forward(kStandardGravityMps2 * u) / s.truth.mps2_per_unit;
    EXPECT_LT((r.calibration.Correct(counts) - s.truth.Correct(counts)).norm(),
              std::sqrt(3.0) * tolerance);
  }
}

TEST(CalibrateRecording, ReadingsInGGiveTheSameCalibrationAsInMps2) {
  SimulateStaticOptions options = Session("colibri", 5);
  const CalibrateResult mps2 = CalibrateRecording(SimulateStatic(options).recording, {});
  options.units = AccelUnits::kG;
  const CalibrateResult g = CalibrateRecording(SimulateStatic(options).recording, {});
  EXPECT_LT((ToVector(mps2.calibration.model) - ToVector(g.calibration.model)).norm(),
            1e-6);
  EXPECT_DOUBLE_EQ(g.calibration.mps2_per_unit, kStandardGravityMps2);
}

TEST(CalibrateRecording, CatchesAMps2LogReadAsG) {
  SimulatedSession s = SimulateStatic(Session("mti-g", 6));
  s.recording.units = AccelUnits::kG;  // the user said --units g
  try {
    CalibrateRecording(s.recording, {});
    FAIL();
  } catch (const UnitsError& e) {
    // One spelling of each unit, the README's (m/s², g).
    EXPECT_NEAR(e.finding().median_magnitude, kStandardGravityMps2, 0.1);
    EXPECT_THAT(e.what(),
                HasSubstr(fmt::format("the readings have a median magnitude of {:.4g} g, "
                                      "but gravity is 1 g (9.8066 m/s\u00b2); the "
                                      "readings look like m/s\u00b2",
                                      e.finding().median_magnitude)));
    EXPECT_THAT(e.what(), Not(AnyOf(HasSubstr("mps2"), HasSubstr("m/s2"))));
    EXPECT_EQ(e.finding().guess, UnitsGuess::kMps2);
    ASSERT_EQ(e.advice().settings.size(), 1u);
    EXPECT_EQ(e.advice().settings[0].option, Option::kLogUnits);
    EXPECT_EQ(e.advice().settings[0].value, "mps2");
  }
}

TEST(CalibrateRecording, RefusesANonFiniteReadingInAViewOfTheCallersMemory) {
  // Rows no log reader checked, read in place: a NaN is refused, naming its
  // column and row, never carried into a number. The gyroscope's and
  // every 16th accelerometer reading by the units check, which reads them
  // first; the other accelerometer readings by detection's first pass.
  SimulateStaticOptions options = Session("mti-g", 7);
  options.gyro = true;
  const SimulatedSession s = SimulateStatic(options);
  const std::size_t n = s.recording.size();
  auto refusal =
      [&](const std::vector<Eigen::Vector3d>& accel,
          const std::vector<Eigen::Vector3d>& gyro) -> std::optional<NotFiniteError> {
    RecordingView view = s.recording;
    view.accel = accel;
    view.gyro_radps = gyro;
    try {
      CalibrateRecording(view, {});
    } catch (const NotFiniteError& e) {
      return e;
    }
    return std::nullopt;
  };
  std::vector<Eigen::Vector3d> accel = s.recording.accel;
  std::vector<Eigen::Vector3d> gyro = s.recording.gyro_radps;
  gyro[n / 2].z() = std::numeric_limits<double>::quiet_NaN();
  auto e = refusal(accel, gyro);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->column(), RowColumn::kGyro);
  EXPECT_EQ(e->row(), n / 2);
  gyro = s.recording.gyro_radps;
  for (const std::size_t row : {std::size_t{16} * 1000, std::size_t{16} * 1000 + 5}) {
    accel = s.recording.accel;
    accel[row].x() = std::numeric_limits<double>::infinity();
    e = refusal(accel, gyro);
    ASSERT_TRUE(e) << row;
    EXPECT_EQ(e->column(), RowColumn::kAccel);
    EXPECT_EQ(e->row(), row);
  }
}

TEST(CalibrateRecording, CatchesAGLogReadAsMps2InOneUnitSpelling) {
  SimulateStaticOptions options = Session("mti-g", 6);
  options.units = AccelUnits::kG;
  SimulatedSession s = SimulateStatic(options);
  s.recording.units = AccelUnits::kMps2;  // the user left --units out
  try {
    CalibrateRecording(s.recording, {});
    FAIL();
  } catch (const UnitsError& e) {
    EXPECT_NEAR(e.finding().median_magnitude, 1.0, 0.01);
    EXPECT_THAT(e.what(),
                HasSubstr(fmt::format("the readings have a median magnitude of {:.4g} "
                                      "m/s\u00b2, but gravity is 9.8066 m/s\u00b2; the "
                                      "readings look like g",
                                      e.finding().median_magnitude)));
    EXPECT_THAT(e.what(), Not(AnyOf(HasSubstr("mps2"), HasSubstr("m/s2"))));
    EXPECT_EQ(e.finding().guess, UnitsGuess::kG);
  }
}

// A phone's "linear" acceleration: each reading less gravity, so a still
// phone reads its noise. No unit or column makes it calibratable; the
// finding says what it is, with no units to advise.
TEST(CalibrateRecording, RefusesAccelerationWithGravityRemoved) {
  SimulatedSession s = SimulateStatic(Session("mti-g", 6));
  for (Eigen::Vector3d& a : s.recording.accel) {
    a -= a.normalized() * kStandardGravityMps2;
  }
  try {
    CalibrateRecording(s.recording, {});
    FAIL();
  } catch (const UnitsError& e) {
    EXPECT_LT(e.finding().median_magnitude, 0.05 * kStandardGravityMps2);
    EXPECT_EQ(e.finding().guess, UnitsGuess::kGravityRemoved);
    EXPECT_THAT(e.what(),
                HasSubstr("the readings look like acceleration with gravity "
                          "removed"));
    EXPECT_TRUE(e.advice().settings.empty());
  }
}

TEST(CalibrateRecording, RefusesTooFewPositionsAndSaysWhatToRecord) {
  SimulateStaticOptions options = Session("mti-g", 7);
  options.positions = 6;
  options.initial_rest_s = 0.0;
  const SimulatedSession s = SimulateStatic(options);
  try {
    CalibrateRecording(s.recording, {});
    FAIL();
  } catch (const SessionError& e) {
    EXPECT_EQ(e.problem(), SessionProblem::kTooFewPositions);
    EXPECT_TRUE(OffersSixParameterModel(e.coverage()));
    EXPECT_EQ(e.advice().stage, Stage::kDetect);
  }
  // Exactly the six poses of ArduPilot and PX4: solved, with the warning
  // that nothing checks the fit.
  CalibrateOptions six;
  six.solve.model = ModelKind::kBiasScale6;
  const CalibrateResult r = CalibrateRecording(s.recording, six);
  EXPECT_TRUE(r.solve.converged());
  EXPECT_THAT(r.warnings, ::testing::Contains(HasSubstr("no redundancy")));
}

// --- The real recordings in tests/data/real/ -----------------------------

// An independent fit of the same model to the same position means: plain
// unweighted Gauss-Newton on |a_k| − g with numeric derivatives (no Ceres, no
// weights), started from mpcal's estimate. It minimises exactly the RMS the
// issue compares, so mpcal's weighted fit cannot beat it, only come close.
double IndependentUnweightedRms(const std::vector<PositionObservation>& positions,
                                ErrorModel model,
                                double gravity_mps2) {
  auto residuals = [&](const Eigen::Matrix<double, 9, 1>& p) {
    const ErrorModel m = FromVector(p);
    Eigen::VectorXd r(static_cast<Eigen::Index>(positions.size()));
    for (std::size_t k = 0; k < positions.size(); ++k) {
      r[static_cast<Eigen::Index>(k)] =
          m.Correct(positions[k].mean_mps2).norm() - gravity_mps2;
    }
    return r;
  };
  Eigen::Matrix<double, 9, 1> p = ToVector(model);
  for (int iteration = 0; iteration < 20; ++iteration) {
    const Eigen::VectorXd r = residuals(p);
    Eigen::MatrixXd j(r.size(), 9);
    for (int i = 0; i < 9; ++i) {
      Eigen::Matrix<double, 9, 1> q = p;
      const double h = 1e-7 * std::max(1.0, std::abs(p[i]));
      q[i] += h;
      j.col(i) = (residuals(q) - r) / h;
    }
    p -= j.colPivHouseholderQr().solve(r);
  }
  return std::sqrt(residuals(p).squaredNorm() / static_cast<double>(positions.size()));
}

TEST(RealRecordings, XsensRawCountsCalibrateAsWellAsImuTk) {
  LogOptions log;
  log.units = AccelUnits::kCounts;
  const Recording rec =
      ReadLog(testing::RealDataPath("xsens-multiposition/xsens_acc.mat"), log);
  CalibrateOptions options;
  options.solve.gravity_mps2 = 9.81744;  // the recording's local gravity
  const CalibrateResult r = CalibrateRecording(rec, options);
  ASSERT_TRUE(r.solve.converged());
  // The initial rest and the 37 hand-held positions.
  EXPECT_EQ(r.positions.size(), 38u);
  // imu_tk fits these positions to about 1.0 mm/s² RMS.
  EXPECT_LT(r.solve.residual_rms_after_mps2, 1.05e-3);
  const double independent =
      IndependentUnweightedRms(r.positions, r.solve.estimate, options.solve.gravity_mps2);
  EXPECT_LT(r.solve.residual_rms_after_mps2, 1.2 * independent);
}

// Its gyroscope is in deg/s: read as rad/s it reaches 895 rad/s, beyond the
// 4000 deg/s of any MEMS gyroscope, and the units are refused before
// anything is fitted, with the units it looks like.
TEST(RealRecordings, FerrarisGyroscopeInDegreesReadAsRadiansIsRefused) {
  LogOptions log;
  log.rate_hz = 102.4;
  const Recording rec =
      ReadLog(testing::RealDataPath("imucal-ferraris/example_ferraris_session.csv"), log);
  try {
    CheckUnits(rec, kStandardGravityMps2);
    FAIL() << "deg/s read as rad/s must be refused";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kUnits);
    ASSERT_EQ(e.advice().settings.size(), 1u);
    EXPECT_EQ(e.advice().settings[0].option, Option::kLogGyroUnits);
    EXPECT_EQ(e.advice().settings[0].value, "dps");
  }
  log.gyro_in_dps = true;
  EXPECT_NO_THROW(CheckUnits(
      ReadLog(testing::RealDataPath("imucal-ferraris/example_ferraris_session.csv"), log),
      kStandardGravityMps2));
}

TEST(RealRecordings, FerrarisSixPosesCalibrateWithTheSixParameterModelOnly) {
  LogOptions log;
  log.rate_hz = 102.4;
  log.gyro_in_dps = true;
  const Recording rec =
      ReadLog(testing::RealDataPath("imucal-ferraris/example_ferraris_session.csv"), log);
  try {
    CalibrateRecording(rec, CalibrateOptions{});
    FAIL() << "the 9-parameter model must be refused on six poses";
  } catch (const Error& e) {
    // Refused by the solver (eleven positions, six orientations), advising
    // the six-parameter model as a fact (the command spells it as a flag).
    ASSERT_FALSE(e.advice().settings.empty());
    EXPECT_EQ(e.advice().settings[0].option, Option::kModel);
    EXPECT_EQ(e.advice().settings[0].value, "bias-scale-6");
  }
  CalibrateOptions six;
  six.solve.model = ModelKind::kBiasScale6;
  const CalibrateResult r = CalibrateRecording(rec, six);
  ASSERT_TRUE(r.solve.converged());
  EXPECT_LT(r.solve.residual_rms_after_mps2, 0.2 * r.solve.residual_rms_before_mps2);
  const double independent =
      IndependentUnweightedRms(r.positions, r.solve.estimate, 9.80665);
  EXPECT_LT(r.solve.residual_rms_after_mps2, 1.2 * independent);
}

}  // namespace
}  // namespace mpcal

namespace mpcal {
namespace {

// The turns detect reports: one between each pair of neighbouring
// positions, each carrying the gravity direction measured before it onto
// the one after to within the simulated gyroscope's errors (a few per cent of
// scale: a degree or two on a 90 deg turn).
TEST(MeasureTurns, CarriesGravityOverEachTurnAndFindsTheScaleOfCounts) {
  SimulateStaticOptions options = Session("colibri", 11);
  options.positions = 12;
  options.dwell_s = 4.0;
  options.initial_rest_s = 0.0;
  options.gyro = true;
  const SimulatedSession s = SimulateStatic(options);
  const DetectResult det = DetectStatic(s.recording, {});
  ASSERT_EQ(det.intervals.size(), 12u);
  const std::vector<Turn> turns = MeasureTurns(s.recording, det.intervals);
  ASSERT_EQ(turns.size(), 11u);
  for (const Turn& t : turns) {
    // The rotation is at least the tilt it causes (the hand's turn about
    // gravity adds more), to within the gyroscope's scale errors (a few %).
    EXPECT_GE(t.angle_deg, 0.94 * t.tilt_deg - 1.0);
    EXPECT_GT(t.tilt_deg, 20.0);
    EXPECT_NEAR(t.axis.norm(), 1.0, 1e-9);
    EXPECT_GT(t.duration_s(), 0.0);
  }
  // The same session in raw counts: the fitted scale is the simulator's
  // (within the gyroscope's own scale errors) and the angles agree.
  options.gyro_units = GyroUnits::kCounts;
  const SimulatedSession c = SimulateStatic(options);
  double scale = 0.0;
  const std::vector<Turn> counted = MeasureTurns(c.recording, det.intervals, &scale);
  ASSERT_EQ(counted.size(), turns.size());
  EXPECT_NEAR(scale * options.gyro_counts_per_radps, 1.0, 0.08);
  for (std::size_t k = 0; k < turns.size(); ++k) {
    EXPECT_NEAR(counted[k].angle_deg, turns[k].angle_deg, 0.08 * turns[k].angle_deg);
  }
  // No gyroscope: no turns.
  Recording accel_only = s.recording;
  accel_only.gyro_radps.clear();
  EXPECT_TRUE(MeasureTurns(accel_only, det.intervals).empty());
}

}  // namespace
}  // namespace mpcal
