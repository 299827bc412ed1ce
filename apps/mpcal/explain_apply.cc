#include "explain_apply.h"

#include <fmt/format.h>

#include "explain.h"

namespace mpcal::cli {

std::string ExplainRestMismatch(const RestMismatch& mismatch) {
  std::string hint;
  switch (mismatch.kind) {
    case RestMismatchKind::kSensorOrUnits:
      hint =
          fmt::format("is it the calibrated sensor, and are the log's units right ({})?",
                      FlagName(Option::kLogUnits));
      break;
    case RestMismatchKind::kLooksLikeG:
    case RestMismatchKind::kLooksLikeMps2:
      hint = fmt::format("the log looks like it is in {}: use {}",
                         mismatch.kind == RestMismatchKind::kLooksLikeG ? "g" : "m/s²",
                         mismatch.advice.settings.empty()
                             ? std::string(FlagName(Option::kLogUnits))
                             : FlagWithValue(mismatch.advice.settings.front()));
      break;
  }
  return fmt::format("{}; {}", mismatch.what, hint);
}

}  // namespace mpcal::cli
