// libFuzzer target for the readers of other tools' calibration files
// (mpcal import): imu_tk's .calib, Kalibr's and OpenVINS's IMU YAML, PX4's and
// ArduPilot's parameter files.
//
// The input is the file's text, given to every format that reads. Any
// outcome but a calibration or mpcal::Error is a finding: another
// exception (yaml-cpp's own included), a sanitizer report, a timeout. A
// calibration read must be one the calibration file's reader accepts
// (Import checks it through the file's text) and must correct a reading to
// finite numbers.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "memory_file.h"
#include "mpcal/error.h"
#include "mpcal/export.h"

using mpcal::fuzz::Check;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (const mpcal::ExportFormat& format : mpcal::ExportFormats()) {
    if (format.read == nullptr) continue;
    std::vector<mpcal::ImportFile> files(static_cast<std::size_t>(format.max_files),
                                         mpcal::ImportFile{"fuzz", text});
    mpcal::ImportOptions options;
    options.accel_units = mpcal::AccelUnits::kCounts;
    options.gyro_units = mpcal::GyroUnits::kCounts;
    try {
      const mpcal::ImportedCalibration c = mpcal::Import(format, files, options);
      Check(c.calibration.Correct(Eigen::Vector3d(1.0, 2.0, 3.0)).allFinite(),
            "a finite correction");
      Check(!c.calibration.std.has_value(), "no 1 sigma");
    } catch (const mpcal::Error&) {
      // The documented way to reject an input.
    }
  }
  return 0;
}
