#include "explain_detect.h"

#include <fmt/format.h>

#include "explain.h"

namespace mpcal::cli {

std::string ExplainDetection(const DetectFinding& f) {
  switch (f.kind) {
    case DetectOutcome::kFound:
      return "";
    case DetectOutcome::kAllClipped:
      return fmt::format(
          "{}; keep the sensor within its range, or give the range with {} if that is "
          "not the limit",
          DescribeFacts(f),
          FlagName(Option::kSensorRange));
    case DetectOutcome::kNeverStill:
      return fmt::format(
          "{}. Hold it still for a few seconds per position; if it is this noisy at "
          "rest, raise {}",
          DescribeFacts(f),
          FlagName(Option::kDetectMaxStill));
    case DetectOutcome::kTooShort: {
      // The minimum and the settling go together; the threshold is the
      // alternative (absent when capped: already at the most a still sensor
      // moves).
      std::string together;
      std::string alternative;
      for (const Setting& s : f.advice.settings) {
        if (s.option == Option::kDetectThreshold) {
          alternative = fmt::format(", or a larger {}", FlagName(s.option));
        } else {
          // (Appended in two steps: GCC 12's -Wrestrict misfires on "" + string.)
          if (!together.empty()) together += ' ';
          together += FlagWithValue(s);
        }
      }
      return fmt::format("{}: hold each position longer, or try {}{}",
                         DescribeFacts(f),
                         together,
                         alternative);
    }
  }
  return "";
}

std::string ExplainNote(const DetectNote& note) {
  if (note.kind == DetectNoteKind::kClippedPosition) {
    return fmt::format("{}; if that is not the limit, give the sensor's range with {}",
                       DescribeFacts(note),
                       FlagName(Option::kSensorRange));
  }
  return DescribeFacts(note);
}

std::string ExplainProblem(const CoverageProblem& problem) { return Describe(problem); }

std::string ExplainStep(const CoverageStep& step) {
  switch (step.kind) {
    case CoverageStepKind::kRecordPositions:
      return Describe(step);
    case CoverageStepKind::kSixParameterModel:
      return fmt::format(
          "or calibrate bias and scale only with {} (six-position protocol: each axis "
          "up and down)",
          FlagWithValue(step.advice.settings.front()));
    case CoverageStepKind::kHoldLonger:
      return fmt::format(
          "{} still stretch{} shorter than the minimum ({}) {} dropped: hold each "
          "position longer",
          step.dropped_short,
          step.dropped_short == 1 ? "" : "es",
          FlagName(Option::kDetectMinStatic),
          step.dropped_short == 1 ? "was" : "were");
  }
  return "";
}

std::string ExplainSummary(const CoverageResult& coverage) {
  return Summary(coverage, [](const CoverageStep& step) { return ExplainStep(step); });
}

DetectionWords ExplainDetectionWords(const DetectResult& detection,
                                     const CoverageResult& coverage) {
  DetectionWords words;
  words.message = ExplainDetection(detection.finding);
  for (const auto& n : detection.notes) words.notes.push_back(ExplainNote(n));
  for (const auto& p : coverage.problems) words.problems.push_back(ExplainProblem(p));
  for (const auto& a : coverage.advice) words.advice.push_back(ExplainStep(a));
  words.summary = ExplainSummary(coverage);
  return words;
}

std::string ExplainUnits(const UnitsError& error) {
  const UnitsError::Finding& f = error.finding();
  std::string hint;
  switch (f.guess) {
    case UnitsGuess::kG:
      hint = "the readings look like g: add " + FlagWithValue(error.advice().settings[0]);
      break;
    case UnitsGuess::kMps2:
      hint = "the readings look like m/s\u00b2: use " +
             FlagWithValue(error.advice().settings[0]);
      break;
    case UnitsGuess::kCounts:
      hint = "the readings look like raw ADC counts: add " +
             FlagWithValue(error.advice().settings[0]);
      break;
    case UnitsGuess::kGravityRemoved:
      hint =
          "this is acceleration with gravity removed, which calibration cannot use: "
          "record the accelerometer with gravity (Sensor Logger: TotalAcceleration.csv "
          "on Android, AccelerometerUncalibrated.csv on iOS; phyphox: 'Acceleration "
          "with g')";
      break;
    case UnitsGuess::kUnknown:
      hint = fmt::format(
          "check {} and {}", FlagName(Option::kLogUnits), FlagName(Option::kLogColumns));
      break;
  }
  return fmt::format("{}; {}", DescribeUnitsFinding(f), hint);
}

std::string ExplainSession(const SessionError& error) {
  switch (error.problem()) {
    case SessionProblem::kNoPositions:
      return ExplainDetection(error.detection().finding);
    case SessionProblem::kTooFewPositions:
      return fmt::format("{}: {}; {} to see the positions found",
                         error.source(),
                         ExplainSummary(error.coverage()),
                         ExplainAdvice(error.advice()));
    case SessionProblem::kCountsNotSpread:
      return fmt::format(
          "{}: the {} static positions do not spread over the sphere, so the offset and "
          "scale of the raw counts cannot be found from them; record positions with each "
          "axis up and down ({})",
          error.source(),
          error.detection().intervals.size(),
          ExplainAdvice(error.advice()));
  }
  return error.what();
}

}  // namespace mpcal::cli
