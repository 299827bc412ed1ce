/// \file export.h
/// \brief The calibration and the noise handed to the next tool, and a
/// calibration taken from it: a registry of file formats, each with a writer
/// (mpcal's calibration and/or noise file → the tool's file) and optionally
/// a reader (the tool's file(s) → a calibration without 1σ).
///
/// A writer returns the file's text and the facts of what the file could not
/// carry (a value not measured, a model term the format cannot hold, a frame
/// the format sees differently), each with its magnitude; the command says
/// them. Every format lives in a file of its own in src/export/, and the
/// registry (src/export/registry.cc) is a plain list of them.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mpcal/calibration.h"
#include "mpcal/noise_file.h"
#include "mpcal/units.h"

namespace mpcal {

/// Whether a format uses a kind of mpcal file.
enum class ExportNeed {
  kUnused,    ///< the format has no place for it
  kOptional,  ///< used when given (its keys are said to be missing otherwise)
  kRequired,
};

/// What the writers are given. A pointer is null when that file was not
/// given (the registry's needs are checked before a writer is called).
struct ExportSources {
  const Calibration* calibration = nullptr;
  const NoiseFile* noise = nullptr;
  /// The files' paths as given, named in the written file's comments.
  std::string calibration_path;
  std::string noise_path;
};

/// Settings of the written file that no mpcal file holds.
struct ExportOptions {
  /// The IMU's topic (Kalibr, OpenVINS: `rostopic`).
  std::string rostopic = "/imu0";
  /// The IMU's sample rate (Hz) where the format wants one and no noise file
  /// gives it; nullopt: the noise file's rate, else the format's default,
  /// said in a note.
  std::optional<double> rate_hz;
  /// The factor the user asked the noise values to be multiplied by (≥ 1;
  /// 1: as measured). Filters are often given inflated noise to cover what
  /// their model lacks; the file then says so with the factor, and beside
  /// each value the record's own.
  double inflate = 1.0;
};

/// Why a value did not reach the file as mpcal has it.
enum class ExportNoteKind {
  /// The format wants a value mpcal did not measure (not in the files
  /// given): the file holds the value in `magnitude` (a default or
  /// placeholder) and says so on that line.
  kNotMeasured,
  /// A noise value not measured on its axis: the file holds its upper bound
  /// (`magnitude`), said so in a comment; `record_needed_s` to measure it.
  kUpperBound,
  /// A term of mpcal's model the format cannot hold, dropped: `magnitude` is
  /// its size (the largest entry, in `unit`).
  kTermDropped,
  /// The format has no key for a value mpcal has (the biases, for filters
  /// that estimate their own): written in the file's comments only;
  /// `magnitude` its largest entry.
  kCommentOnly,
  /// The format's frame is not mpcal's: the file implies a rotation of the
  /// corrected output by `magnitude` rad.
  kFrameRotated,
  /// Held only approximately: `magnitude` is the largest difference it makes
  /// to a corrected reading over the sensor's range (in `unit`).
  kApproximated,
};

/// One fact of what the file does not carry.
struct ExportNote {
  ExportNoteKind kind = ExportNoteKind::kNotMeasured;
  /// The quantity: the format's key ("accelerometer_random_walk", "A") or
  /// mpcal's term ("g_sensitivity", "non_orthogonality").
  std::string quantity;
  double magnitude = 0.0;
  /// The unit of `magnitude` ("rad", "m/s^2", "rad/s per m/s^2"); empty for
  /// a pure number.
  std::string unit;
  std::optional<double> record_needed_s;
  /// A noise value the record did not show and a longer one could (every
  /// kUpperBound, and a value derived from terms not measured): what a
  /// strict export refuses. A value no still record holds (the scale
  /// factor's instability) is not one.
  bool record_could_show = false;
};

/// A written file: its text and what it could not carry.
struct ExportedFile {
  std::string text;
  std::vector<ExportNote> notes;
};

/// What an import needs that the tool's file does not say.
struct ImportOptions {
  /// Units of the raw readings the tool's parameters apply to, and the
  /// factor that turns them into m/s² (rad/s); counts need the factor given.
  AccelUnits accel_units = AccelUnits::kMps2;
  GyroUnits gyro_units = GyroUnits::kRadps;
  std::optional<double> mps2_per_count;
  std::optional<double> radps_per_count;
  /// The gravity magnitude the calibration holds for (m/s²).
  double gravity_mps2 = kStandardGravityMps2;
};

/// One file of the tool's, read whole by the caller (bounded).
struct ImportFile {
  std::string path;
  std::string text;
};

/// A calibration read from another tool's file(s): no 1σ (Calibration::std,
/// the gyroscope's bias_std_radps and m_covariance are nullopt), provenance
/// naming the files; and what of the files mpcal's model could not hold.
struct ImportedCalibration {
  Calibration calibration;
  std::vector<ExportNote> notes;
};

using ExportWriter = ExportedFile (*)(const ExportSources&, const ExportOptions&);
using ImportReader = ImportedCalibration (*)(const std::vector<ImportFile>&,
                                             const ImportOptions&);

/// One entry of the registry.
struct ExportFormat {
  /// Its name on the command line ("kalibr", "openvins", "imu-tk").
  std::string_view name;
  /// The tool and its file, as the tool names them ("Kalibr imu.yaml").
  std::string_view file;
  ExportNeed calibration = ExportNeed::kUnused;
  ExportNeed noise = ExportNeed::kUnused;
  /// Whether the calibration must have a gyroscope.
  bool needs_gyroscope = false;
  /// nullptr: the format is import only.
  ExportWriter write = nullptr;
  /// nullptr: export only. Takes `min_files` to `max_files` files, in the
  /// order `import_files` names them.
  ImportReader read = nullptr;
  int min_files = 1;
  int max_files = 1;
  /// The files an import takes, in order ("ACCEL.calib [GYRO.calib]").
  std::string_view import_files;
};

/// Every format, in the order the help lists them.
const std::vector<ExportFormat>& ExportFormats();
/// The format of that name (case as given); nullptr when unknown.
const ExportFormat* FindExportFormat(std::string_view name);

/// Checks the sources against the format's needs, then writes.
/// \throws mpcal::Error (kInput) naming what is missing: a file the format
///   requires, a gyroscope, or a file the format has no place for.
ExportedFile Export(const ExportFormat& format,
                    const ExportSources& sources,
                    const ExportOptions& options);

/// Checks the number of files, then reads; the calibration is then checked
/// as a calibration file's would be (CalibrationToJson must accept it).
/// \throws mpcal::Error (kInput) naming the file, the key and what is wrong.
ImportedCalibration Import(const ExportFormat& format,
                           const std::vector<ImportFile>& files,
                           const ImportOptions& options);

}  // namespace mpcal
