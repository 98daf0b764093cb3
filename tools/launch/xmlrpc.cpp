#include "tools/launch/xmlrpc.hpp"

#include <cctype>
#include <cerrno>
#include <cstdlib>

namespace slamer::launch {
namespace {

std::string escape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '&') {
      out += "&amp;";
    } else if (c == '<') {
      out += "&lt;";
    } else if (c == '>') {
      out += "&gt;";
    } else {
      out += c;
    }
  }
  return out;
}

// A cursor over the reply: tags, text between them, entity decoding.
class Reader {
 public:
  explicit Reader(const std::string& text) : text_(text) {}

  void skip_space_and_declarations() {
    for (;;) {
      while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_])) != 0) {
        ++pos_;
      }
      if (text_.compare(pos_, 2, "<?") == 0) {
        const std::size_t end = text_.find("?>", pos_);
        if (end == std::string::npos) {
          throw XmlRpcError("XML-RPC reply: unterminated declaration");
        }
        pos_ = end + 2;
        continue;
      }
      return;
    }
  }
  // The next tag's name ("/x" for a closing one, "x/" for an empty one) without consuming it.
  std::string peek_tag() {
    skip_space_and_declarations();
    if (pos_ >= text_.size() || text_[pos_] != '<') {
      return "";
    }
    const std::size_t end = text_.find('>', pos_);
    if (end == std::string::npos) {
      throw XmlRpcError("XML-RPC reply: unterminated tag");
    }
    return text_.substr(pos_ + 1, end - pos_ - 1);
  }
  void expect(const std::string& tag) {
    const std::string found = peek_tag();
    if (found != tag) {
      throw XmlRpcError("XML-RPC reply: expected <" + tag + ">, found " +
                        (found.empty() ? std::string("text or the end") : "<" + found.substr(0, 40) + ">"));
    }
    pos_ = text_.find('>', pos_) + 1;
  }
  // Text up to the next '<', entities decoded (no skipping of spaces: strings keep them).
  std::string text() {
    const std::size_t end = text_.find('<', pos_);
    if (end == std::string::npos) {
      throw XmlRpcError("XML-RPC reply: text runs to the end");
    }
    const std::string raw = text_.substr(pos_, end - pos_);
    pos_ = end;
    std::string out;
    for (std::size_t i = 0; i < raw.size(); ++i) {
      if (raw[i] != '&') {
        out += raw[i];
        continue;
      }
      const std::size_t semi = raw.find(';', i);
      const std::string entity = semi == std::string::npos ? "" : raw.substr(i + 1, semi - i - 1);
      if (entity == "amp") {
        out += '&';
      } else if (entity == "lt") {
        out += '<';
      } else if (entity == "gt") {
        out += '>';
      } else if (entity == "quot") {
        out += '"';
      } else if (entity == "apos") {
        out += '\'';
      } else {
        throw XmlRpcError("XML-RPC reply: unknown entity");
      }
      i = semi;
    }
    return out;
  }

 private:
  const std::string& text_;
  std::size_t pos_ = 0;
};

int64_t parse_integer(const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll(text.c_str(), &end, 10);
  if (text.empty() || end != text.c_str() + text.size() || errno != 0) {
    throw XmlRpcError("XML-RPC reply: bad integer");
  }
  return value;
}

XmlRpcValue parse_value(Reader& in, int depth) {
  if (depth > 16) {
    throw XmlRpcError("XML-RPC reply: nested too deep");
  }
  XmlRpcValue v;
  in.expect("value");
  const std::string tag = in.peek_tag();
  if (tag == "/value") {  // no type: a string
    v.kind = XmlRpcValue::Kind::kString;
    in.expect("/value");
    return v;
  }
  if (tag.empty()) {
    v.kind = XmlRpcValue::Kind::kString;
    v.text = in.text();
  } else if (tag == "string" || tag == "int" || tag == "i4" || tag == "i8" || tag == "boolean" || tag == "double") {
    in.expect(tag);
    const std::string text = in.text();
    in.expect("/" + tag);
    if (tag == "string") {
      v.kind = XmlRpcValue::Kind::kString;
      v.text = text;
    } else if (tag == "double") {
      v.kind = XmlRpcValue::Kind::kDouble;
      v.text = text;
    } else {
      v.kind = tag == "boolean" ? XmlRpcValue::Kind::kBool : XmlRpcValue::Kind::kInt;
      v.integer = parse_integer(text);
    }
  } else if (tag == "string/") {
    in.expect(tag);
    v.kind = XmlRpcValue::Kind::kString;
  } else if (tag == "nil/") {
    in.expect(tag);
  } else if (tag == "array") {
    v.kind = XmlRpcValue::Kind::kArray;
    in.expect("array");
    in.expect("data");
    while (in.peek_tag() == "value") {
      v.items.push_back(parse_value(in, depth + 1));
    }
    in.expect("/data");
    in.expect("/array");
  } else if (tag == "struct") {
    v.kind = XmlRpcValue::Kind::kStruct;
    in.expect("struct");
    while (in.peek_tag() == "member") {
      in.expect("member");
      in.expect("name");
      std::string name = in.text();
      in.expect("/name");
      XmlRpcValue member = parse_value(in, depth + 1);
      in.expect("/member");
      v.member_names.push_back(std::move(name));
      v.member_values.push_back(std::move(member));
    }
    in.expect("/struct");
  } else {
    throw XmlRpcError("XML-RPC reply: unknown value type <" + tag.substr(0, 40) + ">");
  }
  in.expect("/value");
  return v;
}

std::string string_member(const XmlRpcValue& value, const std::string& name) {
  const XmlRpcValue* m = value.member(name);
  return m != nullptr && m->kind == XmlRpcValue::Kind::kString ? m->text : "";
}

int64_t int_member(const XmlRpcValue& value, const std::string& name) {
  const XmlRpcValue* m = value.member(name);
  return m != nullptr && m->kind == XmlRpcValue::Kind::kInt ? m->integer : 0;
}

}  // namespace

const XmlRpcValue* XmlRpcValue::member(const std::string& name) const {
  for (std::size_t i = 0; i < member_names.size(); ++i) {
    if (member_names[i] == name) {
      return &member_values[i];
    }
  }
  return nullptr;
}

std::string xmlrpc_request(const std::string& method, const std::vector<XmlRpcParam>& params) {
  std::string body = "<?xml version=\"1.0\"?>\n<methodCall><methodName>" + escape(method) + "</methodName><params>";
  for (const XmlRpcParam& p : params) {
    body += p.kind == XmlRpcParam::Kind::kString
                ? "<param><value><string>" + escape(p.text) + "</string></value></param>"
                : std::string("<param><value><boolean>") + (p.flag ? "1" : "0") + "</boolean></value></param>";
  }
  return body + "</params></methodCall>\n";
}

XmlRpcValue parse_xmlrpc_response(const std::string& body) {
  Reader in(body);
  in.expect("methodResponse");
  if (in.peek_tag() == "fault") {
    in.expect("fault");
    const XmlRpcValue fault = parse_value(in, 0);
    throw XmlRpcError("supervisor: " + string_member(fault, "faultString"));
  }
  in.expect("params");
  in.expect("param");
  XmlRpcValue value = parse_value(in, 0);
  in.expect("/param");
  in.expect("/params");
  in.expect("/methodResponse");
  return value;
}

std::string http_body(const std::string& response) {
  const std::size_t end = response.find("\r\n\r\n");
  if (end == std::string::npos) {
    throw XmlRpcError("supervisor's HTTP reply has no header end");
  }
  const std::size_t line_end = response.find("\r\n");
  const std::string status_line = response.substr(0, line_end);
  if (status_line.rfind("HTTP/", 0) != 0 || status_line.find(" 200") == std::string::npos) {
    throw XmlRpcError("supervisor's HTTP reply: " + status_line.substr(0, 80));
  }
  return response.substr(end + 4);
}

std::vector<ProcessInfo> parse_process_infos(const XmlRpcValue& value) {
  if (value.kind != XmlRpcValue::Kind::kArray) {
    throw XmlRpcError("supervisor.getAllProcessInfo: expected an array");
  }
  std::vector<ProcessInfo> infos;
  for (const XmlRpcValue& item : value.items) {
    if (item.kind != XmlRpcValue::Kind::kStruct) {
      throw XmlRpcError("supervisor.getAllProcessInfo: expected structs in the array");
    }
    ProcessInfo info;
    info.name = string_member(item, "name");
    info.state = string_member(item, "statename");
    info.pid = int_member(item, "pid");
    info.exit_status = int_member(item, "exitstatus");
    info.description = string_member(item, "description");
    infos.push_back(std::move(info));
  }
  return infos;
}

}  // namespace slamer::launch
