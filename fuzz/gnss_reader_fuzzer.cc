// libFuzzer target for the GNSS reference reader (ParseGnss: RTKLIB .pos,
// NMEA GGA, CSV).
//
// Any outcome but success or mpcal::Error is a finding. A track that parses
// must be usable by verify: as many positions as epochs, finite times that
// strictly increase, finite east-north-up positions.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "mpcal/error.h"
#include "mpcal/gnss.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  mpcal::GnssTrack track;
  try {
    track = mpcal::ParseGnss(text, "fuzz.pos");
  } catch (const mpcal::Error&) {
    return 0;  // the documented way to reject an input
  }
  if (track.enu_m.size() != track.time_s.size()) {
    std::fprintf(stderr,
                 "invariant broken: %zu epochs but %zu positions\n",
                 track.time_s.size(),
                 track.enu_m.size());
    std::abort();
  }
  for (std::size_t i = 0; i < track.size(); ++i) {
    if (!std::isfinite(track.time_s[i]) || !track.enu_m[i].allFinite() ||
        (i > 0 && !(track.time_s[i] > track.time_s[i - 1]))) {
      std::fprintf(
          stderr, "invariant broken at epoch %zu: time %g\n", i, track.time_s[i]);
      std::abort();
    }
  }
  return 0;
}
