#include "mpcal/check.h"

#include <algorithm>

namespace mpcal {

std::string_view ToString(Verdict verdict) {
  switch (verdict) {
    case Verdict::kGood:
      return "good";
    case Verdict::kLookAt:
      return "look at";
    case Verdict::kDoNotUse:
      return "do not use";
  }
  return "";
}

std::string_view ToString(CheckKind kind) {
  switch (kind) {
    case CheckKind::kFit:
      return "fit";
    case CheckKind::kPositions:
      return "positions";
    case CheckKind::kBiasDrift:
      return "bias drift";
    case CheckKind::kSplitHalf:
      return "split-half";
    case CheckKind::kUnits:
      return "units";
    case CheckKind::kGyroscope:
      return "gyroscope";
    case CheckKind::kCorrection:
      return "correction";
    case CheckKind::kClock:
      return "clock";
    case CheckKind::kStops:
      return "stops";
  }
  return "";
}

Verdict Worst(const std::vector<Check>& checks) {
  Verdict worst = Verdict::kGood;
  for (const Check& c : checks) worst = std::max(worst, c.verdict);
  return worst;
}

}  // namespace mpcal
