#include "argil/io/occt_console.hpp"

#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>

#include <mutex>

namespace argil::io::detail {

void silence_occt_console() {
  static std::once_flag once;
  std::call_once(once, [] {
    // Transfer statistics and warnings go to stdout with colour codes otherwise.
    Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
  });
}

}  // namespace argil::io::detail
