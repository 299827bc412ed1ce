// `mpcal import FORMAT FILE... -o CALIB.json`: another tool's calibration
// read into an mpcal calibration file (no 1σ), so that apply, repeat and
// report take it.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "calibration_table.h"
#include "cli_options.h"
#include "command.h"
#include "explain_export.h"
#include "gyro_table.h"
#include "mpcal/atomic_file.h"
#include "mpcal/calibration_file.h"
#include "mpcal/error.h"
#include "mpcal/export.h"
#include "mpcal/text_input.h"

namespace mpcal::cli {
namespace {

struct ImportFlags {
  std::string format;
  std::vector<std::string> files;
  std::string output;
  ImportOptions options;
  GravityFlags gravity;
};

void RunImport(const ImportFlags& f) {
  const ExportFormat* format = FindExportFormat(f.format);
  if (format == nullptr) throw Error(ErrorKind::kOption, "unknown format " + f.format);
  CheckOutput(f.output, f.files);
  std::vector<ImportFile> files;
  files.reserve(f.files.size());
  for (const std::string& path : f.files) {
    files.push_back(
        ImportFile{path,
                   ReadTextInput(path,
                                 kMaxCalibrationFileBytes,
                                 fmt::format("calibration file of {}", format->file))});
  }
  ImportOptions options = f.options;
  options.gravity_mps2 = f.gravity.Resolve();
  ImportedCalibration imported = Import(*format, files, options);
  imported.calibration.provenance =
      Provenance{MPCAL_VERSION,
                 fmt::format("{}", fmt::join(f.files, " ")),
                 fmt::format("import {} --units {} --gyro-units {} --gravity {}",
                             format->name,
                             ToString(options.accel_units),
                             ToString(options.gyro_units),
                             options.gravity_mps2)};
  WriteCalibrationFile(f.output, imported.calibration);
  std::vector<std::string> warnings;
  warnings.reserve(imported.notes.size());
  for (const ExportNote& note : imported.notes) {
    warnings.push_back(DescribeExportNote(note, f.files.front()));
  }
  PrintWarnings(warnings);
  if (f.output == "-") return;
  // The calibration as mpcal reads it, in mpcal's frame and units.
  fmt::print("{}", FormatParameterTable(imported.calibration));
  if (imported.calibration.gyroscope) {
    fmt::print("\n{}",
               FormatGyroTable(*imported.calibration.gyroscope, nullptr, "", false));
  }
  fmt::print(
      "wrote {} (from {}; no 1σ: the file does not give one)\n", f.output, format->file);
}

}  // namespace

void AddImportCommand(CLI::App& root) {
  auto f = std::make_shared<ImportFlags>();
  CLI::App* cmd = root.add_subcommand(
      "import",
      "Read another tool's calibration (imu_tk, Kalibr, OpenVINS, ...) into an mpcal "
      "calibration file without 1σ, for apply, repeat and report.");
  std::vector<std::pair<std::string, std::string>> names;
  for (const std::string& name : ExportFormatNames(false)) names.emplace_back(name, name);
  cmd->add_option("FORMAT", f->format, "The tool's file to read (listed below)")
      ->transform(OneOf(names))
      ->required();
  cmd->add_option("FILES", f->files, "The tool's file(s), in the order listed below")
      ->check(InputPath)
      ->required();
  cmd->add_option("-o,--output",
                  f->output,
                  "The calibration file to write (mpcal.imu/1 or mpcal.accelerometer/1; "
                  "'-': standard output)")
      ->check(OutputPath)
      ->required();
  const std::vector<std::pair<std::string, AccelUnits>> units{
      {"mps2", AccelUnits::kMps2},
      {"g", AccelUnits::kG},
      {"counts", AccelUnits::kCounts}};
  cmd->add_option(
         "--units",
         f->options.accel_units,
         "Units of the accelerometer readings the tool's parameters apply to (counts: "
         "the nominal scale is the geometric mean of the tool's scales)")
      ->transform(OneOf(units))
      ->capture_default_str()
      ->group("Units");
  const std::vector<std::pair<std::string, GyroUnits>> gyro_units{
      {"rads", GyroUnits::kRadps},
      {"dps", GyroUnits::kDps},
      {"counts", GyroUnits::kCounts}};
  cmd->add_option("--gyro-units",
                  f->options.gyro_units,
                  "Units of the gyroscope readings the tool's parameters apply to")
      ->transform(OneOf(gyro_units))
      ->capture_default_str()
      ->group("Units");
  AddGravityOptions(*cmd, f->gravity);
  cmd->footer("Formats:\n" + FormatList(false) +
              "The calibration file has no 1σ (the tools' files give none): every table "
              "says so.");
  cmd->callback([f] { RunImport(*f); });
}

}  // namespace mpcal::cli
