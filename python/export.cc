// mpcal.export and mpcal.import_calibration on the library's registry of
// other tools' formats (mpcal/export.h): the text `mpcal export` writes, and
// the calibration `mpcal import` reads, with what the file could not carry
// as facts (mpcal/__init__.py words them).
#include "export.h"

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <pybind11/stl.h>

#include "arrays.h"
#include "errors.h"
#include "mpcal/atomic_file.h"
#include "mpcal/calibration_file.h"
#include "mpcal/error.h"
#include "mpcal/export.h"
#include "mpcal/noise_file.h"
#include "mpcal/text_input.h"

namespace mpcal::python {
namespace {

std::string NoteKind(ExportNoteKind kind) {
  switch (kind) {
    case ExportNoteKind::kNotMeasured:
      return "not_measured";
    case ExportNoteKind::kUpperBound:
      return "upper_bound";
    case ExportNoteKind::kTermDropped:
      return "term_dropped";
    case ExportNoteKind::kCommentOnly:
      return "comment_only";
    case ExportNoteKind::kFrameRotated:
      return "frame_rotated";
    case ExportNoteKind::kApproximated:
      return "approximated";
  }
  return "not_measured";
}

py::list Notes(const std::vector<ExportNote>& notes) {
  py::list out;
  for (const ExportNote& n : notes) {
    py::dict d;
    d["kind"] = NoteKind(n.kind);
    d["quantity"] = n.quantity;
    d["magnitude"] = n.magnitude;
    d["unit"] = n.unit;
    d["record_needed_s"] =
        n.record_needed_s ? py::object(py::float_(*n.record_needed_s)) : py::none();
    out.append(d);
  }
  return out;
}

const ExportFormat& FormatNamed(const std::string& name, bool writing) {
  const ExportFormat* format = FindExportFormat(name);
  if (format == nullptr ||
      (writing ? format->write == nullptr : format->read == nullptr)) {
    std::vector<std::string> names;
    for (const ExportFormat& f : ExportFormats()) {
      if ((writing ? f.write != nullptr : f.read != nullptr)) names.emplace_back(f.name);
    }
    throw Error(ErrorKind::kOption,
                fmt::format("format='{}' is not a format mpcal {}: give one of '{}'",
                            name,
                            writing ? "writes" : "reads",
                            fmt::join(names, "', '")));
  }
  return *format;
}

// The file of `format` from a calibration (a Calibration, or a file read
// here) and a noise analysis (its mpcal.noise/1 JSON, or a file read here),
// each named in the file's comments by `*_path`; written to `output` whole
// or not at all when it is not empty. Returns (text, notes).
py::tuple Export(const std::string& format_name,
                 const Calibration* calibration,
                 const std::string& calibration_path,
                 bool read_calibration,
                 const std::optional<std::string>& noise_json,
                 const std::string& noise_path,
                 bool read_noise,
                 const std::string& rostopic,
                 std::optional<double> rate_hz,
                 const std::string& output) {
  const ExportFormat& format = FormatNamed(format_name, true);
  if (!output.empty()) {
    CheckOutput(output,
                {read_calibration ? calibration_path : std::string(),
                 read_noise ? noise_path : std::string()});
  }
  ExportOptions options;
  options.rostopic = rostopic;
  options.rate_hz = rate_hz;
  ExportedFile file;
  {
    const py::gil_scoped_release unlocked;
    std::optional<Calibration> loaded;
    std::optional<NoiseFile> noise;
    ExportSources sources;
    sources.calibration = calibration;
    sources.calibration_path = calibration_path;
    sources.noise_path = noise_path;
    if (read_calibration) {
      // As `mpcal export` reads it.
      loaded = CalibrationFromJson(
          ReadTextInput(calibration_path, kMaxResultFileBytes, "mpcal file"),
          calibration_path);
      sources.calibration = &*loaded;
    }
    if (read_noise) {
      noise = ParseNoiseJson(ReadTextInput(noise_path, kMaxResultFileBytes, "mpcal file"),
                             fmt::format("noise file '{}'", noise_path));
    } else if (noise_json) {
      noise = ParseNoiseJson(*noise_json, fmt::format("noise '{}'", noise_path));
    }
    if (noise) sources.noise = &*noise;
    file = mpcal::Export(format, sources, options);
    if (!output.empty()) WriteFileAtomically(output, file.text);
  }
  return py::make_tuple(py::str(file.text), Notes(file.notes));
}

// Another tool's calibration, as `mpcal import` reads it. Returns
// (calibration, notes).
py::tuple Import(const std::string& format_name,
                 const std::vector<std::string>& paths,
                 const std::string& units,
                 const std::string& gyro_units,
                 double gravity_mps2,
                 const std::string& provenance) {
  const ExportFormat& format = FormatNamed(format_name, false);
  ImportOptions options;
  options.accel_units = AccelUnitsArgument(units, "units");
  options.gyro_units = GyroUnitsArgument(gyro_units, "gyro_units");
  options.gravity_mps2 = gravity_mps2;
  ImportedCalibration imported;
  {
    const py::gil_scoped_release unlocked;
    std::vector<ImportFile> files;
    files.reserve(paths.size());
    for (const std::string& path : paths) {
      files.push_back(
          ImportFile{path,
                     ReadTextInput(path,
                                   kMaxCalibrationFileBytes,
                                   fmt::format("calibration file of {}", format.file))});
    }
    imported = mpcal::Import(format, files, options);
  }
  imported.calibration.provenance =
      Provenance{MPCAL_VERSION, fmt::format("{}", fmt::join(paths, " ")), provenance};
  return py::make_tuple(py::cast(std::move(imported.calibration)), Notes(imported.notes));
}

std::string NeedName(ExportNeed need) {
  switch (need) {
    case ExportNeed::kUnused:
      return "unused";
    case ExportNeed::kOptional:
      return "optional";
    case ExportNeed::kRequired:
      return "required";
  }
  return "unused";
}

py::list Formats() {
  py::list out;
  for (const ExportFormat& f : ExportFormats()) {
    py::dict d;
    d["name"] = std::string(f.name);
    d["file"] = std::string(f.file);
    d["calibration"] = NeedName(f.calibration);
    d["noise"] = NeedName(f.noise);
    d["needs_gyroscope"] = f.needs_gyroscope;
    d["writes"] = f.write != nullptr;
    d["reads"] = f.read != nullptr;
    out.append(d);
  }
  return out;
}

}  // namespace

void AddExport(py::module_& m) {
  m.def("_export", &Export);
  m.def("_import", &Import);
  m.def("_formats", &Formats);
}

}  // namespace mpcal::python
