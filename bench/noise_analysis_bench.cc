// The analysis part of `mpcal noise` alone, without reading the log: the
// cumulative sums (in place) and the Allan curves and terms of one 3-axis
// sensor of an 8-hour record at 400 Hz (11.52 M samples). `mpcal noise`
// runs the accelerometer and the gyroscope on two threads, so its analysis
// takes about this long; the rest of its time is reading the text
// (bench/noise_bench.sh measures the whole process).
//
//   mpcal_noise_analysis_bench [--benchmark_filter=...]
#include <cstddef>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "mpcal/noise.h"

namespace {

constexpr std::size_t kSamples = 8 * 3600 * 400;

std::vector<Eigen::Vector3d> WhiteSamples(std::size_t n) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal(0.0, 0.01);
  std::vector<Eigen::Vector3d> v(n);
  for (Eigen::Vector3d& s : v) s = {normal(rng), normal(rng), 9.8 + normal(rng)};
  return v;
}

// Sums and analysis, as AnalyseNoise runs them for one sensor.
void BM_SensorAnalysis8h400Hz(benchmark::State& state) {
  const std::vector<Eigen::Vector3d> samples = WhiteSamples(kSamples);
  for (auto _ : state) {
    mpcal::AllanSums sums(mpcal::AllanOptions{});
    sums.Add(samples.data(), samples.size());
    const mpcal::SensorNoise r =
        mpcal::AnalyseSensorNoise(sums, 1.0, 1.0 / 400.0, mpcal::NoiseOptions{});
    benchmark::DoNotOptimize(r.axes[0].curve.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(kSamples));
}
BENCHMARK(BM_SensorAnalysis8h400Hz)->Unit(benchmark::kMillisecond)->UseRealTime();

// The terms alone (fit, intervals, record-length forecast) on a computed
// curve: what is left once the Allan sums are done.
void BM_TermsFromCurve(benchmark::State& state) {
  const std::vector<Eigen::Vector3d> samples = WhiteSamples(1 << 20);
  mpcal::AllanSums sums(mpcal::AllanOptions{});
  sums.Add(samples.data(), samples.size());
  for (auto _ : state) {
    const mpcal::SensorNoise r =
        mpcal::AnalyseSensorNoise(sums, 1.0, 0.0025, mpcal::NoiseOptions{});
    benchmark::DoNotOptimize(r.axes[0].curve.data());
  }
}
BENCHMARK(BM_TermsFromCurve)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
