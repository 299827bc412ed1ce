// False-alarm rate of `mpcal repeat`: sets of three power-ups of
// one device whose bias does NOT move between them (turn-on spread zero),
// each calibrated end to end. A parameter is flagged "changed" by a test at
// 1 % significance, so if every calibration's 1σ is honest about 1 % of the
// parameter tests flag by chance. Too many flags mean overconfident 1σ; far
// too few, pessimistic ones.
//
//   mpcal_false_alarm_bench [SETS_PER_PRESET=40] [SEED=1000]
#include <array>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "mpcal/calibrate.h"
#include "mpcal/repeat.h"
#include "mpcal/simulate.h"

int main(int argc, char** argv) {
  using namespace mpcal;
  const int sets = argc > 1 ? std::atoi(argv[1]) : 40;
  const std::uint64_t seed = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 1000;
  constexpr int kTrials = 3;
  const RepeatabilityOptions options;  // 1 % significance, the default

  int total_flagged = 0, total_tests = 0;
  for (const std::string& preset : PresetNames()) {
    SimulateStaticOptions sim;
    sim.device = FindPreset(preset);
    sim.device.turn_on_bias_std_mps2.setZero();
    std::array<int, kNumModelParameters> flagged{};
    for (int set = 0; set < sets; ++set) {
      sim.seed = seed + static_cast<std::uint64_t>(set);
      std::vector<Calibration> trials;
      for (const SimulatedSession& s : SimulateTrials(sim, kTrials)) {
        trials.push_back(CalibrateRecording(s.recording, CalibrateOptions{}).calibration);
      }
      const RepeatabilityResult r = AnalyzeRepeatability(trials, options);
      for (std::size_t p = 0; p < flagged.size(); ++p) {
        flagged[p] += r.parameters[p].changed.value_or(false) ? 1 : 0;
      }
    }
    int preset_flagged = 0;
    for (int f : flagged) preset_flagged += f;
    fmt::print("{:<13} flagged per parameter: {} of {} sets each: {}\n",
               preset,
               fmt::join(flagged, " "),
               sets,
               preset_flagged);
    total_flagged += preset_flagged;
    total_tests += sets * kNumModelParameters;
  }
  // Binomial(n, 0.01): pass within 4σ of its mean.
  const double expected = options.significance * total_tests;
  const double sigma = std::sqrt(expected * (1.0 - options.significance));
  const bool pass = std::abs(total_flagged - expected) <= 4.0 * sigma;
  fmt::print(
      "false alarms: {} of {} parameter tests ({:.2f} %; {:.0f} % expected, pass "
      "within {:.0f}..{:.0f}); {}\n",
      total_flagged,
      total_tests,
      100.0 * total_flagged / total_tests,
      100.0 * options.significance,
      std::max(0.0, expected - 4.0 * sigma),
      expected + 4.0 * sigma,
      pass ? "PASS" : "FAIL");
  return pass ? 0 : 1;
}
