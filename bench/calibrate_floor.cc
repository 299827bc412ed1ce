// The C++ side of bench/python_bench.sh: the session the Python bench
// calibrates (simulated in memory with the same options and seed, 1.7 M
// rows), calibrated by CalibrateRecording REPS times.
//
//   mpcal_calibrate_floor REPS
//
// Prints one line per run: the seconds CalibrateRecording took (steady
// clock), the bias x (m/s²) so that the two sides can be seen to agree, and
// the CPU seconds the process spent meanwhile (its threads' too), which a
// loaded machine does not stretch as it does the clock.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>

#include "mpcal/calibrate.h"
#include "mpcal/simulate.h"

int main(int argc, char** argv) {
  const int reps = argc > 1 ? std::atoi(argv[1]) : 5;
  mpcal::SimulateStaticOptions options;
  options.device = mpcal::FindPreset("mti-g");
  options.seed = 1;
  options.rate_hz = 1000.0;
  options.dwell_s = 60.0;
  options.initial_rest_s = 88.0;
  const mpcal::SimulatedSession session = mpcal::SimulateStatic(options);
  for (int i = 0; i < reps; ++i) {
    const std::clock_t start_cpu = std::clock();
    const auto start = std::chrono::steady_clock::now();
    const mpcal::CalibrateResult result =
        mpcal::CalibrateRecording(session.recording, mpcal::CalibrateOptions{});
    const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
    const double cpu_s = static_cast<double>(std::clock() - start_cpu) / CLOCKS_PER_SEC;
    std::printf(
        "%.6f %.12g %.6f\n", took.count(), result.calibration.model.bias_mps2.x(), cpu_s);
  }
  return 0;
}
