// CRC-32 (ISO-HDLC: reflected polynomial 0x04C11DB7, as zlib's crc32), which
// MCAP uses for its chunks, data and summary sections.
//
// An MCAP chunk's CRC is computed over every unpacked byte, so it runs as
// fast as the bytes can be unpacked or it sets the reading time: zlib's
// crc32 (tables, several bytes a step) is several times slower than
// unpacking an LZ4 chunk. On x86-64 with PCLMULQDQ the bytes
// are folded 64 at a time by carry-less multiplication instead, the method
// and constants of Gopal et al., "Fast CRC Computation for Generic
// Polynomials Using PCLMULQDQ Instruction" (Intel, 2009), laid out as in
// Chromium's zlib (third_party/zlib/crc32_simd.c, BSD licence); the tail
// below 16 bytes, and every byte on other processors, go to zlib's crc32.
// Both give the same value (tests/bag/crc32_test.cc checks it against zlib's
// at every length and alignment).
#include <zlib.h>

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "bag/mcap_records.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define MPCAL_CRC32_FOLD 1
#endif

namespace mpcal::bag::mcap {
namespace {

#ifdef MPCAL_CRC32_FOLD

#define MPCAL_CRC32_TARGET __attribute__((target("pclmul,sse4.1")))

MPCAL_CRC32_TARGET __m128i Load(const unsigned char* p) {
  return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
}

// Folds `x` forward over 128 bits (with the constants `k`) onto `next`.
MPCAL_CRC32_TARGET __m128i FoldOnto(__m128i x, __m128i k, __m128i next) {
  const __m128i lo = _mm_clmulepi64_si128(x, k, 0x00);
  const __m128i hi = _mm_clmulepi64_si128(x, k, 0x11);
  return _mm_xor_si128(_mm_xor_si128(hi, lo), next);
}

// The folding needs at least 64 bytes and a multiple of 16. `crc` is the
// register before the bytes (the CRC value complemented), and so is the
// result.
MPCAL_CRC32_TARGET std::uint32_t Fold(const unsigned char* buf,
                                      std::size_t len,
                                      std::uint32_t crc) {
  // x^(4*128+64) mod P, x^(4*128) mod P; x^(128+64), x^128; x^64 mod P;
  // P and mu for the Barrett reduction: bit-reflected (Gopal et al., end).
  alignas(16) static const std::uint64_t k1k2[] = {0x0154442bd4, 0x01c6e41596};
  alignas(16) static const std::uint64_t k3k4[] = {0x01751997d0, 0x00ccaa009e};
  alignas(16) static const std::uint64_t k5k0[] = {0x0163cd6124, 0x0000000000};
  alignas(16) static const std::uint64_t poly[] = {0x01db710641, 0x01f7011641};
  __m128i x1 = _mm_xor_si128(Load(buf), _mm_cvtsi32_si128(static_cast<int>(crc)));
  __m128i x2 = Load(buf + 16);
  __m128i x3 = Load(buf + 32);
  __m128i x4 = Load(buf + 48);
  buf += 64, len -= 64;
  // Four lanes of 128 bits, each folded 512 bits forward per step.
  __m128i k = _mm_load_si128(reinterpret_cast<const __m128i*>(k1k2));
  for (; len >= 64; buf += 64, len -= 64) {
    x1 = FoldOnto(x1, k, Load(buf));
    x2 = FoldOnto(x2, k, Load(buf + 16));
    x3 = FoldOnto(x3, k, Load(buf + 32));
    x4 = FoldOnto(x4, k, Load(buf + 48));
  }
  // The four lanes into one, then the remaining 16-byte blocks.
  k = _mm_load_si128(reinterpret_cast<const __m128i*>(k3k4));
  x1 = FoldOnto(x1, k, x2);
  x1 = FoldOnto(x1, k, x3);
  x1 = FoldOnto(x1, k, x4);
  for (; len >= 16; buf += 16, len -= 16) x1 = FoldOnto(x1, k, Load(buf));
  // 128 bits to 64, then Barrett's reduction to 32.
  const __m128i low32 = _mm_setr_epi32(~0, 0, ~0, 0);
  x2 = _mm_clmulepi64_si128(x1, k, 0x10);
  x1 = _mm_xor_si128(_mm_srli_si128(x1, 8), x2);
  k = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(k5k0));
  x2 = _mm_srli_si128(x1, 4);
  x1 = _mm_xor_si128(_mm_clmulepi64_si128(_mm_and_si128(x1, low32), k, 0x00), x2);
  k = _mm_load_si128(reinterpret_cast<const __m128i*>(poly));
  x2 = _mm_and_si128(x1, low32);
  x2 = _mm_and_si128(_mm_clmulepi64_si128(x2, k, 0x10), low32);
  x2 = _mm_clmulepi64_si128(x2, k, 0x00);
  x1 = _mm_xor_si128(x1, x2);
  return static_cast<std::uint32_t>(_mm_extract_epi32(x1, 1));
}

bool CanFold() {
  static const bool can =
      __builtin_cpu_supports("pclmul") && __builtin_cpu_supports("sse4.1");
  return can;
}

#endif

}  // namespace

std::uint32_t Crc32(std::string_view data) {
  auto bytes = reinterpret_cast<const unsigned char*>(data.data());
  std::size_t left = data.size();
  std::uint32_t crc = 0;
#ifdef MPCAL_CRC32_FOLD
  if (left >= 64 && CanFold()) {
    const std::size_t folded = left & ~std::size_t{15};
    crc = ~Fold(bytes, folded, ~crc);
    bytes += folded, left -= folded;
  }
#endif
  return static_cast<std::uint32_t>(crc32_z(crc, bytes, left));
}

}  // namespace mpcal::bag::mcap
