// One query per input line, one answer per output line, in order: {"id": …, "value": v}, or
// {"id": …, "error": "…"} for a query that cannot be answered (the run goes on). The query
// fields are those of the kernel issue: quantity "moment", region {"polygon", "origin"} or
// {"cap": {"axis", "half_angle"}}, optional "clip", "factors" [{"axis", "power"}], and
// "denominator" (rational moments: not supported yet); and quantity "sky_irradiance" (the sky
// issue: a polygon region, "normal", "sky" {"cie", "sun_zenith", "sun_azimuth", "method"?}).

#include "cli/eval_command.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <string>

#include <nlohmann/json.hpp>

#include "geometry/error.hpp"
#include "geometry/input_checks.hpp"
#include "geometry/rad_reader.hpp"
#include "illumination/cap_moment.hpp"
#include "illumination/factor_moment.hpp"
#include "illumination/hemisphere_clip.hpp"
#include "illumination/moments.hpp"
#include "sky/cie_sky.hpp"

namespace daylit::cli {

namespace {

using nlohmann::json;

// Results whose estimated error exceeds this are refused rather than reported.
constexpr double kAccuracyBound = 1e-10;

// Bounds that keep every query to about a second and bounded memory, whatever the input:
// a line is read up to kMaxLineBytes (a 10,000-vertex polygon takes about 300 kB); nesting beyond
// kMaxDepth is refused (queries need 4 levels, and the echoed "id" is copied and printed
// recursively); a polygon has at most kMaxVertices (its crossing test is quadratic); the kernels
// cost edges × power, which kMaxWork bounds (1e7: about 1.5 s on one core).
constexpr std::size_t kMaxLineBytes = std::size_t(1) << 20;
constexpr int kMaxDepth = 64;
constexpr std::size_t kMaxVertices = 10000;
constexpr double kMaxWork = 1e7;

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
  if (!(p >= 0) || p != std::floor(p) || p > 1e6) throw Error(what + " must be a non-negative integer (at most 1e6)");
  return int(p);
}

// region.polygon: at most kMaxVertices, coordinates within ±kMaxCoordinate as in the readers,
// planar within kPlanarityTolerance of its extent (the .rad reader's tolerance), and not crossing
// itself. Repeated vertices are kept (their edges have zero length and add nothing). A polygon
// whose vertices lie on a line is accepted: its region is empty and every moment is 0, as for a
// polygon seen edge-on.
std::vector<Vec3> polygon_field(const json& poly) {
  if (!poly.is_array() || poly.size() < 3) throw Error("region.polygon must have at least 3 vertices");
  if (poly.size() > kMaxVertices)
    throw Error("region.polygon has " + std::to_string(poly.size()) + " vertices, more than " + std::to_string(kMaxVertices));
  std::vector<Vec3> vertices;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const std::string what = "region.polygon[" + std::to_string(i) + "]";
    vertices.push_back(vector_field(poly[i], what));
    const Vec3& v = vertices.back();
    if (!(std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}) <= kMaxCoordinate))
      throw Error(what + " is beyond 1e12 in magnitude");
  }
  const PolygonShape shape = polygon_shape(vertices);
  if (shape.zero_area) {
    if (!vertices_collinear(vertices, kPlanarityTolerance))
      throw Error("region.polygon has zero area but its vertices are not on a line: it crosses itself");
    return vertices;
  }
  if (shape.deviation > kPlanarityTolerance * shape.extent)
    throw Error("region.polygon is not planar: a vertex lies " + std::to_string(shape.deviation) +
                " from its mean plane, more than 1e-4 of its extent " + std::to_string(shape.extent));
  if (boundary_crosses_itself(vertices, shape.normal)) throw Error("region.polygon crosses itself");
  return vertices;
}

// region {"cap": {"axis": [x,y,z], "half_angle": radians}}: the cap {u : â·u ≥ cos half_angle},
// half_angle in (0, π], with the query's optional "clip" and "factors", by the closed forms of
// cap_moment.hpp (factor patterns (), (c^n), (c^n, L^1) with a clip c; (), (L^k) without).
double answer_cap_moment(const json& q, const json& cap) {
  if (!cap.is_object() || !cap.contains("axis") || !cap.contains("half_angle"))
    throw Error("region.cap must be {\"axis\": [x,y,z], \"half_angle\": radians}");
  const Vec3 axis = vector_field(cap["axis"], "region.cap.axis");
  if (!(norm(axis) > 0)) throw Error("region.cap.axis must be non-zero");
  const json& h = cap["half_angle"];
  if (!h.is_number() || !(h.get<double>() > 0 && h.get<double>() <= M_PI))
    throw Error("region.cap.half_angle must be a number in (0, pi] (radians)");
  std::optional<Vec3> clip;
  if (q.contains("clip")) clip = vector_field(q["clip"], "clip");
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
  return cap_moment(axis, h.get<double>(), clip, factors);
}

double answer_moment(const json& q) {
  if (!q.contains("region") || !q["region"].is_object()) throw Error("a moment query needs a \"region\" object");
  const json& r = q["region"];
  SphericalRegion region;
  if (r.contains("polygon")) {
    const std::vector<Vec3> vertices = polygon_field(r["polygon"]);
    if (!r.contains("origin")) throw Error("region.polygon needs region.origin");
    const Vec3 origin = vector_field(r["origin"], "region.origin");
    if (!(std::max({std::abs(origin.x), std::abs(origin.y), std::abs(origin.z)}) <= kMaxCoordinate))
      throw Error("region.origin is beyond 1e12 in magnitude");
    region = directions_through(vertices, origin);
  } else if (r.contains("cap")) {
    return answer_cap_moment(q, r["cap"]);
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
  double edges = 0, powers = 1;
  for (const auto& loop : region.loops) edges += double(loop.size());
  for (const Factor& f : factors) powers += f.power;
  if (edges * powers > kMaxWork)
    throw Error("edges × powers = " + std::to_string(edges * powers) + " exceeds 1e7: the query would take too long");
  const FactorMoment m = factor_moment(region, factors);
  if (!(m.relative_error <= kAccuracyBound))
    throw Error("the edge terms cancel beyond what __float128 carries (estimated relative error " +
                std::to_string(m.relative_error) + ")");
  return m.value;
}

// {"quantity": "sky_irradiance", "region": R, "normal": n, "sky": {"cie": 1..15, "sun_zenith": deg,
// "sun_azimuth": deg, "method": "quadrature"|"fit"}}: E/L_z over the part of R above the horizon and
// in front of n (x east, y north, z up; azimuth clockwise from north). R is a polygon seen from an
// origin or a cap {"axis", "half_angle"}. Polygons: type 5 is uniform and exact; the others by
// adaptive quadrature of ISO 15469's formula to 1e-12 (the reference, the default) or by the
// closed-form moments of the fitted luminance (fast; its error is the fit's). Caps: nested
// adaptive quadrature to 1e-12 (cie_sky_irradiance_over_cap).
json answer_sky_irradiance(const json& q) {
  if (!q.contains("region") || !q["region"].is_object()) throw Error("a sky_irradiance query needs a \"region\" object");
  const json& r = q["region"];
  if (!r.contains("cap") && (!r.contains("polygon") || !r.contains("origin")))
    throw Error("region must be {\"polygon\": [...], \"origin\": [...]} or {\"cap\": {\"axis\": [...], \"half_angle\": radians}}");
  const Vec3 n = vector_field(q.value("normal", json()), "normal");
  if (!(norm(n) > 0)) throw Error("normal must be non-zero");
  const json& sky = q.value("sky", json());
  if (!sky.is_object() || !sky.contains("cie") || !sky.contains("sun_zenith") || !sky.contains("sun_azimuth"))
    throw Error("sky must be {\"cie\": 1..15, \"sun_zenith\": deg, \"sun_azimuth\": deg}");
  if (!sky["cie"].is_number_integer()) throw Error("sky.cie must be an integer 1..15");
  if (!sky["sun_zenith"].is_number() || !sky["sun_azimuth"].is_number()) throw Error("sky.sun_zenith and sky.sun_azimuth must be numbers");
  const CieSky cie(sky["cie"].get<int>(), sun_direction(sky["sun_zenith"].get<double>(), sky["sun_azimuth"].get<double>()));
  const std::string method = sky.value("method", "quadrature");
  if (r.contains("cap")) {
    const json& cap = r["cap"];
    if (!cap.is_object() || !cap.contains("axis") || !cap.contains("half_angle"))
      throw Error("region.cap must be {\"axis\": [x,y,z], \"half_angle\": radians}");
    const Vec3 axis = vector_field(cap["axis"], "region.cap.axis");
    if (!(norm(axis) > 0)) throw Error("region.cap.axis must be non-zero");
    const json& h = cap["half_angle"];
    if (!h.is_number() || !(h.get<double>() > 0 && h.get<double>() <= M_PI))
      throw Error("region.cap.half_angle must be a number in (0, pi] (radians)");
    if (method != "quadrature")
      throw Error("sky.method \"fit\" has no closed form over caps (its terms are moments about three axes); use quadrature");
    return cie_sky_irradiance_over_cap(cie, axis, h.get<double>(), normalized(n), 1e-12).value;
  }
  const json& poly = r["polygon"];
  if (!poly.is_array() || poly.size() < 3) throw Error("region.polygon must have at least 3 vertices");
  std::vector<Vec3> vertices;
  for (std::size_t i = 0; i < poly.size(); ++i) vertices.push_back(vector_field(poly[i], "region.polygon[" + std::to_string(i) + "]"));
  const SphericalRegion region =
      above_horizon_and_in_front(directions_through(vertices, vector_field(r["origin"], "region.origin")), normalized(n));
  if (method == "fit") return cie_sky_irradiance(fit_cie_sky(cie), cie.sun, region, normalized(n));
  if (method != "quadrature") throw Error("sky.method must be \"quadrature\" or \"fit\"");
  if (cie.type == 5) return lambert(region, normalized(n));  // uniform: L = L_z exactly
  return cie_sky_irradiance_quadrature(cie, region, normalized(n), 1e-12).value;
}

json answer(const json& q) {
  if (!q.is_object()) throw Error("a query must be a JSON object");
  const std::string quantity = q.value("quantity", "");
  if (quantity == "moment") return answer_moment(q);
  if (quantity == "sky_irradiance") return answer_sky_irradiance(q);
  throw Error(quantity.empty() ? "the query has no \"quantity\"" : "unknown quantity '" + quantity + "'");
}

// A message from the JSON library, which may quote kilobytes of the input: the start of it.
std::string shortened(const std::string& message) {
  return message.size() <= 200 ? message : message.substr(0, 200) + "...";
}

// Reads one line (without its '\n'); false at the end of the input. A line longer than
// kMaxLineBytes is read to its end, but only that much of it is kept, and `too_long` is set.
bool read_bounded_line(std::istream& in, std::string& line, bool& too_long) {
  line.clear();
  too_long = false;
  bool any = false;
  std::streambuf* buffer = in.rdbuf();
  for (int c; (c = buffer->sbumpc()) != std::char_traits<char>::eof();) {
    any = true;
    if (c == '\n') return true;
    if (line.size() < kMaxLineBytes)
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
      std::cout << json{{"id", nullptr}, {"error", where + ": line longer than " + std::to_string(kMaxLineBytes) + " bytes"}}.dump()
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

std::string answer_line(const std::string& line, const std::string& where) {
  json out;
  out["id"] = nullptr;
  try {
    const json q = json::parse(line, [&](int depth, json::parse_event_t, json&) {
      if (depth > kMaxDepth) throw Error("nested deeper than " + std::to_string(kMaxDepth) + " levels");
      return true;
    });
    if (q.is_object() && q.contains("id")) out["id"] = q["id"];
    try {
      out["value"] = answer(q);
    } catch (const Error& e) {
      out["error"] = e.what();
    } catch (const json::exception& e) {  // a field of another type than the query needs
      out["error"] = "a field has the wrong type (" + shortened(e.what()) + ")";
    }
  } catch (const json::exception& e) {  // syntax, invalid UTF-8, or a number beyond double
    out["error"] = where + ": invalid JSON (" + shortened(e.what()) + ")";
  } catch (const Error& e) {
    out["error"] = where + ": invalid query (" + std::string(e.what()) + ")";
  }
  // Messages may quote invalid UTF-8 from the input: replaced, never an exception.
  return out.dump(-1, ' ', false, json::error_handler_t::replace);
}

std::function<int()> add_eval_command(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  CLI::App* eval = app.add_subcommand("eval", "Evaluate kernel queries given as JSON Lines (closed forms)");
  eval->description(
      "Reads one JSON query per line (from FILE, or standard input) and writes one JSON answer per line:\n"
      "{\"id\": ..., \"value\": v} or {\"id\": ..., \"error\": \"...\"}. Supported now: quantity \"moment\" on\n"
      "polygon regions seen from an origin, with an optional clip hemisphere and factor patterns (), (n), (n,1),\n"
      "(n,1,1); and on cap regions {\"cap\": {\"axis\", \"half_angle\"}} with patterns (), (c^n), (c^n, L^1).");
  eval->add_option("file", *path, "JSON Lines file (default: standard input)");
  return [path] { return run_eval(*path); };
}

}  // namespace daylit::cli
