// The gyroscope's stage of `mpcal calibrate` alone (its speed bar is
// on the whole process, bench/gyro_speed_bench.sh): on imu_tk's Xsens
// recording read once, with its positions and accelerometer calibration,
// CalibrateGyroscope from raw counts (the scale found from the data), and
// its kernel, one turn's rotation with the Jacobian per entry of M.
#include <benchmark/benchmark.h>

#include <string>

#include "gyro/rotation.h"
#include "gyro/turn_problem.h"
#include "mpcal/calibrate.h"
#include "mpcal/gyro.h"
#include "mpcal/gyro_log.h"
#include "mpcal/log_reader.h"

namespace mpcal {
namespace {

struct Xsens {
  Recording recording;
  CalibrateResult accel;
};

const Xsens& Session() {
  static const Xsens session = [] {
    const std::string dir = std::string(MPCAL_REAL_DATA_DIR) + "/xsens-multiposition/";
    LogOptions log;
    log.units = AccelUnits::kCounts;
    Xsens s;
    s.recording = ReadLog(dir + "xsens_acc.mat", log);
    MergeGyroLog(s.recording, ReadLog(dir + "xsens_gyro.mat", log), GyroUnits::kCounts);
    CalibrateOptions options;
    options.solve.gravity_mps2 = 9.81744;
    options.calibrate_gyroscope = false;
    s.accel = CalibrateRecording(s.recording, options);
    return s;
  }();
  return session;
}

void BM_CalibrateGyroscopeXsens(benchmark::State& state) {
  const Xsens& s = Session();
  for (auto _ : state) {
    GyroResult r = CalibrateGyroscope(
        s.recording, s.accel.detection.intervals, s.accel.calibration, GyroOptions{});
    benchmark::DoNotOptimize(r.calibration.m.data());
  }
}
BENCHMARK(BM_CalibrateGyroscopeXsens)->Unit(benchmark::kMillisecond);

// Every turn of the recording integrated with the Jacobian (per sample).
void BM_RotationOverTurnWithJacobian(benchmark::State& state) {
  const Xsens& s = Session();
  const internal::TurnProblem p = internal::BuildTurnProblem(s.recording,
                                                             s.accel.detection.intervals,
                                                             s.accel.calibration,
                                                             1.0,
                                                             GSensitivity::kOff,
                                                             5.0,
                                                             0.0);
  const Eigen::Matrix3d m = 2.09e-4 * Eigen::Matrix3d::Identity();
  std::int64_t samples = 0;
  for (const internal::TurnData& t : p.turns) samples += std::ssize(t.steps);
  for (auto _ : state) {
    for (const internal::TurnData& t : p.turns) {
      Eigen::Matrix<double, 3, 9> jacobian;
      benchmark::DoNotOptimize(internal::RotationOverTurn(m, t.steps, &jacobian));
      benchmark::DoNotOptimize(jacobian.data());
    }
  }
  state.SetItemsProcessed(state.iterations() * samples);
}
BENCHMARK(BM_RotationOverTurnWithJacobian)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace mpcal

BENCHMARK_MAIN();
