// Supervisor's XML-RPC replies as slamer-launch reads them: any bytes give a
// value or XmlRpcError, never a crash.
#include <cstddef>
#include <cstdint>
#include <string>

#include "tools/launch/xmlrpc.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    slamer::launch::parse_process_infos(slamer::launch::parse_xmlrpc_response(bytes));
  } catch (const slamer::launch::XmlRpcError&) {
  }
  try {
    slamer::launch::http_body(bytes);
  } catch (const slamer::launch::XmlRpcError&) {
  }
  return 0;
}
