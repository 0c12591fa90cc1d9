#pragma once
// Internal to argil_io: keeps OpenCASCADE from printing to the console.

namespace argil::io::detail {

/// Removes OpenCASCADE's console printers once per process (idempotent, cheap).
void silence_occt_console();

}  // namespace argil::io::detail
