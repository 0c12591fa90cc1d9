#pragma once
// FNV-1a 64-bit hashing: how journals check their records and name their
// inputs, and how sessions fingerprint their state. Not cryptographic.

#include <cstdint>
#include <string_view>

namespace argil::sculpt {

inline constexpr std::uint64_t kFnvOffsetBasis = 0xcbf29ce484222325ULL;

/// FNV-1a of `bytes`, continuing from `seed` (the offset basis for a fresh hash).
inline std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t seed = kFnvOffsetBasis) {
  std::uint64_t h = seed;
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ULL;
  }
  return h;
}

}  // namespace argil::sculpt
