#include "bag/decompress.h"

#include <bzlib.h>
#include <lz4.h>
#include <lz4frame.h>
#include <zstd.h>

// XXH32 inlined from xxhash.h (libxxhash-dev), header only: nothing to link.
#define XXH_INLINE_ALL
#include <xxhash.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <optional>

#include "bag/bag_io.h"
#include "mpcal/bag.h"

namespace mpcal::bag {
namespace {

// The output grows a step at a time, so a chunk claiming a huge size costs
// only what its data really unpacks to.
constexpr std::size_t kStepBytes = 1 << 20;
constexpr std::size_t kLz4MaxBlockBytes = 4 << 20;
constexpr std::size_t kZstdFirstRoomBytes = 4 << 20;

// Makes room for at least one more byte than `expected` allows, so a stream
// that unpacks to more than it claims is caught.
char* Grow(ByteBuffer& out,
           std::size_t& used,
           std::uint64_t expected,
           std::size_t& room) {
  if (used == out.size()) {
    const std::uint64_t limit = expected + 1;
    out.Resize(static_cast<std::size_t>(
        std::min<std::uint64_t>(limit, out.size() + kStepBytes)));
  }
  room = out.size() - used;
  return out.data() + used;
}

[[noreturn]] void SizeMismatch(const char* name,
                               std::size_t got,
                               std::uint64_t expected) {
  throw DataError(
      std::string(name) + " data unpacks to " +
      (got > expected ? "more than " + std::to_string(expected) : std::to_string(got)) +
      " bytes; the chunk header says " + std::to_string(expected));
}

void Bz2(std::string_view input, std::uint64_t expected, ByteBuffer& out) {
  bz_stream s{};
  if (BZ2_bzDecompressInit(&s, 0, 0) != BZ_OK) throw DataError("bz2: cannot initialise");
  std::unique_ptr<bz_stream, int (*)(bz_stream*)> guard(&s, BZ2_bzDecompressEnd);
  if (input.size() > std::numeric_limits<unsigned>::max())
    throw DataError("bz2: chunk too large");
  s.next_in = const_cast<char*>(input.data());
  s.avail_in = static_cast<unsigned>(input.size());
  out.Resize(0);
  std::size_t used = 0;
  for (;;) {
    std::size_t room = 0;
    s.next_out = Grow(out, used, expected, room);
    s.avail_out = static_cast<unsigned>(room);
    const int rc = BZ2_bzDecompress(&s);
    used = out.size() - s.avail_out;
    if (used > expected) SizeMismatch("bz2", used, expected);
    if (rc == BZ_STREAM_END) break;
    if (rc != BZ_OK)
      throw DataError("bz2 data is damaged (libbz2 code " + std::to_string(rc) + ")");
    if (s.avail_in == 0 && s.avail_out != 0) throw DataError("bz2 data ends early");
  }
  if (used != expected) SizeMismatch("bz2", used, expected);
  out.Resize(used);
}

// The frame's content checksum as its writer stored it, when the frame has
// one (LZ4 Frame Format 1.6.2, lz4/doc/lz4_Frame_format.md: magic
// 0x184D2204, the FLG byte's bit 2, the XXH32 of the content, seed 0, in the
// four bytes after the end mark); `frame` is the whole frame as consumed.
std::optional<std::uint32_t> StoredContentChecksum(std::string_view frame) {
  constexpr std::uint32_t kFrameMagic = 0x184D2204;
  constexpr unsigned kContentChecksumFlag = 1u << 2;
  if (frame.size() < 4 + 1 + 4) return std::nullopt;
  ByteCursor c(frame);
  if (c.U32("the frame magic") != kFrameMagic) return std::nullopt;
  if ((c.U8("the frame's flags") & kContentChecksumFlag) == 0) return std::nullopt;
  return ByteCursor(frame.substr(frame.size() - 4)).U32("the content checksum");
}

void Lz4(std::string_view input,
         std::uint64_t expected,
         bool checked_after,
         ByteBuffer& out) {
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) {
    throw DataError("lz4: cannot initialise");
  }
  std::unique_ptr<LZ4F_dctx, LZ4F_errorCode_t (*)(LZ4F_dctx*)> guard(
      raw, LZ4F_freeDecompressionContext);
  LZ4F_decompressOptions_t options{};
  // skipChecksums is in lz4 from 1.9.4 (Debian bookworm). The content
  // checksum is then verified below, by xxhash.h's XXH32 over the whole
  // unpacked chunk, which takes less than half the time of liblz4's own
  // block-by-block update (bench/bag_bench.sh's ROS 1 lz4 files); with an
  // older lz4, liblz4 verifies it. A caller that checks the bytes itself (an
  // MCAP chunk's CRC) skips it: one check of the same bytes is enough.
#if LZ4_VERSION_NUMBER >= 10904
  const bool verify_here = !checked_after;
  options.skipChecksums = 1;
#else
  const bool verify_here = false;
  (void)checked_after;
#endif
  // LZ4 unpacks a block straight into the output only when the room there
  // holds its largest block (4 MiB at most, the frame's BD byte); with less it
  // unpacks into a buffer of its own and copies. The buffer is not
  // zero-filled, so pages it does not write cost no memory.
  out.Resize(kLz4MaxBlockBytes);
  std::size_t used = 0;
  std::size_t in_pos = 0;
  for (;;) {
    std::size_t room = 0;
    char* dst = Grow(out, used, expected, room);
    std::size_t src_size = input.size() - in_pos;
    const std::size_t hint =
        LZ4F_decompress(raw, dst, &room, input.data() + in_pos, &src_size, &options);
    if (LZ4F_isError(hint)) {
      throw DataError(std::string("lz4 frame is damaged (") + LZ4F_getErrorName(hint) +
                      ")");
    }
    in_pos += src_size;
    used += room;
    if (used > expected) SizeMismatch("lz4", used, expected);
    if (hint == 0) break;
    if (in_pos == input.size() && room == 0) throw DataError("lz4 frame ends early");
  }
  if (used != expected) SizeMismatch("lz4", used, expected);
  out.Resize(used);
  if (verify_here) {
    const std::optional<std::uint32_t> stored =
        StoredContentChecksum(input.substr(0, in_pos));
    if (stored && XXH32(out.data(), used, 0) != *stored) {
      throw DataError(
          "lz4 frame is damaged (ERROR_contentChecksum_invalid: the XXH32 of the "
          "unpacked bytes does not match the frame's content checksum)");
    }
  }
}

void Zstd(std::string_view input, std::uint64_t expected, ByteBuffer& out) {
  std::unique_ptr<ZSTD_DCtx, std::size_t (*)(ZSTD_DCtx*)> ctx(ZSTD_createDCtx(),
                                                              ZSTD_freeDCtx);
  if (!ctx) throw DataError("zstd: cannot initialise");
  // A window beyond the chunk's size would only serve a hostile frame.
  ZSTD_DCtx_setParameter(ctx.get(), ZSTD_d_windowLogMax, 30);
  ZSTD_inBuffer in{input.data(), input.size(), 0};
  // zstd unpacks a frame straight into the output, in one pass, only when
  // the room there holds the whole frame; with less it unpacks into a window
  // of its own and copies out. A writer closes a chunk once it passes its
  // size (@mcap/core: 1 MiB), so the first room is the chunk's size and one
  // byte, up to 4 MiB (more grows a step at a time); it is not zero-filled,
  // so pages a smaller chunk does not reach cost no memory.
  out.Resize(static_cast<std::size_t>(
      std::min<std::uint64_t>(expected + 1, kZstdFirstRoomBytes)));
  std::size_t used = 0;
  for (;;) {
    std::size_t room = 0;
    char* dst = Grow(out, used, expected, room);
    ZSTD_outBuffer o{dst, room, 0};
    const std::size_t rc = ZSTD_decompressStream(ctx.get(), &o, &in);
    if (ZSTD_isError(rc)) {
      throw DataError(std::string("zstd data is damaged (") + ZSTD_getErrorName(rc) +
                      ")");
    }
    used += o.pos;
    if (used > expected) SizeMismatch("zstd", used, expected);
    if (rc == 0 && in.pos == in.size) break;
    if (in.pos == in.size && o.pos < o.size) throw DataError("zstd data ends early");
  }
  if (used != expected) SizeMismatch("zstd", used, expected);
  out.Resize(used);
}

}  // namespace

bool IsKnownCompression(std::string_view c) {
  return c.empty() || c == "none" || c == "bz2" || c == "lz4" || c == "zstd";
}

std::string_view Decompress(std::string_view compression,
                            std::string_view input,
                            std::uint64_t expected_size,
                            ByteBuffer& out,
                            bool checked_after) {
  if (expected_size > kBagMaxChunkBytes) {
    throw DataError("a chunk of " + std::to_string(expected_size) +
                    " bytes unpacked is above the cap of " +
                    std::to_string(kBagMaxChunkBytes));
  }
  if (compression.empty() || compression == "none") {
    if (input.size() != expected_size)
      SizeMismatch("stored", input.size(), expected_size);
    return input;
  }
  if (compression == "bz2") {
    Bz2(input, expected_size, out);
  } else if (compression == "lz4") {
    Lz4(input, expected_size, checked_after, out);
  } else if (compression == "zstd") {
    Zstd(input, expected_size, out);
  } else {
    throw DataError("unknown compression '" + std::string(compression) + "'");
  }
  return out.view();
}

std::string Decompress(std::string_view compression,
                       std::string_view input,
                       std::uint64_t expected_size,
                       bool checked_after) {
  ByteBuffer out;
  return std::string(Decompress(compression, input, expected_size, out, checked_after));
}

}  // namespace mpcal::bag
