// One query per input line, one answer per output line, in order: {"id": …, "value": v}, or
// {"id": …, "error": "…"} for a query that cannot be answered (the run goes on). The query
// fields are those of the kernel issue: quantity "moment", region {"polygon", "origin"} (a cap
// region is not supported yet), optional "clip", "factors" [{"axis", "power"}], and
// "denominator" (rational moments: not supported yet).

#include "cli/eval_command.hpp"

#include <fstream>
#include <iostream>
#include <string>

#include <nlohmann/json.hpp>

#include "geometry/error.hpp"
#include "illumination/factor_moment.hpp"
#include "illumination/hemisphere_clip.hpp"

namespace daylit::cli {

namespace {

using nlohmann::json;

// Results whose estimated error exceeds this are refused rather than reported.
constexpr double kAccuracyBound = 1e-10;

Vec3 vector_field(const json& j, const std::string& what) {
  if (!j.is_array() || j.size() != 3) throw Error(what + " must be an array of 3 numbers");
  Vec3 v;
  double* c[3] = {&v.x, &v.y, &v.z};
  for (int i = 0; i < 3; ++i) {
    if (!j[i].is_number()) throw Error(what + " must be an array of 3 numbers");
    *c[i] = j[i].get<double>();
  }
  if (!is_finite(v)) throw Error(what + " must be finite");
  return v;
}

int power_field(const json& j, const std::string& what) {
  if (!j.is_number()) throw Error(what + " must be a number");
  const double p = j.get<double>();
  if (!(p >= 0) || p != std::floor(p) || p > 1e7) throw Error(what + " must be a non-negative integer (at most 1e7)");
  return int(p);
}

double answer_moment(const json& q) {
  if (!q.contains("region") || !q["region"].is_object()) throw Error("a moment query needs a \"region\" object");
  const json& r = q["region"];
  SphericalRegion region;
  if (r.contains("polygon")) {
    const json& poly = r["polygon"];
    if (!poly.is_array() || poly.size() < 3) throw Error("region.polygon must have at least 3 vertices");
    std::vector<Vec3> vertices;
    for (std::size_t i = 0; i < poly.size(); ++i) vertices.push_back(vector_field(poly[i], "region.polygon[" + std::to_string(i) + "]"));
    if (!r.contains("origin")) throw Error("region.polygon needs region.origin");
    region = directions_through(vertices, vector_field(r["origin"], "region.origin"));
  } else if (r.contains("cap")) {
    throw Error("cap regions are not supported yet");
  } else {
    throw Error("region must have \"polygon\" or \"cap\"");
  }
  if (q.contains("clip")) region = clip_to_hemisphere(region, vector_field(q["clip"], "clip"));
  if (q.contains("denominator")) {
    const json& d = q["denominator"];
    if (!d.is_object() || !d.contains("power")) throw Error("denominator must be {\"axis\": [x,y,z], \"power\": q}");
    if (power_field(d["power"], "denominator.power") > 0)
      throw Error("rational moments (a denominator with power > 0) are not supported yet");
  }
  std::vector<Factor> factors;
  if (q.contains("factors")) {
    const json& fs = q["factors"];
    if (!fs.is_array()) throw Error("factors must be an array");
    for (std::size_t i = 0; i < fs.size(); ++i) {
      const std::string where = "factors[" + std::to_string(i) + "]";
      if (!fs[i].is_object() || !fs[i].contains("axis") || !fs[i].contains("power"))
        throw Error(where + " must be {\"axis\": [x,y,z], \"power\": p}");
      factors.push_back({vector_field(fs[i]["axis"], where + ".axis"), power_field(fs[i]["power"], where + ".power")});
    }
  }
  const FactorMoment m = factor_moment(region, factors);
  if (!(m.relative_error <= kAccuracyBound))
    throw Error("the edge terms cancel beyond what __float128 carries (estimated relative error " +
                std::to_string(m.relative_error) + ")");
  return m.value;
}

json answer(const json& q) {
  if (!q.is_object()) throw Error("a query must be a JSON object");
  const std::string quantity = q.value("quantity", "");
  if (quantity == "moment") return answer_moment(q);
  throw Error(quantity.empty() ? "the query has no \"quantity\"" : "unknown quantity '" + quantity + "'");
}

int run_eval(const std::string& path) {
  std::ifstream file;
  if (!path.empty()) {
    file.open(path);
    if (!file) throw Error(path + ": cannot open file");
  }
  std::istream& in = path.empty() ? std::cin : file;
  const std::string name = path.empty() ? "stdin" : path;
  std::string line;
  for (long line_number = 1; std::getline(in, line); ++line_number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    json out;
    try {
      const json q = json::parse(line);
      out["id"] = q.is_object() && q.contains("id") ? q["id"] : json();
      try {
        out["value"] = answer(q);
      } catch (const Error& e) {
        out["error"] = e.what();
      }
    } catch (const json::parse_error& e) {
      out["id"] = nullptr;
      out["error"] = name + ":" + std::to_string(line_number) + ": invalid JSON (" + e.what() + ")";
    }
    std::cout << out.dump() << '\n';
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
      "(n,1,1).");
  eval->add_option("file", *path, "JSON Lines file (default: standard input)");
  return [path] { return run_eval(*path); };
}

}  // namespace daylit::cli
