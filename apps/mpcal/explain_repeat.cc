#include "explain_repeat.h"

#include <fmt/format.h>

#include "explain.h"

namespace mpcal::cli {

std::string ExplainRepeatRefusal(const Error& error) {
  const Advice& advice = error.advice();
  if (advice.stage != Stage::kCalibrate || advice.settings.empty()) return Explain(error);
  std::string flags;
  for (std::size_t i = 0; i < advice.settings.size(); ++i) {
    const Option option = advice.settings[i].option;
    if (i > 0) {
      // The site's latitude and height go together: one alternative.
      const bool site =
          option == Option::kHeight && advice.settings[i - 1].option == Option::kLatitude;
      flags += site ? "/" : " or ";
    }
    flags += FlagName(option);
  }
  return fmt::format(
      "{} (calibrate every session with the same {})", error.what(), flags);
}

}  // namespace mpcal::cli
