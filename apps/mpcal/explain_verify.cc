#include "explain_verify.h"

#include <fmt/format.h>

#include "explain.h"

namespace mpcal::cli {

std::string ExplainVerifyFinding(const VerifyFinding& finding) {
  switch (finding.kind) {
    case VerifyFindingKind::kClockDisagreement:
      return fmt::format("{}; if the clocks differ, pass {} motion or {}",
                         finding.what,
                         FlagName(Option::kTimeAlign),
                         FlagName(Option::kTimeOffset));
    case VerifyFindingKind::kNoStop:
    case VerifyFindingKind::kGyroscopeUnused:
      break;
  }
  const std::string advice = ExplainAdvice(finding.advice);
  return advice.empty() ? finding.what : fmt::format("{}; {}", finding.what, advice);
}

}  // namespace mpcal::cli
