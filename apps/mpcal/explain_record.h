// The words of `mpcal record`: one line per guide event (for a pipe), and
// the live screen (for a terminal) from the guide's facts.
#pragma once

#include <cstdio>
#include <string>

#include "mpcal/record_guide.h"

namespace mpcal::cli {

/// What the live screen shows, as the guide and the loop know it.
struct RecordScreen {
  std::string source;
  std::string output;
  std::size_t rows = 0;
  double span_s = 0.0;
  GravityNow gravity;
  StillMeter meter;
  int positions = 0;
  std::vector<bool> held;
  int next_target = -1;
  GuideBound bound;
  GuideTurns turns;
  bool done = false;
  /// The last event's line ("captured 5: ..."), shown under the instruction.
  std::string last_event;
};

/// What points down for a cube direction, e.g. "-x+y edge".
std::string DownName(int direction);

/// One line for an event, e.g. "captured 5: -z face down (2 deg off)",
/// "next: -x+y edge down", "turn needed: about the x axis",
/// "done: every parameter within its target (12 positions)".
std::string WordEvent(const GuideEvent& event);

/// The plain instruction for now, e.g. "turn so that the -x+y edge points
/// down, then hold still", "hold ... 1.2 s more", "captured: now turn ...".
std::string WordInstruction(const RecordScreen& screen);

/// The whole screen, lines ending with "\x1b[K\n" (clear to the end of the
/// line), to be written after "\x1b[H" (cursor home). `stream` says whether
/// colour is allowed.
std::string DrawScreen(const RecordScreen& screen, std::FILE* stream);

/// The bound's worst parameter against its target, e.g. "worst:
/// scale_factor_error_y at 2.3x its target 1.2e-4".
std::string WordBound(const GuideBound& bound);

}  // namespace mpcal::cli
