// The part of supervisor's XML-RPC interface slamer-launch uses
// (http://supervisord.org/api.html; XML-RPC spec: http://xmlrpc.com/spec.md):
// request bodies, and a bounded parser of the replies (they come from another
// process over a socket: malformed bytes give ParseError, never a crash).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace slamer::launch {

class XmlRpcError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct XmlRpcValue {
  enum class Kind { kString, kInt, kBool, kDouble, kArray, kStruct, kNil };
  Kind kind = Kind::kNil;
  std::string text;                        // kString; the literal of kDouble
  int64_t integer = 0;                     // kInt, kBool
  std::vector<XmlRpcValue> items;          // kArray
  std::vector<std::string> member_names;   // kStruct, in order
  std::vector<XmlRpcValue> member_values;  // (a vector of pairs would need the type complete)

  const XmlRpcValue* member(const std::string& name) const;
};

// <methodCall> with string and boolean parameters.
struct XmlRpcParam {
  enum class Kind { kString, kBool } kind;
  std::string text;
  bool flag = false;
};
std::string xmlrpc_request(const std::string& method, const std::vector<XmlRpcParam>& params = {});

// The value of a <methodResponse>. A <fault> throws XmlRpcError with its
// faultString; anything malformed (or nested deeper than 16) throws XmlRpcError.
XmlRpcValue parse_xmlrpc_response(const std::string& body);

// The body of an HTTP/1.0 response (status 200 required, else XmlRpcError).
std::string http_body(const std::string& response);

// supervisor.getProcessInfo's fields that slamer-launch uses.
struct ProcessInfo {
  std::string name;
  std::string state;  // STOPPED, STARTING, RUNNING, BACKOFF, STOPPING, EXITED, FATAL, UNKNOWN
  int64_t pid = 0;
  int64_t exit_status = 0;
  std::string description;
};
// supervisor.getAllProcessInfo's array.
std::vector<ProcessInfo> parse_process_infos(const XmlRpcValue& value);

}  // namespace slamer::launch
