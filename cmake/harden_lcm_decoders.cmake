# Run as a script after lcm-gen --cpp. lcm-gen 1.3.1 decodes an array count or
# string length from the wire and then resizes/assigns before checking that the
# bytes exist, so a 30-byte forged message can ask for gigabytes or make
# std::string throw. Every element takes at least one byte on the wire, so a
# count larger than the bytes left is malformed; a string length includes its
# terminating NUL, so it is at least 1, and the bytes must be a C string (one
# NUL, at the end): otherwise the message does not re-encode to itself, and a
# std::string with an inner NUL makes encode() write less than getEncodedSize(). Fails if the generated code no longer
# has the expected shape (a newer lcm-gen must be looked at, not silently passed).
file(GLOB header_list ${HEADER_DIR}/*.hpp)
set(total_guards 0)
foreach(header ${header_list})
  file(READ ${header} code)
  # (no ';' in the MATCHALL patterns: CMake would split the matches into list items)
  string(REGEX MATCHALL "this->[A-Za-z0-9_]+\\.resize\\(this->[A-Za-z0-9_]+\\)" resizes "${code}")
  string(REGEX MATCHALL "if\\(__[A-Za-z0-9_]+ > maxlen - pos\\) return -1" strings "${code}")
  string(REGEX REPLACE
    "([ ]*)this->([A-Za-z0-9_]+)\\.resize\\(this->([A-Za-z0-9_]+)\\);"
    "\\1if (this->\\3 < 0 || this->\\3 > maxlen - pos) return -1;  // slamer: hardened\n\\1this->\\2.resize(this->\\3);"
    code "${code}")
  string(REGEX REPLACE
    "if\\((__[A-Za-z0-9_]+) > maxlen - pos\\) return -1;"
    "if(\\1 < 1 || \\1 > maxlen - pos || !slamer_lcm_is_c_string(static_cast<const char*>(buf) + offset + pos, \\1)) return -1;  // slamer: hardened"
    code "${code}")
  # The helper the string checks call: exactly one NUL, at the end.
  string(REPLACE "#include <lcm/lcm_coretypes.h>"
    "#include <lcm/lcm_coretypes.h>\n#include <cstring>\n#ifndef SLAMER_LCM_IS_C_STRING\n#define SLAMER_LCM_IS_C_STRING\ninline bool slamer_lcm_is_c_string(const char* s, int len) { return s[len - 1] == 0 && std::memchr(s, 0, static_cast<size_t>(len - 1)) == nullptr; }\n#endif"
    code "${code}")
  list(LENGTH resizes n_resizes)
  list(LENGTH strings n_strings)
  math(EXPR total_guards "${total_guards} + ${n_resizes} + ${n_strings}")
  # Any resize or string assign left unguarded means the generator changed.
  string(REGEX MATCHALL "resize\\(" all_resizes "${code}")
  string(REGEX MATCHALL "\\.assign\\(" all_assigns "${code}")
  list(LENGTH all_resizes n_all_resizes)
  list(LENGTH all_assigns n_all_assigns)
  if(NOT n_all_resizes EQUAL n_resizes OR NOT n_all_assigns EQUAL n_strings)
    message(FATAL_ERROR "harden_lcm_decoders: unexpected lcm-gen output in ${header}: "
                        "${n_all_resizes} resize/${n_resizes} matched, ${n_all_assigns} assign/${n_strings} matched")
  endif()
  if(n_strings GREATER 0 AND NOT code MATCHES "inline bool slamer_lcm_is_c_string")
    message(FATAL_ERROR "harden_lcm_decoders: ${header} does not include lcm/lcm_coretypes.h as expected")
  endif()
  file(WRITE ${header} "${code}")
endforeach()
if(total_guards EQUAL 0)
  message(FATAL_ERROR "harden_lcm_decoders: no decoder found to harden in ${HEADER_DIR}")
endif()
