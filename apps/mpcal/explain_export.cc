// The facts of `export` and `import` in words.
#include "explain_export.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "mpcal/noise.h"

namespace mpcal::cli {

namespace {

std::string WithUnit(double v, const std::string& unit) {
  return unit.empty() ? fmt::format("{:.4g}", v) : fmt::format("{:.4g} {}", v, unit);
}

const char* NeedWord(ExportNeed need) {
  switch (need) {
    case ExportNeed::kUnused:
      return "";
    case ExportNeed::kOptional:
      return "optional";
    case ExportNeed::kRequired:
      return "required";
  }
  return "";
}

}  // namespace

std::string DescribeExportNote(const ExportNote& n, const std::string& file) {
  const std::string v = WithUnit(n.magnitude, n.unit);
  switch (n.kind) {
    case ExportNoteKind::kNotMeasured:
      return fmt::format(
          "{}: {} was not measured (not in the files given); the file holds {}, "
          "labelled so on its line",
          file,
          n.quantity,
          v);
    case ExportNoteKind::kUpperBound:
      return fmt::format(
          "{}: {} was not measured; the file has its upper bound {} (labelled in a "
          "comment){}",
          file,
          n.quantity,
          v,
          n.record_needed_s ? fmt::format("; record at least {} to measure it",
                                          FormatRecordLength(*n.record_needed_s))
                            : "");
    case ExportNoteKind::kTermDropped:
      return fmt::format("{}: the format cannot hold {} (largest entry {}); dropped",
                         file,
                         n.quantity,
                         v);
    case ExportNoteKind::kCommentOnly:
      return fmt::format(
          "{}: the format has no key for {} (largest entry {}): written in the file's "
          "comments only (the tool estimates its own)",
          file,
          n.quantity,
          v);
    case ExportNoteKind::kFrameRotated:
      return fmt::format(
          "{}: {}: the format's frame is not mpcal's; output corrected by this file is "
          "rotated by {} ({:.4g} deg) from mpcal's",
          file,
          n.quantity,
          v,
          n.magnitude * 180.0 / 3.14159265358979323846);
    case ExportNoteKind::kApproximated:
      return fmt::format(
          "{}: {} held approximately; a corrected reading differs from mpcal's by up to "
          "{}",
          file,
          n.quantity,
          v);
  }
  return file + ": " + n.quantity;
}

std::vector<std::string> ExportFormatNames(bool writing) {
  std::vector<std::string> names;
  for (const ExportFormat& f : ExportFormats()) {
    if ((writing ? f.write : nullptr) != nullptr || (!writing && f.read != nullptr)) {
      names.emplace_back(f.name);
    }
  }
  return names;
}

std::string FormatList(bool writing) {
  std::string out;
  for (const ExportFormat& f : ExportFormats()) {
    if (writing && f.write == nullptr) continue;
    if (!writing && f.read == nullptr) continue;
    std::string what;
    if (writing) {
      std::vector<std::string> needs;
      if (f.calibration != ExportNeed::kUnused) {
        needs.push_back(fmt::format("calibration {}{}",
                                    NeedWord(f.calibration),
                                    f.needs_gyroscope ? ", with gyroscope" : ""));
      }
      if (f.noise != ExportNeed::kUnused) {
        needs.push_back(fmt::format("noise {}", NeedWord(f.noise)));
      }
      what = fmt::format("{}", fmt::join(needs, "; "));
    } else {
      what = std::string(f.import_files);
    }
    out += fmt::format("  {:<20} {} ({})\n", f.name, f.file, what);
  }
  return out;
}

}  // namespace mpcal::cli
