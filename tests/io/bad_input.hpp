#pragma once
// Bad inputs built from good ones by text edits, and the error a bad file gives.

#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "argil/io.hpp"

namespace argil::test {

// The error of reading `path`, which must fail.
inline Status read_error(const std::filesystem::path& path) {
  const Result<io::Model> result = io::read_model(path);
  REQUIRE_FALSE(result.ok());
  INFO(result.status().message);
  CHECK_THAT(result.status().message, Catch::Contains(path.string()));
  return result.status();
}

inline std::string replace_first(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

// Replaces the `index`-th number of the array that follows "key" in a JSON text.
inline std::string replace_array_number(std::string text, const std::string& key, int index,
                                        const std::string& replacement) {
  std::size_t at = text.find('[', text.find("\"" + key + "\""));
  REQUIRE(at != std::string::npos);
  for (int k = 0; k <= index; ++k) {
    at = text.find_first_of("-0123456789", at + 1);
    REQUIRE(at != std::string::npos);
    if (k == index) break;
    at = text.find(',', at);
  }
  const std::size_t end = text.find_first_of(",]", at);
  return text.replace(at, end - at, replacement);
}

}  // namespace argil::test
