// Reads a calibration file and corrects readings one at a time, as an
// embedded logger or a navigation filter would.
//
//   build/examples/example_correct_readings calib.json
#include <iostream>

#include "mpcal/calibration_file.h"
#include "mpcal/error.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: example_correct_readings CALIB.json\n";
    return 2;
  }
  try {
    const mpcal::Calibration calibration = mpcal::ReadCalibrationFile(argv[1]);
    // A sensor lying flat, read in the units the calibration was made for
    // (calibration.input_units): 1 g on z, nothing on x and y.
    const Eigen::Vector3d reading(
        0.0, 0.0, calibration.gravity_mps2 / calibration.mps2_per_unit);
    const Eigen::Vector3d a_mps2 = calibration.Correct(reading);
    std::cout << "corrected specific force (m/s2): " << a_mps2.transpose()
              << ", |a| = " << a_mps2.norm() << "\n";
  } catch (const mpcal::Error& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
