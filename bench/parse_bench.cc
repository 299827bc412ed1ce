// Kernels of `mpcal calibrate` and `mpcal apply` on long logs:
// reading a log (ReadLog) against the floor of parsing its numbers with
// fast_float alone, streaming a correction (ApplyCalibration), and the
// per-row correction itself, eqs 8-10 as written (trigonometry per call)
// against the folded matrix of Corrector.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include <benchmark/benchmark.h>
#include <fast_float/fast_float.h>
#include <fmt/format.h>

#include "mpcal/apply.h"
#include "mpcal/calibration.h"
#include "mpcal/log_reader.h"

namespace mpcal {
namespace {

constexpr int kRows = 200000;  // 200 s at 1 kHz, ~10 MB

// A 1 kHz log in the simulator's shape (t, ax, ay, az; 9 significant digits),
// written once per process.
const std::string& LogPath() {
  static const std::string path = [] {
    const std::string p = (std::filesystem::temp_directory_path() /
                           fmt::format("mpcal_parse_bench_{}.csv", ::getpid()))
                              .string();
    std::mt19937_64 rng(1);
    std::normal_distribution<double> noise(0.0, 0.01);
    std::ofstream out(p, std::ios::binary);
    out << "t,ax,ay,az\n";
    for (int i = 0; i < kRows; ++i) {
      out << fmt::format("{},{:.9g},{:.9g},{:.9g}\n",
                         i * 0.001,
                         0.12 + noise(rng),
                         -0.34 + noise(rng),
                         9.80665 + noise(rng));
    }
    std::atexit([] { std::filesystem::remove(LogPath()); });
    return p;
  }();
  return path;
}

std::string ReadAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

Calibration ExampleCalibration() {
  Calibration c;
  c.model.bias_mps2 = {0.1236, 0.1078, -0.1365};
  c.model.scale_factor_error = {-0.0019998, -0.0009909, -0.0009957};
  c.model.theta_yz_rad = 1e-5;
  c.model.theta_zx_rad = 1.8e-4;
  c.model.theta_zy_rad = 1.7e-4;
  return c;
}

// The floor: every number of the file (in memory) through fast_float.
void BM_FloorParseInMemory(benchmark::State& state) {
  const std::string text = ReadAll(LogPath());
  for (auto _ : state) {
    const char* p = text.data();
    const char* const end = p + text.size();
    double sum = 0.0;
    while (p < end) {
      while (p < end && !((*p >= '0' && *p <= '9') || *p == '-' || *p == '.')) ++p;
      double v = 0.0;
      const auto r = fast_float::from_chars(p, end, v);
      if (r.ec != std::errc()) {
        ++p;
        continue;
      }
      sum += v;
      p = r.ptr;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * text.size()));
  state.SetItemsProcessed(state.iterations() * kRows);
}
BENCHMARK(BM_FloorParseInMemory)->Unit(benchmark::kMillisecond);

void BM_ReadLog(benchmark::State& state) {
  const auto bytes = std::filesystem::file_size(LogPath());
  for (auto _ : state) {
    Recording r = ReadLog(LogPath(), {});
    benchmark::DoNotOptimize(r.accel.data());
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes));
  state.SetItemsProcessed(state.iterations() * kRows);
}
BENCHMARK(BM_ReadLog)->Unit(benchmark::kMillisecond);

void BM_ApplyCalibration(benchmark::State& state) {
  const auto bytes = std::filesystem::file_size(LogPath());
  const std::string out = LogPath() + ".out";
  const Calibration c = ExampleCalibration();
  for (auto _ : state) {
    ApplyResult r = ApplyCalibration(c, LogPath(), out, {});
    benchmark::DoNotOptimize(r.data_rows);
  }
  std::filesystem::remove(out);
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes));
  state.SetItemsProcessed(state.iterations() * kRows);
}
BENCHMARK(BM_ApplyCalibration)->Unit(benchmark::kMillisecond);

// Eqs 8-10 as Calibration::Correct evaluates them: six trigonometric calls
// per row.
void BM_CorrectPerRow(benchmark::State& state) {
  const Calibration c = ExampleCalibration();
  Eigen::Vector3d y(0.1, -0.2, 9.8);
  for (auto _ : state) {
    y = c.Correct(y);
    benchmark::DoNotOptimize(y);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CorrectPerRow);

// The same correction folded into one 3×3 matrix and an offset.
void BM_CorrectFolded(benchmark::State& state) {
  const Corrector correct(ExampleCalibration(), AccelUnits::kMps2, AccelUnits::kMps2);
  Eigen::Vector3d y(0.1, -0.2, 9.8);
  for (auto _ : state) {
    y = correct(y);
    benchmark::DoNotOptimize(y);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CorrectFolded);

}  // namespace
}  // namespace mpcal

BENCHMARK_MAIN();
