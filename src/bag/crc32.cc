// CRC-32 (ISO-HDLC: reflected polynomial 0x04C11DB7, as zlib's crc32), which
// MCAP uses for its chunks, data and summary sections.
//
// An MCAP chunk's CRC is computed over every unpacked byte, so it runs as
// fast as the bytes can be unpacked or it sets the reading time: zlib's
// crc32 (tables, a few bytes a step) is several times slower than unpacking
// an LZ4 chunk. Intel's ISA-L computes the same CRC (crc32_gzip_refl: gzip's,
// which is zlib's) by carry-less multiplication where the processor has it
// and by tables where not; tests/bag/crc32_test.cc holds it to zlib's at
// every length and alignment.
#include <isa-l/crc.h>

#include <cstdint>
#include <string_view>

#include "bag/mcap_records.h"

namespace mpcal::bag::mcap {

std::uint32_t Crc32(std::string_view data) {
  return crc32_gzip_refl(
      0, reinterpret_cast<const unsigned char*>(data.data()), data.size());
}

}  // namespace mpcal::bag::mcap
