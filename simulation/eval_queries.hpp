#pragma once
// `daylit eval`'s query answering: one JSON query line in, one JSON answer line out, for exact
// point evaluations of the kernels (moments, cap moments, rational moments, sky irradiance,
// luminaire irradiance and its gradient). The CLI reads the lines; this answers them.

#include <cstddef>
#include <string>

namespace daylit {

// The longest query line answered (a 10,000-vertex polygon takes about 300 kB); the reader keeps
// at most this much of a line and reports the rest as too long.
inline constexpr std::size_t kMaxEvalLineBytes = std::size_t(1) << 20;

// The answer to one query line (without its newline), as one line of JSON: {"id": …, "value": v}
// or {"id": …, "error": "…"}. Input errors (invalid JSON, nesting beyond 64 levels) name `where`
// ("file:line"). Never throws for any input; used by `daylit eval` and its fuzz target.
std::string answer_line(const std::string& line, const std::string& where);

}  // namespace daylit
