// MCAP's CRC-32 against zlib's crc32 (the check the format names), at every
// length up to a few folds and at every alignment of the start, so that the
// folded part, the 16-byte steps and the tail each meet every case.
#include <zlib.h>

#include <cstdint>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "bag/mcap_records.h"

namespace mpcal::bag::mcap {
namespace {

std::uint32_t Zlib(std::string_view s) {
  return static_cast<std::uint32_t>(
      crc32_z(0, reinterpret_cast<const Bytef*>(s.data()), s.size()));
}

TEST(Crc32, KnownValues) {
  EXPECT_EQ(Crc32(""), 0u);
  // The check value of CRC-32/ISO-HDLC (the catalogue's "123456789").
  EXPECT_EQ(Crc32("123456789"), 0xCBF43926u);
}

TEST(Crc32, EqualsZlibAtEveryLengthAndAlignment) {
  std::mt19937 rng(3);
  std::string bytes(4096 + 16, '\0');
  for (char& c : bytes) c = static_cast<char>(rng());
  int differ = 0;
  for (std::size_t start = 0; start < 16; ++start) {
    for (std::size_t n = 0; n <= 4096; ++n) {
      const std::string_view s(bytes.data() + start, n);
      differ += Crc32(s) != Zlib(s);
    }
  }
  EXPECT_EQ(differ, 0);
}

TEST(Crc32, EqualsZlibOnAChunkAndFindsOneFlippedBit) {
  std::mt19937 rng(5);
  std::string chunk((1 << 20) + 13, '\0');
  for (char& c : chunk) c = static_cast<char>(rng());
  const std::uint32_t crc = Crc32(chunk);
  EXPECT_EQ(crc, Zlib(chunk));
  for (const std::size_t at : {std::size_t{0}, std::size_t{777}, chunk.size() - 1}) {
    std::string damaged = chunk;
    damaged[at] = static_cast<char>(damaged[at] ^ 0x10);
    EXPECT_NE(Crc32(damaged), crc) << "bit flipped at byte " << at;
  }
}

}  // namespace
}  // namespace mpcal::bag::mcap
