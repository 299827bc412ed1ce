// The words of `mpcal record` (explain_record.h): the guide returns facts
// (directions by index, figures, events); here they become lines and the
// live screen.
#include "explain_record.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "colour.h"
#include "mpcal/coverage.h"

namespace mpcal::cli {
namespace {

constexpr const char* kAxisNames[] = {"x", "y", "z"};

// A bar of `width` cells, `fraction` of them full.
std::string Bar(double fraction, int width) {
  const int full = static_cast<int>(std::lround(std::clamp(fraction, 0.0, 1.0) * width));
  std::string bar;
  for (int i = 0; i < width; ++i) bar += i < full ? "#" : ".";
  return bar;
}

// The cells of the map for one kind of direction, with their marks.
std::vector<std::string> MapCells(const RecordScreen& s,
                                  CanonicalDirection::Kind kind,
                                  std::FILE* stream) {
  const auto& cube = CanonicalDirections();
  std::vector<std::string> cells;
  for (std::size_t k = 0; k < cube.size(); ++k) {
    if (cube[k].kind != kind) continue;
    const int idx = static_cast<int>(k);
    const bool held = k < s.held.size() && s.held[k];
    const bool next = idx == s.next_target;
    const bool now = s.gravity.known && s.gravity.nearest == idx;
    const std::string name = cube[k].down.substr(0, cube[k].down.find(' '));
    std::string cell = fmt::format(
        "{}{}{:<9}", held ? "[x]" : (next ? "[>]" : "[ ]"), now ? "*" : " ", name);
    if (held) cell = Paint(stream, cell, Tint::kGood);
    if (next) cell = Paint(stream, cell, Tint::kLookAt);
    cells.push_back(cell);
  }
  return cells;
}

// The map's lines: a label, then at most six cells a line.
void MapLines(const std::string& label,
              const std::vector<std::string>& cells,
              std::vector<std::string>* lines) {
  for (std::size_t b = 0; b < cells.size(); b += 6) {
    std::string l = fmt::format("{:<8}", b == 0 ? label : "");
    for (std::size_t i = b; i < std::min(cells.size(), b + 6); ++i) l += cells[i];
    lines->push_back(l);
  }
}

}  // namespace

std::string DownName(int direction) {
  const auto& cube = CanonicalDirections();
  if (direction < 0 || static_cast<std::size_t>(direction) >= cube.size()) return "?";
  return cube[static_cast<std::size_t>(direction)].down;
}

std::string WordBound(const GuideBound& bound) {
  if (!bound.determined) return "the positions do not determine every parameter yet";
  const auto i = static_cast<std::size_t>(bound.worst);
  return fmt::format("weakest: {} at {:.2f}x its target (1 sigma {:.3g}, target {:.3g})",
                     kParameterNames[i],
                     bound.worst_ratio,
                     bound.std[i],
                     bound.target[static_cast<std::size_t>(GroupOf(bound.worst))]);
}

std::string WordEvent(const GuideEvent& e) {
  switch (e.kind) {
    case GuideEventKind::kCaptured:
      return fmt::format("captured {}: {} down ({:.0f} deg off) at {:.1f} s",
                         e.positions,
                         DownName(e.direction),
                         e.off_deg,
                         e.time_s);
    case GuideEventKind::kNextTarget:
      return fmt::format("next: {} down; {}", DownName(e.target), WordBound(e.bound));
    case GuideEventKind::kTurnNeeded:
      return fmt::format(
          "turn needed: no turn about the {} axis yet (turn by about 90 deg about it "
          "between two positions)",
          kAxisNames[e.axis]);
    case GuideEventKind::kDone:
      return fmt::format("done: every parameter within its target ({} positions; {})",
                         e.positions,
                         WordBound(e.bound));
  }
  return "";
}

std::string WordInstruction(const RecordScreen& s) {
  if (s.done) return "done: every parameter within its target";
  if (!s.meter.known) return "waiting for the sensor's first second of rows";
  const std::string target =
      s.next_target >= 0 ? fmt::format("the {} points down", DownName(s.next_target))
                         : "a new orientation";
  if (s.meter.still && s.meter.progress >= 1.0) {
    return fmt::format("captured: now turn so that {}, then hold still", target);
  }
  if (s.meter.still) {
    return fmt::format("hold still ... {:.0f} %", 100.0 * s.meter.progress);
  }
  return fmt::format("turn so that {}, then hold still", target);
}

std::string DrawScreen(const RecordScreen& s, std::FILE* stream) {
  std::string out;
  auto line = [&out](const std::string& text) { out += text + "\x1b[K\n"; };
  line(fmt::format("mpcal record  {} -> {}   {} rows, {:.1f} s   (q or Ctrl-C stops)",
                   s.source,
                   s.output,
                   s.rows,
                   s.span_s));
  line("");
  if (s.gravity.known) {
    line(
        fmt::format("now:   {} down ({:.0f} deg off)   gravity ({:+.2f} {:+.2f} {:+.2f})",
                    DownName(s.gravity.nearest),
                    s.gravity.off_deg,
                    s.gravity.direction.x(),
                    s.gravity.direction.y(),
                    s.gravity.direction.z()));
  } else {
    line("now:   (no rows yet)");
  }
  line(fmt::format("still: [{}] {:3.0f} %  held {:.1f} s  motion {:.4f} / {:.4f} m/s2",
                   Bar(s.meter.progress, 20),
                   100.0 * s.meter.progress,
                   s.meter.held_s,
                   s.meter.statistic_mps2,
                   s.meter.threshold_mps2));
  line(fmt::format("positions captured: {}   {}", s.positions, WordBound(s.bound)));
  if (s.turns.gyro) {
    line(
        fmt::format("turns: {}  about x {:.0f} deg, y {:.0f} deg, z {:.0f} deg{}",
                    s.turns.turns,
                    s.turns.about_deg[0],
                    s.turns.about_deg[1],
                    s.turns.about_deg[2],
                    s.turns.all_excited() ? "" : "  (every axis needs a turn about it)"));
  }
  line("");
  std::vector<std::string> map;
  MapLines("faces", MapCells(s, CanonicalDirection::Kind::kFace, stream), &map);
  MapLines("edges", MapCells(s, CanonicalDirection::Kind::kEdge, stream), &map);
  MapLines("corners", MapCells(s, CanonicalDirection::Kind::kCorner, stream), &map);
  for (const std::string& l : map) line(l);
  line("        [x] held  [>] next  * now (what points down)");
  line("");
  line(">> " + WordInstruction(s));
  line(s.last_event);
  return out;
}

}  // namespace mpcal::cli
