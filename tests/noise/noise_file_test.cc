// The noise files: the JSON read back as written, and Kalibr's YAML with the
// measured values, the rule across axes and upper bounds labelled.
#include <cmath>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "mpcal/error.h"
#include "mpcal/noise.h"
#include "mpcal/noise_file.h"

namespace mpcal {
namespace {

using testing::HasSubstr;

TermEstimate Measured(double v) {
  TermEstimate e;
  e.status = TermStatus::kMeasured;
  e.value = v;
  e.lo = 0.9 * v;
  e.hi = 1.1 * v;
  e.tau_lo_s = 0.01;
  e.tau_hi_s = 1.0;
  return e;
}

TermEstimate Bound(double ub, double needed_s) {
  TermEstimate e;
  e.status = TermStatus::kNotSeen;
  e.upper_bound = ub;
  e.record_needed_s = needed_s;
  return e;
}

NoiseResult Example(bool gyro_walk_measured) {
  NoiseResult r;
  r.rate_hz = 200.0;
  r.sample_period_s = 0.005;
  r.record_s = 7200.0;
  r.samples = 1440000;
  r.segment.end = r.samples;
  SensorNoise a, g;
  for (int i = 0; i < 3; ++i) {
    a.axes[i].terms[1] = Measured(1e-3 * (1 + i));  // white noise: largest on z
    a.axes[i].terms[3] = Measured(2e-5 * (3 - i));  // random walk: largest on x
    g.axes[i].terms[1] = Measured(1e-4 * (1 + 0.1 * i));
    g.axes[i].terms[3] =
        gyro_walk_measured ? Measured(3e-6) : Bound(5e-6 * (1 + i), 30000.0);
    for (AxisNoise* ax : {&a.axes[i], &g.axes[i]}) {
      AllanPoint p;
      p.tau_s = 0.005;
      p.m = 1;
      p.avar = 4e-6;
      p.adev = 2e-3;
      p.adev_lo = 1.9e-3;
      p.adev_hi = 2.1e-3;
      p.edf = 1e6;
      ax->curve.push_back(p);
    }
  }
  SetRecordNeeded(a);
  SetRecordNeeded(g);
  r.accel_mps2 = a;
  r.gyro_radps = g;
  return r;
}

TEST(NoiseJson, ReadsBackWhatItWrote) {
  const NoiseResult r = Example(false);
  const std::string text = NoiseJson(r, "still.csv", 0.95);
  EXPECT_THAT(text, HasSubstr("\"format\": \"mpcal.noise/1\""));
  EXPECT_THAT(text, HasSubstr("\"white_noise_mps2_per_rthz\""));
  EXPECT_THAT(text, HasSubstr("\"random_walk_radps2_per_rthz\""));
  const NoiseFile f = ParseNoiseJson(text, "test");
  EXPECT_EQ(f.input, "still.csv");
  EXPECT_DOUBLE_EQ(f.result.rate_hz, 200.0);
  ASSERT_TRUE(f.result.gyro_radps.has_value());
  EXPECT_DOUBLE_EQ(*f.result.accel_mps2.axes[2].term(NoiseTerm::kWhiteNoise).value, 3e-3);
  const TermEstimate& k = f.result.gyro_radps->axes[1].term(NoiseTerm::kRandomWalk);
  EXPECT_EQ(k.status, TermStatus::kNotSeen);
  EXPECT_FALSE(k.value.has_value());
  EXPECT_DOUBLE_EQ(k.upper_bound, 1e-5);
  EXPECT_DOUBLE_EQ(*k.record_needed_s, 30000.0);
  ASSERT_EQ(f.result.accel_mps2.axes[0].curve.size(), 1u);
  EXPECT_DOUBLE_EQ(f.result.accel_mps2.axes[0].curve[0].adev_hi, 2.1e-3);
}

TEST(NoiseJson, RefusesAnotherFormat) {
  EXPECT_THROW(ParseNoiseJson("{\"format\": \"mpcal.noise/2\"}", "x"), Error);
  EXPECT_THROW(ParseNoiseJson("{\"format\": \"mpcal.accelerometer/1\"}", "x"), Error);
  EXPECT_THROW(ParseNoiseJson("[]", "x"), Error);
}

TEST(KalibrYaml, LargestAxisOfMeasuredValues) {
  const KalibrFile k = KalibrYaml(Example(true), "still.csv", "/imu0");
  EXPECT_THAT(k.text, HasSubstr("accelerometer_noise_density: 3.000000e-03"));
  EXPECT_THAT(k.text, HasSubstr("accelerometer_random_walk: 6.000000e-05"));
  EXPECT_THAT(k.text, HasSubstr("gyroscope_noise_density: 1.200000e-04"));
  EXPECT_THAT(k.text, HasSubstr("gyroscope_random_walk: 3.000000e-06"));
  EXPECT_THAT(k.text, HasSubstr("update_rate: 200"));
  EXPECT_THAT(k.text, HasSubstr("rostopic: \"/imu0\""));
  EXPECT_THAT(k.text, HasSubstr("# Rule across axes: the largest of x, y, z"));
  EXPECT_THAT(k.text, HasSubstr("from axis z"));
  EXPECT_THAT(k.text, testing::Not(HasSubstr("UPPER BOUND")));
  EXPECT_EQ(k.accel_noise_density.axis, 2);
  EXPECT_EQ(k.accel_random_walk.axis, 0);
  EXPECT_FALSE(k.gyro_random_walk.upper_bound);
}

TEST(KalibrYaml, RandomWalkNotMeasuredIsItsBoundLabelled) {
  const KalibrFile k = KalibrYaml(Example(false), "still.csv", "/imu0");
  EXPECT_TRUE(k.gyro_random_walk.upper_bound);
  EXPECT_DOUBLE_EQ(k.gyro_random_walk.value, 1.5e-5);
  EXPECT_THAT(
      k.text,
      HasSubstr("gyroscope_random_walk: 1.500000e-05  # UPPER BOUND, rad/s^2/sqrt(Hz)"));
  EXPECT_THAT(k.text, HasSubstr("NOT MEASURED"));
  EXPECT_THAT(k.text, HasSubstr("record at least 8.3 h"));
  ASSERT_TRUE(k.gyro_random_walk.record_needed_s.has_value());
  EXPECT_DOUBLE_EQ(*k.gyro_random_walk.record_needed_s, 30000.0);
}

// One axis measured, the others only bounded above it: the file carries the
// measured value, and its comment names the axes that were not measured.
TEST(KalibrYaml, ABoundNeverWinsOverAMeasuredValue) {
  NoiseResult r = Example(false);
  r.gyro_radps->axes[0].terms[3] = Measured(2e-6);  // y and z: bounds 1e-5, 1.5e-5
  SetRecordNeeded(*r.gyro_radps);
  const KalibrFile k = KalibrYaml(r, "still.csv", "/imu0");
  EXPECT_FALSE(k.gyro_random_walk.upper_bound);
  EXPECT_EQ(k.gyro_random_walk.axis, 0);
  EXPECT_DOUBLE_EQ(k.gyro_random_walk.value, 2e-6);
  EXPECT_THAT(k.text,
              HasSubstr("gyroscope_random_walk: 2.000000e-06  # rad/s^2/sqrt(Hz)"));
  EXPECT_THAT(k.text, HasSubstr("not measured on y, z (its bound not used)"));
}

// The model check goes to the JSON and back, a term where the model misses
// the curve reads back as `disagrees` with its bound, and the Kalibr file
// says so on the value's comment line and in the sensor's check line.
TEST(NoiseJson, ModelCheckAndDisagreeingTermReadBack) {
  NoiseResult r = Example(true);
  ModelCheck& c = r.accel_mps2.axes[1].check;
  c.points = 61;
  c.outside = 40;
  c.share_outside = 40.0 / 61.0;
  c.fits = false;
  c.disagree = {TauRange{0.01, 0.03}, TauRange{0.19, 2.6}};
  c.from_tau_s = 0.005;
  TermEstimate e;
  e.status = TermStatus::kDisagrees;
  e.upper_bound = 5e-3;
  for (AxisNoise& a : r.accel_mps2.axes) a.terms[1] = e;
  r.gyro_radps->axes[2].check = ModelCheck{57, 0, 0.0, {}, true, 0.04, 4};
  const NoiseFile back = ParseNoiseJson(NoiseJson(r, "still.csv", 0.95), "test");
  const ModelCheck& b = back.result.accel_mps2.axes[1].check;
  EXPECT_EQ(b.points, 61);
  EXPECT_EQ(b.outside, 40);
  EXPECT_FALSE(b.fits);
  ASSERT_EQ(b.disagree.size(), 2u);
  EXPECT_DOUBLE_EQ(b.disagree[1].hi_s, 2.6);
  EXPECT_EQ(back.result.gyro_radps->axes[2].check.excluded, 4);
  EXPECT_DOUBLE_EQ(back.result.gyro_radps->axes[2].check.from_tau_s, 0.04);
  const TermEstimate& n = back.result.accel_mps2.axes[1].term(NoiseTerm::kWhiteNoise);
  EXPECT_EQ(n.status, TermStatus::kDisagrees);
  EXPECT_DOUBLE_EQ(n.upper_bound, 5e-3);
  const KalibrFile k = KalibrYaml(r, "still.csv", "/imu0");
  EXPECT_TRUE(k.accel_noise_density.upper_bound);
  EXPECT_THAT(k.text, HasSubstr("NOT MEASURED: the model misses the curve"));
  EXPECT_THAT(k.text, HasSubstr("y MISSES (40 of 61 cluster times outside"));
  EXPECT_THAT(k.text, HasSubstr("fitted from tau = 0.04 s"));
}

// The Gauss-Markov process and the sinusoid go to the JSON and back with
// their intervals, regions and fitted curves; a term not seen reads back
// without figures, and one left out of the model says so.
TEST(NoiseJson, GaussMarkovAndSinusoidReadBack) {
  NoiseResult r = Example(true);
  AxisNoise& ax = r.accel_mps2.axes[0];
  ax.gauss_markov.status = TermStatus::kMeasured;
  ax.gauss_markov.sigma = 2e-3;
  ax.gauss_markov.sigma_lo = 1.8e-3;
  ax.gauss_markov.sigma_hi = 2.3e-3;
  ax.gauss_markov.tau_c_s = 0.3;
  ax.gauss_markov.tau_c_lo_s = 0.25;
  ax.gauss_markov.tau_c_hi_s = 0.37;
  ax.gauss_markov.tau_lo_s = 0.2;
  ax.gauss_markov.tau_hi_s = 2.5;
  ax.fit_gauss_markov = {4e-6, 0.3};
  AxisNoise& gz = r.gyro_radps->axes[2];
  gz.sinusoid.status = TermStatus::kMeasured;
  gz.sinusoid.amplitude = 3e-4;
  gz.sinusoid.amplitude_lo = 2.8e-4;
  gz.sinusoid.amplitude_hi = 3.2e-4;
  gz.sinusoid.period_s = 2.0;
  gz.sinusoid.period_lo_s = 1.9;
  gz.sinusoid.period_hi_s = 2.1;
  gz.sinusoid.tau_lo_s = 0.4;
  gz.sinusoid.tau_hi_s = 1.2;
  gz.fit_sinusoid = {9e-8, 2.0};
  r.accel_mps2.axes[1].sinusoid.modelled = false;
  const std::string text = NoiseJson(r, "still.csv", 0.95);
  EXPECT_THAT(text, HasSubstr("\"sigma_mps2\""));
  EXPECT_THAT(text, HasSubstr("\"amplitude_radps\""));
  const NoiseFile back = ParseNoiseJson(text, "test");
  const GaussMarkovTerm& g = back.result.accel_mps2.axes[0].gauss_markov;
  EXPECT_EQ(g.status, TermStatus::kMeasured);
  EXPECT_DOUBLE_EQ(*g.sigma, 2e-3);
  EXPECT_DOUBLE_EQ(g.tau_c_hi_s, 0.37);
  EXPECT_DOUBLE_EQ(g.tau_hi_s, 2.5);
  const SinusoidTerm& s = back.result.gyro_radps->axes[2].sinusoid;
  EXPECT_EQ(s.status, TermStatus::kMeasured);
  EXPECT_DOUBLE_EQ(*s.amplitude, 3e-4);
  EXPECT_DOUBLE_EQ(s.period_lo_s, 1.9);
  EXPECT_DOUBLE_EQ(s.tau_lo_s, 0.4);
  // The fitted curve reads back: σ and A are written, their squares kept.
  const AxisNoise& bx = back.result.accel_mps2.axes[0];
  EXPECT_NEAR(bx.fit_gauss_markov.sigma2, 4e-6, 1e-18);
  EXPECT_NEAR(bx.FittedAvar(0.6), ax.FittedAvar(0.6), 1e-12 * ax.FittedAvar(0.6));
  EXPECT_NEAR(back.result.gyro_radps->axes[2].FittedAvar(0.7),
              gz.FittedAvar(0.7),
              1e-12 * gz.FittedAvar(0.7));
  const SinusoidTerm& none = back.result.accel_mps2.axes[1].sinusoid;
  EXPECT_EQ(none.status, TermStatus::kNotSeen);
  EXPECT_FALSE(none.amplitude.has_value());
  EXPECT_FALSE(none.modelled);
  EXPECT_TRUE(back.result.accel_mps2.axes[2].sinusoid.modelled);
}

// The sensor's one figure of how long to record: the longest of the axes
// where the term was not seen, whichever axis the Kalibr value came from.
TEST(KalibrYaml, RecordNeededIsTheSensorsOneFigure) {
  NoiseResult r = Example(false);
  r.gyro_radps->axes[0].terms[3].record_needed_s = 50000.0;  // x: bound 5e-6
  SetRecordNeeded(*r.gyro_radps);
  EXPECT_DOUBLE_EQ(*r.gyro_radps->record_needed_s[3], 50000.0);
  const KalibrFile k = KalibrYaml(r, "still.csv", "/imu0");
  EXPECT_EQ(k.gyro_random_walk.axis, 2);  // the largest bound is z's
  EXPECT_DOUBLE_EQ(*k.gyro_random_walk.record_needed_s, 50000.0);
  EXPECT_THAT(k.text, HasSubstr("record at least " + FormatRecordLength(50000.0)));
  EXPECT_EQ(FormatRecordLength(50000.0), "13.9 h");
  EXPECT_EQ(FormatRecordLength(2760.0), "46 min");
  const NoiseFile back = ParseNoiseJson(NoiseJson(r, "still.csv", 0.95), "test");
  EXPECT_DOUBLE_EQ(*back.result.gyro_radps->record_needed_s[3], 50000.0);
}

// Read back by a YAML parser: every key once, every value as written, a
// hostile topic and input name kept whole (no injected key, no truncation).
TEST(KalibrYaml, ReadsBackWithHostileNames) {
  const std::string topic = "/imu0\nupdate_rate: 1 # cut: here";
  const std::string input = "a\nrostopic: x # b.csv";
  const NoiseResult r = Example(false);
  const KalibrFile k = KalibrYaml(r, input, topic);
  const YAML::Node y = YAML::Load(k.text);
  ASSERT_TRUE(y.IsMap());
  EXPECT_EQ(y.size(), 6u);
  EXPECT_EQ(y["rostopic"].as<std::string>(), topic);
  EXPECT_DOUBLE_EQ(y["update_rate"].as<double>(), 200.0);
  EXPECT_NEAR(y["accelerometer_noise_density"].as<double>() / 3e-3, 1.0, 1e-6);
  EXPECT_NEAR(y["accelerometer_random_walk"].as<double>() / 6e-5, 1.0, 1e-6);
  EXPECT_NEAR(y["gyroscope_noise_density"].as<double>() / 1.2e-4, 1.0, 1e-6);
  EXPECT_NEAR(y["gyroscope_random_walk"].as<double>() / 1.5e-5, 1.0, 1e-6);
  // The comment lines: the header, and one line per value.
  EXPECT_THAT(k.text, HasSubstr("# Kalibr IMU noise model, measured by mpcal"));
  EXPECT_THAT(k.text, HasSubstr("# Rule across axes: the largest of x, y, z"));
  EXPECT_THAT(k.text, HasSubstr("# gyroscope_random_walk from axis z"));
  EXPECT_THAT(k.text, HasSubstr("m/s^2/sqrt(Hz)"));
}

TEST(KalibrYaml, NeedsAGyroscope) {
  NoiseResult r = Example(true);
  r.gyro_radps.reset();
  EXPECT_THROW(KalibrYaml(r, "a.csv", "/imu0"), Error);
}

}  // namespace
}  // namespace mpcal
