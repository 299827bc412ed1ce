/// \file count.h
/// \brief A number with its noun, singular or plural as the number asks:
/// "1 position", "2 positions", "1 still stretch", "3 still stretches".
///
/// Every message and table that counts goes through Count, so that no output
/// reads "1 positions".
#pragma once

#include <concepts>
#include <string>
#include <string_view>

namespace mpcal {

/// "`n` `singular`" when n is 1, else "`n` `plural`" (by default the
/// singular with an "s").
std::string Count(std::integral auto n,
                  std::string_view singular,
                  std::string_view plural = {}) {
  std::string out = std::to_string(n) + " ";
  if (n == 1) return out.append(singular);
  if (!plural.empty()) return out.append(plural);
  return out.append(singular).append("s");
}

}  // namespace mpcal
