// Kernels of `mpcal calibrate` after reading: static detection over
// a long 1 kHz session, and the whole calibration of its positions (detection
// plus the solver, which works on 27 position means whatever the log's
// length). Compare with BM_ReadLog (parse_bench) per row: detection must stay
// a small fraction of reading.
#include <benchmark/benchmark.h>

#include "mpcal/calibrate.h"
#include "mpcal/detect.h"
#include "mpcal/simulate.h"

namespace mpcal {
namespace {

// 10 s of rest + 26 × (60 s + turn) at 1 kHz: ~1.7 M samples, as the
// whole-process speed benchmark's session.
const SimulatedSession& Session() {
  static const SimulatedSession session = [] {
    SimulateStaticOptions o;
    o.device = FindPreset("mti-g");
    o.rate_hz = 1000.0;
    o.dwell_s = 60.0;
    return SimulateStatic(o);
  }();
  return session;
}

void BM_DetectStatic(benchmark::State& state) {
  const Recording& r = Session().recording;
  for (auto _ : state) {
    DetectResult d = DetectStatic(r, DetectOptions{});
    benchmark::DoNotOptimize(d.intervals.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(r.size()));
}
BENCHMARK(BM_DetectStatic)->Unit(benchmark::kMillisecond);

void BM_CalibrateRecording(benchmark::State& state) {
  const Recording& r = Session().recording;
  for (auto _ : state) {
    CalibrateResult c = CalibrateRecording(r, CalibrateOptions{});
    benchmark::DoNotOptimize(c.calibration.model.bias_mps2.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(r.size()));
}
BENCHMARK(BM_CalibrateRecording)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace mpcal

BENCHMARK_MAIN();
