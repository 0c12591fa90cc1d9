#pragma once
// Base64 (RFC 4648, with padding) of raw bytes: the viewer page carries its
// vertex arrays as base64 strings of little-endian typed arrays.

#include <cstddef>
#include <string>
#include <vector>

namespace argil::sculpt::detail {

std::string base64(const void* bytes, std::size_t size);

/// The bytes of a vector of numbers (float, double, std::uint32_t, ...).
template <class T>
std::string base64_of(const std::vector<T>& values) {
  return base64(values.data(), values.size() * sizeof(T));
}

}  // namespace argil::sculpt::detail
