#pragma once
// The one exception type of the library (STYLE.md habit 5). Readers throw it with a source
// location; the CLI prints "error: <what>" and exits non-zero.

#include <stdexcept>
#include <string>

namespace daylit {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Where a piece of input came from: file and 1-based line.
struct SourceLocation {
  std::string file;
  int line = 0;

  std::string str() const { return line > 0 ? file + ":" + std::to_string(line) : file; }
};

inline Error input_error(const SourceLocation& where, const std::string& problem) {
  return Error(where.str() + ": " + problem);
}

}  // namespace daylit
