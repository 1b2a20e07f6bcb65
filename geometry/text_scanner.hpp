#pragma once
// Whitespace-separated tokens with line numbers and '#' comments, and strict number parsing:
// shared by the .rad and .pts readers so that both reject bad input the same way.

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string>
#include <string_view>

#include "geometry/error.hpp"
#include "geometry/input_checks.hpp"

namespace daylit {

struct Token {
  std::string_view text;
  int line = 0;
};

class TextScanner {
 public:
  TextScanner(std::string_view text, std::string file) : text_(text), file_(std::move(file)) {}

  // Next token, or an empty token at the end of the text. Comments run from '#' to end of line.
  // A word that starts with a double or single quote runs to the matching quote, white space and
  // '#' included, as Radiance's fgetword reads it ("porsche #1"); the token is what lies between
  // the quotes. An unterminated or empty quoted word is an error naming its line.
  Token next() {
    skip_blank();
    if (pos_ < text_.size() && (text_[pos_] == '"' || text_[pos_] == '\'')) {
      const char quote = text_[pos_];
      const int line = line_;
      const std::size_t begin = ++pos_;
      while (pos_ < text_.size() && text_[pos_] != quote) line_ += text_[pos_++] == '\n';
      if (pos_ >= text_.size()) throw input_error(where(line), std::string("quoted word without its closing ") + quote);
      const std::string_view word = text_.substr(begin, pos_ - begin);
      ++pos_;
      if (word.empty()) throw input_error(where(line), "empty quoted word");
      return {word, line};
    }
    const std::size_t begin = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
    return {text_.substr(begin, pos_ - begin), line_};
  }

  // Position of the next token without consuming it (the line it starts on, 0 at the end).
  int peek_line() {
    skip_blank();
    return pos_ < text_.size() ? line_ : 0;
  }

  bool at_end() {
    skip_blank();
    return pos_ >= text_.size();
  }

  // The rest of the current line (for error messages about `!command` lines).
  std::string_view rest_of_line() const {
    const std::size_t end = text_.find('\n', pos_);
    return text_.substr(pos_, end == std::string_view::npos ? std::string_view::npos : end - pos_);
  }

  SourceLocation where(int line) const { return {file_, line}; }
  const std::string& file() const { return file_; }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

  void skip_blank() {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == '\n') {
        ++line_;
        ++pos_;
      } else if (is_space(c)) {
        ++pos_;
      } else if (c == '#') {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
      } else {
        break;
      }
    }
  }

  std::string_view text_;
  std::string file_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

// Input text quoted for a message: bytes other than printable ASCII as \xHH (binary garbage and
// NUL bytes must not reach the terminal, and what() ends at a NUL), and at most `max` bytes of
// the input shown, so that a megabyte-long token gives a one-line message.
inline std::string printable(std::string_view s, std::size_t max = 40) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out = "'";
  for (std::size_t i = 0; i < s.size() && i < max; ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += char(c);
    } else {
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  out += s.size() > max ? "'... (" + std::to_string(s.size()) + " bytes)" : "'";
  return out;
}

// A finite real number, or an error naming the place and the offending text. A number too small
// for a double reads as zero (or a subnormal), as in Radiance; one too large is an error.
inline double parse_real(const Token& t, const SourceLocation& where, std::string_view what) {
  std::string_view s = t.text;
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  double value = 0;
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (t.text.empty()) throw input_error(where, "unexpected end of file, expected " + std::string(what));
  if (ec == std::errc::result_out_of_range && end == s.data() + s.size()) {
    // from_chars reports underflow and overflow alike; strtod (on the same, complete, token)
    // returns ±HUGE_VAL only for overflow.
    const std::string copy(s);
    value = std::strtod(copy.c_str(), nullptr);
    if (std::isinf(value))
      throw input_error(where, "number " + printable(t.text) + " is out of range for " + std::string(what));
    ec = std::errc();
  }
  if (ec != std::errc() || end != s.data() + s.size())
    throw input_error(where, "expected a number for " + std::string(what) + ", found " + printable(t.text));
  if (!std::isfinite(value))
    throw input_error(where, "non-finite number " + printable(t.text) + " for " + std::string(what));
  return value;
}

// A coordinate: a real number within ±kMaxCoordinate.
inline double parse_coordinate(const Token& t, const SourceLocation& where, std::string_view what) {
  const double value = parse_real(t, where, what);
  if (!(std::abs(value) <= kMaxCoordinate))
    throw input_error(where, "coordinate " + printable(t.text) + " for " + std::string(what) +
                                 " is beyond 1e12 in magnitude: move the model's origin nearer (or use larger units)");
  return value;
}

// A non-negative integer count, or an error.
inline long parse_count(const Token& t, const SourceLocation& where, std::string_view what) {
  long value = 0;
  const auto [end, ec] = std::from_chars(t.text.data(), t.text.data() + t.text.size(), value);
  if (t.text.empty()) throw input_error(where, "unexpected end of file, expected " + std::string(what));
  if (ec != std::errc() || end != t.text.data() + t.text.size() || value < 0)
    throw input_error(where, "expected a non-negative integer for " + std::string(what) + ", found " +
                                 printable(t.text));
  return value;
}

// Reads a whole file; an error names it if it cannot be opened.
std::string read_text_file(const std::string& path);

}  // namespace daylit
