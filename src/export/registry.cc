// The registry of formats, and the checks every export and import passes
// before a format's writer or reader runs.
#include <algorithm>
#include <string>

#include <fmt/format.h>

#include "export/filter_formats.h"
#include "export/formats.h"
#include "mpcal/advice.h"
#include "mpcal/calibration_file.h"
#include "mpcal/error.h"
#include "mpcal/export.h"

namespace mpcal {

const std::vector<ExportFormat>& ExportFormats() {
  // One line per format, in the order the help lists them.
  static const std::vector<ExportFormat> formats = {
      export_formats::Kalibr(),
      export_formats::KalibrScaleMisalignment(),
      export_formats::OpenVins(),
      export_formats::ImuTk(),
      export_formats::ImuTkAccel(),
      export_formats::ImuTkGyro(),
      export_formats::OrbSlam3(),
      export_formats::Vins(),
      export_formats::KfGins(),
      export_formats::RosImu(),
      export_formats::Px4(),
      export_formats::ArduPilot(),
  };
  return formats;
}

const ExportFormat* FindExportFormat(std::string_view name) {
  const auto& formats = ExportFormats();
  const auto it = std::find_if(formats.begin(),
                               formats.end(),
                               [&](const ExportFormat& f) { return f.name == name; });
  return it == formats.end() ? nullptr : &*it;
}

namespace {

void CheckNeed(ExportNeed need, bool given, std::string_view format, const char* what) {
  if (need == ExportNeed::kRequired && !given) {
    throw Error(ErrorKind::kInput,
                fmt::format("format '{}' needs {}, and none was given", format, what));
  }
  if (need == ExportNeed::kUnused && given) {
    throw Error(
        ErrorKind::kInput,
        fmt::format("format '{}' has no place for {}; leave it out", format, what));
  }
}

}  // namespace

ExportedFile Export(const ExportFormat& format,
                    const ExportSources& sources,
                    const ExportOptions& options) {
  if (format.write == nullptr) {
    throw Error(
        ErrorKind::kInput,
        fmt::format("format '{}' is read only (import), not written", format.name));
  }
  CheckNeed(format.calibration,
            sources.calibration != nullptr,
            format.name,
            "a calibration file (mpcal.accelerometer/1 or mpcal.imu/1)");
  CheckNeed(format.noise,
            sources.noise != nullptr,
            format.name,
            "a noise file (mpcal.noise/1)");
  if (format.needs_gyroscope && sources.calibration != nullptr &&
      !sources.calibration->gyroscope) {
    throw Error(ErrorKind::kInput,
                fmt::format("format '{}' needs the gyroscope's calibration, and '{}' has "
                            "none (an accelerometer-only calibration); calibrate the IMU "
                            "with its gyroscope columns",
                            format.name,
                            sources.calibration_path));
  }
  return format.write(sources, options);
}

ImportedCalibration Import(const ExportFormat& format,
                           const std::vector<ImportFile>& files,
                           const ImportOptions& options) {
  if (format.read == nullptr) {
    throw Error(
        ErrorKind::kInput,
        fmt::format("format '{}' is written only (export), not read", format.name));
  }
  const int n = static_cast<int>(files.size());
  if (n < format.min_files || n > format.max_files) {
    throw Error(
        ErrorKind::kInput,
        fmt::format(
            "format '{}' takes {} ({}), {} given",
            format.name,
            format.min_files == format.max_files
                ? fmt::format(
                      "{} file{}", format.min_files, format.min_files == 1 ? "" : "s")
                : fmt::format("{} to {} files", format.min_files, format.max_files),
            format.import_files,
            n));
  }
  ImportedCalibration imported = format.read(files, options);
  // What a calibration file's reader would refuse is refused here, with the
  // same words: the calibration passes through the file's text and back.
  try {
    imported.calibration =
        CalibrationFromJson(CalibrationToJson(imported.calibration), files.front().path);
  } catch (const Error& e) {
    // Parameters for raw counts read as m/s² (or the reverse) are the
    // likeliest cause: the units of the tool's raw readings.
    Advice advice;
    advice.settings = {Setting{Option::kLogUnits, "counts"}};
    throw Error(ErrorKind::kUnits,
                fmt::format("{}; are the tool's raw readings in {}?",
                            e.what(),
                            ToString(options.accel_units)),
                advice);
  }
  return imported;
}

}  // namespace mpcal
