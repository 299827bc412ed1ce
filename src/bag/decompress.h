// Private to src/bag/: the chunk compressions of ROS 1 bags and MCAP files.
// bz2, lz4 and zstd stay inside this file's implementation.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "bag/bag_io.h"

namespace mpcal::bag {

/// "" and "none" (stored), "bz2", "lz4" (the LZ4 frame format) and "zstd".
bool IsKnownCompression(std::string_view compression);

/// Unpacks `input`, which must unpack to exactly `expected_size` bytes
/// (at most kBagMaxChunkBytes). Memory grows with what the data really
/// unpacks to, not with what `expected_size` claims.
/// `checked_after` says the caller checks the unpacked bytes itself (an MCAP
/// chunk's uncompressed_crc): an LZ4 frame's own content checksum is then
/// skipped, as one check of the same bytes is enough.
/// \throws DataError for an unknown compression, damaged data, or a size
///   other than `expected_size`.
std::string Decompress(std::string_view compression,
                       std::string_view input,
                       std::uint64_t expected_size,
                       bool checked_after = false);

/// Decompress into `out`, with no copy a reader does not need: returns the
/// unpacked bytes, which view `input` itself for a stored chunk and `out`
/// otherwise.
std::string_view Decompress(std::string_view compression,
                            std::string_view input,
                            std::uint64_t expected_size,
                            ByteBuffer& out,
                            bool checked_after = false);

}  // namespace mpcal::bag
