// Calibrates a simulated session and prints each parameter beside the truth:
// the library's main job in a dozen lines.
//
//   build/examples/example_calibrate_session
#include <iostream>

#include "mpcal/calibrate.h"
#include "mpcal/simulate.h"

int main() {
  mpcal::SimulateStaticOptions sim;
  sim.device = mpcal::FindPreset("colibri");
  const mpcal::SimulatedSession session = mpcal::SimulateStatic(sim);

  const mpcal::CalibrateResult result =
      mpcal::CalibrateRecording(session.recording, mpcal::CalibrateOptions{});
  std::cout << result.solve.BriefReport() << "\n";

  const auto estimate = mpcal::ToVector(result.calibration.model);
  const auto sigma = mpcal::ToVector(*result.calibration.std);
  const auto truth = mpcal::ToVector(session.truth.model);
  for (int i = 0; i < mpcal::kNumModelParameters; ++i) {
    std::cout << mpcal::kParameterNames[i] << ": " << estimate[i] << " ± " << sigma[i]
              << " (truth " << truth[i] << ")\n";
  }
}
