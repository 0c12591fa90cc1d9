// libFuzzer target: arbitrary bytes as a .iges file through the OpenCASCADE import path.
#include "cad_file_target.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return argil::fuzz::read_cad_bytes(data, size, ".iges");
}
