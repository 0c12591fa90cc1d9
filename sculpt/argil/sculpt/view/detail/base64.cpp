#include "argil/sculpt/view/detail/base64.hpp"

#include <cstdint>

namespace argil::sculpt::detail {

std::string base64(const void* bytes, std::size_t size) {
  static constexpr char kDigits[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* in = static_cast<const std::uint8_t*>(bytes);
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= size; i += 3) {
    const std::uint32_t n =
        (std::uint32_t{in[i]} << 16) | (std::uint32_t{in[i + 1]} << 8) | in[i + 2];
    for (int shift = 18; shift >= 0; shift -= 6) out.push_back(kDigits[(n >> shift) & 63]);
  }
  if (i < size) {
    const bool two = i + 1 < size;
    const std::uint32_t n =
        (std::uint32_t{in[i]} << 16) | (two ? std::uint32_t{in[i + 1]} << 8 : 0);
    out.push_back(kDigits[(n >> 18) & 63]);
    out.push_back(kDigits[(n >> 12) & 63]);
    out.push_back(two ? kDigits[(n >> 6) & 63] : '=');
    out.push_back('=');
  }
  return out;
}

}  // namespace argil::sculpt::detail
