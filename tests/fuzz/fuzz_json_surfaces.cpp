// libFuzzer target: arbitrary bytes through the native JSON surface loader
// (argil::io::parse_json, which read_json() calls with the file's content).
// Rejection must be a clean Status; acceptance must give a usable model.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "argil/io/json/json_format.hpp"
#include "model_checks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const argil::Result<argil::io::Model> model = argil::io::parse_json(text, "<fuzz>");
  if (model.ok()) {
    argil::fuzz::check_accepted_model(model.value());
  } else if (model.status().message.empty()) {
    argil::fuzz::fail("rejection without a message", 0);
  }
  return 0;
}
