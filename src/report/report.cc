#include "mpcal/report.h"

#include <chrono>
#include <ctime>

#include <fmt/chrono.h>
#include <fmt/format.h>

#include "mpcal/atomic_file.h"
#include "report/html.h"
#include "report/sections.h"

namespace mpcal {

namespace {

std::string NowUtc() {
  const std::time_t now =
      std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  return fmt::format("{:%Y-%m-%d %H:%M:%S} UTC", fmt::gmtime(now));
}

}  // namespace

std::string RenderReport(const ReportInputs& inputs) {
  using namespace report;
  // The sections first: the header links to those that were written.
  std::string html = "<main>\n";
  if (inputs.calibration) html += CalibrationSection(*inputs.calibration);
  if (inputs.calibration) {
    html += GyroSection(*inputs.calibration, inputs.session ? &*inputs.session : nullptr);
  }
  if (inputs.session) {
    html += SessionSection(*inputs.session,
                           inputs.calibration ? &*inputs.calibration : nullptr);
  }
  if (inputs.repeatability) html += RepeatabilitySection(*inputs.repeatability);
  if (inputs.verification)
    html += VerificationSection(*inputs.verification, inputs.explain_advice);
  if (inputs.noise) html += NoiseSection(*inputs.noise);
  if (!inputs.calibration && !inputs.session && !inputs.repeatability &&
      !inputs.verification && !inputs.noise) {
    html += Paragraph("Nothing to report: no input was given.", "note");
  }
  html += "</main>\n";
  return PageBegin(inputs.title) +
         HeaderSection(
             inputs, inputs.generated_at.empty() ? NowUtc() : inputs.generated_at, html) +
         html + PageEnd();
}

void WriteReport(const std::string& path, const ReportInputs& inputs) {
  WriteFileAtomically(path, RenderReport(inputs));
}

}  // namespace mpcal
