// What `mpcal calibrate` does once its flags are read: read the log,
// calibrate, print the table and the checks, write the file. `mpcal record
// --calibrate` runs the same on the session it wrote.
#pragma once

#include <string>

#include "cli_options.h"
#include "mpcal/calibrate.h"
#include "mpcal/log_reader.h"

namespace mpcal::cli {

struct CalibrateFlags {
  std::string input;
  std::string output;
  GyroLogFlags gyro_log;
  LogOptions log;
  GravityFlags gravity;
  CalibrateOptions calibrate;
  bool verbose = false;
};

/// Reads `f.input`, calibrates, prints, and writes `f.output` when given.
/// \throws mpcal::Error as the command reports it.
void RunCalibrate(CalibrateFlags& f);

}  // namespace mpcal::cli
