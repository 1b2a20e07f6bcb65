// `daylit eval`: reads JSON Lines queries from a file or standard input and writes one answer per
// line, in order (the answering is simulation/eval_queries.cpp).

#include "cli/eval_command.hpp"

#include <CLI/CLI.hpp>

#include <fstream>
#include <iostream>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "geometry/error.hpp"
#include "simulation/eval_queries.hpp"

namespace daylit::cli {

namespace {

using nlohmann::json;

// Reads one line (without its '\n'); false at the end of the input. A line longer than
// kMaxEvalLineBytes is read to its end, but only that much of it is kept, and `too_long` is set.
bool read_bounded_line(std::istream& in, std::string& line, bool& too_long) {
  line.clear();
  too_long = false;
  bool any = false;
  std::streambuf* buffer = in.rdbuf();
  for (int c; (c = buffer->sbumpc()) != std::char_traits<char>::eof();) {
    any = true;
    if (c == '\n') return true;
    if (line.size() < kMaxEvalLineBytes)
      line.push_back(char(c));
    else
      too_long = true;
  }
  return any;
}

int run_eval(const std::string& path) {
  std::ifstream file;
  if (!path.empty()) {
    file.open(path, std::ios::binary);
    if (!file) throw Error(path + ": cannot open file");
  }
  std::istream& in = path.empty() ? std::cin : file;
  const std::string name = path.empty() ? "stdin" : path;
  std::string line;
  bool too_long = false;
  for (long line_number = 1; read_bounded_line(in, line, too_long); ++line_number) {
    const std::string where = name + ":" + std::to_string(line_number);
    if (too_long) {
      std::cout << json{{"id", nullptr}, {"error", where + ": line longer than " + std::to_string(kMaxEvalLineBytes) + " bytes"}}.dump()
                << '\n';
      continue;
    }
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::cout << answer_line(line, where) << '\n';
  }
  std::cout.flush();
  return 0;
}

}  // namespace

std::function<int()> add_eval_command(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  CLI::App* eval = app.add_subcommand("eval", "Evaluate kernel queries given as JSON Lines (closed forms)");
  eval->description(
      "Reads one JSON query per line (from FILE, or standard input) and writes one JSON answer per line:\n"
      "{\"id\": ..., \"value\": v} or {\"id\": ..., \"error\": \"...\"}. Supported now: quantity \"moment\" on\n"
      "polygon regions seen from an origin, with an optional clip hemisphere and factor patterns (), (n), (n,1),\n"
      "(n,1,1); and on cap regions {\"cap\": {\"axis\", \"half_angle\"}} with patterns (), (c^n), (c^n, L^1).\n"
      "A \"denominator\": {\"axis\": d, \"power\": q} with q = 1 or 2 divides by (d·u)^q (rational moments, Chen and\n"
      "Arvo) on polygon regions strictly on one side of d·u = 0: any factors of total degree <= 12, and (n), (n,1),\n"
      "(n,1,1) for any n with q = 1.\n"
      "Quantity \"irradiance\": a luminaire polygon of exitance {\"uniform\": M} or {\"polynomial\": [{\"coef\", \"powers\"}]}\n"
      "seen from \"origin\" with \"normal\" past optional \"occluders\"; with \"gradient\": true also dE/d(origin).");
  eval->add_option("file", *path, "JSON Lines file (default: standard input)");
  return [path] { return run_eval(*path); };
}

}  // namespace daylit::cli
