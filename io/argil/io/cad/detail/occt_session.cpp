#include "argil/io/cad/detail/occt_session.hpp"

#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>

namespace argil::io::detail {

void silence_occt_console() {
  static std::once_flag once;
  std::call_once(once, [] {
    // Transfer statistics and warnings go to stdout with colour codes otherwise.
    Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
  });
}

std::unique_lock<std::mutex> lock_occt_exchange() {
  static std::mutex mutex;
  return std::unique_lock<std::mutex>(mutex);
}

}  // namespace argil::io::detail
