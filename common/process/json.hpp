// A string as a JSON string literal: quotes and backslashes escaped, control
// characters as \u00XX, everything else (UTF-8 included) as it is.
#pragma once

#include <string>

namespace slamer {

std::string json_quote(const std::string& text);

}  // namespace slamer
