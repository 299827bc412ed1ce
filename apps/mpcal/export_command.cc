// `mpcal export FORMAT FILE... -o OUT`: the calibration and the noise written
// in the next tool's own file (the registry in mpcal/export.h), and a
// warning for each thing the file could not carry.
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
#include "mpcal/atomic_file.h"
#include "mpcal/calibration_file.h"
#include "mpcal/error.h"
#include "mpcal/export.h"
#include "mpcal/noise_file.h"
#include "mpcal/text_input.h"

namespace mpcal::cli {
namespace {

struct ExportFlags {
  std::string format;
  std::vector<std::string> files;
  std::string output;
  ExportOptions options;
  bool strict = false;
};

// The mpcal files given, each taken by its "format" tag: a calibration or a
// noise analysis, at most one of each.
struct Loaded {
  std::optional<Calibration> calibration;
  std::optional<NoiseFile> noise;
  ExportSources sources;
};

void LoadOne(const std::string& path, Loaded* loaded) {
  const std::string text = ReadTextInput(path, kMaxResultFileBytes, "mpcal file");
  const std::string tag = JsonFormatTag(text);
  const bool noise = tag.starts_with("mpcal.noise/");
  const bool calibration =
      tag.starts_with("mpcal.accelerometer/") || tag.starts_with("mpcal.imu/");
  if (!noise && !calibration) {
    throw Error(
        ErrorKind::kFormat,
        fmt::format("'{}' is {}; export takes a calibration file (mpcal.imu/1, "
                    "mpcal.accelerometer/1) and a noise file (mpcal.noise/1)",
                    path,
                    tag.empty() ? std::string("not an mpcal JSON file")
                                : fmt::format("an mpcal file of format '{}'", tag)));
  }
  if ((noise && loaded->noise) || (calibration && loaded->calibration)) {
    throw Error(
        ErrorKind::kInput,
        fmt::format("'{}' and '{}' are both {} files; give one calibration and at "
                    "most one noise file",
                    noise ? loaded->sources.noise_path : loaded->sources.calibration_path,
                    path,
                    noise ? "noise" : "calibration"));
  }
  if (noise) {
    loaded->noise = ParseNoiseJson(text, fmt::format("noise file '{}'", path));
    loaded->sources.noise_path = path;
  } else {
    loaded->calibration = CalibrationFromJson(text, path);
    loaded->sources.calibration_path = path;
  }
}

void RunExport(const ExportFlags& f) {
  const ExportFormat* format = FindExportFormat(f.format);
  if (format == nullptr) throw Error(ErrorKind::kOption, "unknown format " + f.format);
  CheckOutput(f.output, f.files);
  if (const std::string why = ValidateInflation(f.options.inflate); !why.empty())
    throw Error(ErrorKind::kOption, "--inflate: " + why);
  Loaded loaded;
  for (const std::string& path : f.files) LoadOne(path, &loaded);
  if (loaded.calibration) loaded.sources.calibration = &*loaded.calibration;
  if (loaded.noise) loaded.sources.noise = &*loaded.noise;
  if ((f.options.inflate != 1.0 || f.strict) && !loaded.noise) {
    throw Error(ErrorKind::kOption,
                fmt::format("{} applies to the noise values, and no noise file "
                            "(mpcal.noise/1) was given; give one, or leave it out",
                            f.strict ? "--strict" : "--inflate"));
  }
  const ExportedFile out = Export(*format, loaded.sources, f.options);
  if (f.strict) {
    // A noise value the record did not show is an error, and no file written.
    std::vector<std::string> unmeasured;
    for (const ExportNote& note : out.notes) {
      if (note.kind == ExportNoteKind::kUpperBound || note.record_could_show)
        unmeasured.push_back(note.quantity);
    }
    if (!unmeasured.empty()) {
      throw Error(ErrorKind::kInput,
                  fmt::format("{}: --strict: {} not measured in '{}' (the file would "
                              "hold {}); record longer, or leave out --strict to write "
                              "them, marked",
                              f.output,
                              fmt::join(unmeasured, ", "),
                              loaded.sources.noise_path,
                              unmeasured.size() == 1 ? "an upper bound or a placeholder"
                                                     : "upper bounds or placeholders"));
    }
  }
  WriteFileAtomically(f.output, out.text);
  std::vector<std::string> warnings;
  warnings.reserve(out.notes.size());
  for (const ExportNote& note : out.notes) {
    warnings.push_back(DescribeExportNote(note, f.output));
  }
  PrintWarnings(warnings);
  if (f.output != "-") fmt::print("wrote {} ({})\n", f.output, format->file);
}

}  // namespace

void AddExportCommand(CLI::App& root) {
  auto f = std::make_shared<ExportFlags>();
  CLI::App* cmd = root.add_subcommand(
      "export",
      "Write the calibration and the noise in the next tool's own file (Kalibr, "
      "OpenVINS, imu_tk, ...), saying what the file cannot carry.");
  std::vector<std::pair<std::string, std::string>> names;
  for (const std::string& name : ExportFormatNames(true)) names.emplace_back(name, name);
  cmd->add_option("FORMAT", f->format, "The tool's file to write (listed below)")
      ->transform(OneOf(names))
      ->required();
  cmd->add_option(
         "FILES",
         f->files,
         "The calibration file (mpcal.imu/1 or mpcal.accelerometer/1) and/or the "
         "noise file (mpcal.noise/1), in any order")
      ->check(InputPath)
      ->expected(1, 2)
      ->required();
  cmd->add_option("-o,--output",
                  f->output,
                  "The file to write ('-': standard output); written whole or not at all")
      ->check(OutputPath)
      ->required();
  cmd->add_option(
         "--rostopic", f->options.rostopic, "The IMU's topic, where the file names one")
      ->capture_default_str()
      ->group("Output");
  cmd->add_option(
         "--rate",
         f->options.rate_hz,
         "The IMU's sample rate (Hz) where the file wants one (default: the noise "
         "file's)")
      ->check(PositiveNumber)
      ->group("Output");
  cmd->add_option("--inflate",
                  f->options.inflate,
                  "Multiply the noise values by this factor (at least 1): the file says "
                  "so and gives the measured values beside them")
      ->capture_default_str()
      ->group("Output");
  cmd->add_flag("--strict",
                f->strict,
                "A noise value the record did not measure (an upper bound, or a value "
                "derived from one) is an error (exit 1, no file) instead of written, "
                "marked")
      ->group("Output");
  cmd->footer("Formats:\n" + FormatList(true) +
              "Example:\n"
              "  mpcal noise still.csv --json noise.json\n"
              "  mpcal export kalibr noise.json -o imu.yaml\n"
              "A value the file wants and mpcal did not measure, and a term of the "
              "calibration the file cannot hold, each get a warning line.");
  cmd->callback([f] { RunExport(*f); });
}

}  // namespace mpcal::cli
