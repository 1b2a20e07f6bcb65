// Fuzz target: one line of `daylit eval` input. Whatever the bytes, the answer must be one line of
// valid JSON with an "id" and exactly one of "value" (a finite number) and "error"; any exception,
// crash, sanitizer report or hang is a finding.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <nlohmann/json.hpp>

#include "simulation/eval_queries.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string line(reinterpret_cast<const char*>(data), size);
  const std::string answer = daylit::answer_line(line, "fuzz:1");
  const auto finding = [&](const char* what) {
    std::fprintf(stderr, "%s: %s\n", what, answer.c_str());
    std::abort();
  };
  if (answer.find('\n') != std::string::npos) finding("answer spans lines");
  const nlohmann::json out = nlohmann::json::parse(answer, nullptr, false);
  if (out.is_discarded() || !out.is_object()) finding("answer is not a JSON object");
  if (!out.contains("id")) finding("answer lacks id");
  if (out.contains("value") == out.contains("error")) finding("answer needs exactly one of value and error");
  if (out.contains("value") && !(out["value"].is_number() && std::isfinite(out["value"].get<double>())))
    finding("value is not a finite number");
  if (out.contains("error") && !out["error"].is_string()) finding("error is not a string");
  return 0;
}
