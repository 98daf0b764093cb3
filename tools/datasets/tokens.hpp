// Whitespace tokenizer with strict number parsing for the dataset readers
// (internal to tools/datasets): a token is a number only if all of it is.
#pragma once

#include <charconv>
#include <string_view>

namespace slamer::dataset_detail {

class Tokens {
 public:
  explicit Tokens(std::string_view text) : text_(text) {}

  bool next(std::string_view* token) {
    while (pos_ < text_.size() && is_space(text_[pos_])) {
      ++pos_;
    }
    if (pos_ >= text_.size()) {
      return false;
    }
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_])) {
      ++pos_;
    }
    *token = text_.substr(start, pos_ - start);
    ++count_;
    return true;
  }

  template <class T>
  bool number(T* value) {
    std::string_view token;
    if (!next(&token)) {
      return false;
    }
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), *value);
    return error == std::errc() && end == token.data() + token.size();
  }

  bool skip(int count) {
    std::string_view token;
    for (int i = 0; i < count; ++i) {
      if (!next(&token)) {
        return false;
      }
    }
    return true;
  }

  int count() const { return count_; }  // tokens read so far (1 = the first)

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

  std::string_view text_;
  std::size_t pos_ = 0;
  int count_ = 0;
};

}  // namespace slamer::dataset_detail
