// The detect and calibrate rooms' findings in the words and flags a
// command-line user reads (the library's own Describe names no flag): why no
// position was found, the notes, the coverage's problems and advice, and the
// errors of a session that cannot be calibrated.
#pragma once

#include <string>
#include <vector>

#include "mpcal/calibrate.h"
#include "mpcal/coverage.h"
#include "mpcal/detect.h"

namespace mpcal::cli {

/// "no static position found in 40.0 s: ...; raise --max-still".
std::string ExplainDetection(const DetectFinding& finding);
/// "position 0.8-3.4 s dropped: ...; give the sensor's range with --range".
std::string ExplainNote(const DetectNote& note);
/// A problem is a fact: the library's sentence.
std::string ExplainProblem(const CoverageProblem& problem);
/// "or calibrate bias and scale only with --model bias-scale-6 (...)".
std::string ExplainStep(const CoverageStep& step);
/// The verdict's one line, with the steps in flags.
std::string ExplainSummary(const CoverageResult& coverage);
/// Every sentence of a detection and its coverage, for the JSON report.
DetectionWords ExplainDetectionWords(const DetectResult& detection,
                                     const CoverageResult& coverage);

/// "...; the readings look like g: add --units g".
std::string ExplainUnits(const UnitsError& error);
/// "...: no static position found ...", "...; run 'mpcal detect X' to see the
/// positions found".
std::string ExplainSession(const SessionError& error);

/// Runs `f`, rethrowing a UnitsError or SessionError as an Error whose
/// sentence is already in the command line's words.
template <typename F>
decltype(auto) WithDetectWords(F&& f) {
  try {
    return f();
  } catch (const UnitsError& e) {
    throw Error(e.kind(), ExplainUnits(e));
  } catch (const SessionError& e) {
    throw Error(e.kind(), ExplainSession(e));
  }
}

}  // namespace mpcal::cli
