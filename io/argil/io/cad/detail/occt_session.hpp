#pragma once
// Internal to argil_io: the process-wide OpenCASCADE state that the import and
// export seams share.

#include <mutex>

namespace argil::io::detail {

/// Removes OpenCASCADE's console printers once per process (idempotent, cheap).
void silence_occt_console();

/// Held for the whole of an OCCT read or write: the readers and writers share
/// global parameters (Interface_Static) and are not thread-safe.
[[nodiscard]] std::unique_lock<std::mutex> lock_occt_exchange();

}  // namespace argil::io::detail
