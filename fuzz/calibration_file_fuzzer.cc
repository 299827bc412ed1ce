// libFuzzer target for the calibration-file reader (CalibrationFromJson).
//
// Any outcome but success or mpcal::Error is a finding. A file that parses
// must also survive a round trip: written back with CalibrationToJson and
// read again, it gives the same parameters (what `mpcal apply` relies on).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "mpcal/calibration_file.h"
#include "mpcal/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  mpcal::Calibration c;
  try {
    c = mpcal::CalibrationFromJson(text, "fuzz.json");
  } catch (const mpcal::Error&) {
    return 0;  // the documented way to reject an input
  }
  std::string written;
  try {
    written = mpcal::CalibrationToJson(c);
  } catch (const mpcal::Error& e) {
    std::fprintf(stderr, "a calibration that was read cannot be written: %s\n", e.what());
    std::abort();
  }
  mpcal::Calibration again;
  try {
    again = mpcal::CalibrationFromJson(written, "round-trip.json");
  } catch (const mpcal::Error& e) {
    std::fprintf(stderr, "the written calibration does not read back: %s\n", e.what());
    std::abort();
  }
  if (mpcal::ToVector(again.model) != mpcal::ToVector(c.model) ||
      again.gravity_mps2 != c.gravity_mps2 || again.mps2_per_unit != c.mps2_per_unit) {
    std::fprintf(stderr, "the round trip changed the parameters\n");
    std::abort();
  }
  if (again.gyroscope.has_value() != c.gyroscope.has_value() ||
      (c.gyroscope && (again.gyroscope->m != c.gyroscope->m ||
                       again.gyroscope->bias_radps != c.gyroscope->bias_radps ||
                       again.gyroscope->radps_per_unit != c.gyroscope->radps_per_unit))) {
    std::fprintf(stderr, "the round trip changed the gyroscope\n");
    std::abort();
  }
  return 0;
}
