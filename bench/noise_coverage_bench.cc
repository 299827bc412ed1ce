// Coverage of the noise terms on mpcal's own simulator (src/simulate), in
// process: records of 2-8 h at 50-400 Hz with the "consumer" preset (its
// random walks show within an hour), many seeds each; per axis, N against
// the truth (bar: 3 %), K inside its reported interval (bar: 90 % of the
// axes where it is measured), B inside its interval or within 25 %.
//
//   mpcal_noise_coverage_bench [SEEDS_PER_CASE] [PRESET]
//
// Exit status 0 when every bar is met. The independent counterpart (data
// from bench/independent/gen_still.py through the whole command) is
// bench/independent_noise_bench.sh.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "mpcal/noise.h"
#include "mpcal/simulate_noise.h"

namespace {

struct Case {
  double hours;
  double rate_hz;
};

struct Tally {
  double worst_n = 0.0;
  int axes = 0;
  int k_measured = 0;
  int k_inside = 0;
  int k_high = 0;  // truth below the interval
  int k_bound_ok = 0;
  int k_not = 0;
  int b_measured = 0;
  int b_ok = 0;
};

mpcal::NoiseResult Analyse(const mpcal::NoiseSimulationOptions& o) {
  mpcal::NoiseGenerator gen(o);
  mpcal::Recording rec;
  rec.source = "<simulated>";
  rec.time_s.reserve(gen.rows());
  rec.accel.reserve(gen.rows());
  rec.gyro_radps.reserve(gen.rows());
  double t = 0.0;
  Eigen::Vector3d a, g;
  while (gen.Next(&t, &a, &g)) {
    rec.time_s.push_back(t);
    rec.accel.push_back(a);
    rec.gyro_radps.push_back(g);
  }
  mpcal::NoiseSegment all;
  all.end = rec.size();
  return mpcal::AnalyseNoise(std::move(rec), all, 1.0, mpcal::NoiseOptions{});
}

void Score(const mpcal::AxisNoise& a, const mpcal::AxisNoiseTruth& truth, Tally& t) {
  using mpcal::NoiseTerm;
  ++t.axes;
  const mpcal::TermEstimate& n = a.term(NoiseTerm::kWhiteNoise);
  const double n_err = n.value ? std::abs(*n.value / truth.white_noise - 1.0) : 1.0;
  t.worst_n = std::max(t.worst_n, n_err);
  const mpcal::TermEstimate& k = a.term(NoiseTerm::kRandomWalk);
  if (k.value) {
    ++t.k_measured;
    const bool inside = k.lo <= truth.random_walk && truth.random_walk <= k.hi;
    t.k_inside += inside;
    t.k_high += truth.random_walk < k.lo;
  } else {
    ++t.k_not;
    t.k_bound_ok += k.upper_bound >= truth.random_walk;
  }
  const mpcal::TermEstimate& b = a.term(NoiseTerm::kBiasInstability);
  if (b.value && truth.bias_instability > 0.0) {
    ++t.b_measured;
    const double r = *b.value / truth.bias_instability;
    t.b_ok += (b.lo <= truth.bias_instability && truth.bias_instability <= b.hi) ||
              std::abs(r - 1.0) <= 0.25;
  }
}

}  // namespace

int main(int argc, char** argv) {
  const int seeds = argc > 1 ? std::atoi(argv[1]) : 10;
  const std::string preset = argc > 2 ? argv[2] : "consumer";
  const std::vector<Case> cases = {
      {2, 50}, {2, 100}, {3, 400}, {4, 50}, {4, 200}, {6, 100}, {8, 50}, {8, 100}};
  Tally all;
  fmt::print("{:<14} {:>9} {:>16} {:>10}\n", "record", "N worst", "K inside", "B ok");
  for (const Case& c : cases) {
    Tally tc;
    for (int seed = 1; seed <= seeds; ++seed) {
      mpcal::NoiseSimulationOptions o = *mpcal::NoisePreset(preset);
      o.duration_s = c.hours * 3600.0;
      o.rate_hz = c.rate_hz;
      o.seed = static_cast<std::uint64_t>(seed);
      const mpcal::NoiseResult r = Analyse(o);
      for (int axis = 0; axis < 3; ++axis) {
        Score(r.accel_mps2.axes[axis], o.accel_mps2[axis], tc);
        Score(r.gyro_radps->axes[axis], o.gyro_radps[axis], tc);
      }
    }
    fmt::print("{:<14} {:>8.2f}% {:>9}/{:<3} {:>3} {:>6}/{:<3}\n",
               fmt::format("{:g} h {:g} Hz", c.hours, c.rate_hz),
               100.0 * tc.worst_n,
               tc.k_inside,
               tc.k_measured,
               tc.k_high,
               tc.b_ok,
               tc.b_measured);
    all.worst_n = std::max(all.worst_n, tc.worst_n);
    for (auto [dst, src] : {std::pair{&all.axes, tc.axes},
                            std::pair{&all.k_measured, tc.k_measured},
                            std::pair{&all.k_inside, tc.k_inside},
                            std::pair{&all.k_high, tc.k_high},
                            std::pair{&all.k_bound_ok, tc.k_bound_ok},
                            std::pair{&all.k_not, tc.k_not},
                            std::pair{&all.b_measured, tc.b_measured},
                            std::pair{&all.b_ok, tc.b_ok}}) {
      *dst += src;
    }
  }
  const double cover =
      all.k_measured > 0 ? static_cast<double>(all.k_inside) / all.k_measured : 0.0;
  fmt::print(
      "N: worst error {:.2f} % over {} axes (bar: 3 %)\n", 100.0 * all.worst_n, all.axes);
  fmt::print(
      "K: measured on {} axes, truth inside the interval on {} ({:.1f} %, bar 90 %; "
      "{} below it, {} above); not measured on {}, bound above the truth on {}\n",
      all.k_measured,
      all.k_inside,
      100.0 * cover,
      all.k_high,
      all.k_measured - all.k_inside - all.k_high,
      all.k_not,
      all.k_bound_ok);
  fmt::print("B: measured on {} axes, within its interval or 25 % on {}\n",
             all.b_measured,
             all.b_ok);
  // Intervals and bounds are 95 % ones: a few misses are expected, so each
  // bar is a rate (90 %), not all.
  const auto rate = [](int ok, int n) {
    return n > 0 ? static_cast<double>(ok) / n : 1.0;
  };
  const bool ok = all.worst_n <= 0.03 && all.k_measured > 0 && cover >= 0.9 &&
                  rate(all.k_bound_ok, all.k_not) >= 0.9 &&
                  rate(all.b_ok, all.b_measured) >= 0.9;
  fmt::print("{}\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
