// Kernels of `mpcal simulate static`: simulating the default MTi-G session
// (26 positions, 512 Hz, 164,864 samples) and writing it as CSV, with and
// without exact (shortest round-trip) digits and the gyroscope.
#include <sstream>
#include <string>

#include <benchmark/benchmark.h>

#include "mpcal/log_writer.h"
#include "mpcal/simulate.h"

namespace mpcal {
namespace {

SimulateStaticOptions DefaultOptions(bool gyro) {
  SimulateStaticOptions options;
  options.device = FindPreset("mti-g");
  options.gyro = gyro;
  return options;
}

void BM_SimulateStatic(benchmark::State& state) {
  const SimulateStaticOptions options = DefaultOptions(state.range(0) != 0);
  std::size_t samples = 0;
  for (auto _ : state) {
    const SimulatedSession s = SimulateStatic(options);
    samples = s.recording.size();
    benchmark::DoNotOptimize(s.recording.accel.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * samples));
  state.SetLabel(state.range(0) != 0 ? "with gyro" : "accelerometer only");
}
BENCHMARK(BM_SimulateStatic)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_WriteRecordingCsv(benchmark::State& state) {
  const SimulatedSession s = SimulateStatic(DefaultOptions(false));
  LogWriteOptions write;
  write.significant_digits = static_cast<int>(state.range(0));
  std::size_t bytes = 0;
  for (auto _ : state) {
    std::ostringstream out;
    WriteRecordingCsv(out, s.recording, write);
    bytes = out.str().size();
    benchmark::DoNotOptimize(bytes);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes));
  state.SetItemsProcessed(
      static_cast<std::int64_t>(state.iterations() * s.recording.size()));
  state.SetLabel(state.range(0) == 0 ? "exact digits" : "9 significant digits");
}
BENCHMARK(BM_WriteRecordingCsv)->Arg(9)->Arg(0)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace mpcal

BENCHMARK_MAIN();
