// One query per input line, one answer per output line, in order: {"id": …, "value": v}, or
// {"id": …, "error": "…"} for a query that cannot be answered (the run goes on). The query
// fields are those of the kernel issue: quantity "moment", region {"polygon", "origin"} or
// {"cap": {"axis", "half_angle"}}, optional "clip", "factors" [{"axis", "power"}], and
// "denominator" {"axis", "power": 0, 1 or 2} (rational moments ∫ Π (a_k·u)^{p_k} / (d·u)^q dσ over
// polygon regions strictly on one side of d·u = 0); and quantity "sky_irradiance" (the sky
// issue: a polygon region, "normal", "sky" {"cie", "sun_zenith", "sun_azimuth", "method"?}); and
// quantity "irradiance" (the gradient issue: a luminaire polygon of uniform or polynomial exitance
// behind optional occluders, seen from "origin" with "normal", and with "gradient": true its
// derivative with respect to the origin).

#include "simulation/eval_queries.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "geometry/error.hpp"
#include "geometry/input_checks.hpp"
#include "geometry/rad_reader.hpp"
#include "geometry/visibility.hpp"
#include "illumination/cap_moment.hpp"
#include "illumination/factor_moment.hpp"
#include "illumination/hemisphere_clip.hpp"
#include "illumination/irradiance_gradient.hpp"
#include "illumination/moments.hpp"
#include "illumination/rational_moments.hpp"
#include "sky/cie_sky.hpp"

namespace daylit {

namespace {

using nlohmann::json;

// Results whose estimated error exceeds this are refused rather than reported.
constexpr double kAccuracyBound = 1e-10;

// Bounds that keep every query to about a second and bounded memory, whatever the input:
// (`daylit eval` reads a line up to kMaxEvalLineBytes, eval_queries.hpp); nesting beyond
// kMaxDepth is refused (queries need 4 levels, and the echoed "id" is copied and printed
// recursively); a polygon has at most kMaxVertices (its crossing test is quadratic); the kernels
// cost edges × power, which kMaxWork bounds (1e7: about 1.5 s on one core).
constexpr int kMaxDepth = 64;
constexpr std::size_t kMaxVertices = 10000;
// An irradiance query clips every convex piece of the luminaire against every piece of the
// occluders exactly: at most kMaxOccluders occluders, kMaxVertices vertices in all, and luminaire
// vertices × occluder vertices at most kMaxClipWork (measured: star-shaped polygons of 1000
// vertices each, 1e6, take 7 s; 1000 quadrilaterals before a quadrilateral, 1.6e4, take 1 s).
constexpr std::size_t kMaxOccluders = 1000;
constexpr double kMaxClipWork = 2e5;
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
std::vector<Vec3> polygon_field(const json& poly, const std::string& name = "region.polygon") {
  if (!poly.is_array() || poly.size() < 3) throw Error(name + " must have at least 3 vertices");
  if (poly.size() > kMaxVertices)
    throw Error(name + " has " + std::to_string(poly.size()) + " vertices, more than " + std::to_string(kMaxVertices));
  std::vector<Vec3> vertices;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const std::string what = name + "[" + std::to_string(i) + "]";
    vertices.push_back(vector_field(poly[i], what));
    const Vec3& v = vertices.back();
    if (!(std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}) <= kMaxCoordinate))
      throw Error(what + " is beyond 1e12 in magnitude");
  }
  const PolygonShape shape = polygon_shape(vertices);
  if (shape.zero_area) {
    if (!vertices_collinear(vertices, kPlanarityTolerance))
      throw Error(name + " has zero area but its vertices are not on a line: it crosses itself");
    return vertices;
  }
  if (shape.deviation > kPlanarityTolerance * shape.extent)
    throw Error(name + " is not planar: a vertex lies " + std::to_string(shape.deviation) +
                " from its mean plane, more than 1e-4 of its extent " + std::to_string(shape.extent));
  if (boundary_crosses_itself(vertices, shape.normal)) throw Error(name + " crosses itself");
  return vertices;
}

// region.cap {"axis": [x,y,z], "half_angle": radians}: a non-zero axis and a half-angle in (0, π].
struct CapRegion {
  Vec3 axis;
  double half_angle;
};
CapRegion cap_field(const json& cap) {
  if (!cap.is_object() || !cap.contains("axis") || !cap.contains("half_angle"))
    throw Error("region.cap must be {\"axis\": [x,y,z], \"half_angle\": radians}");
  const Vec3 axis = vector_field(cap["axis"], "region.cap.axis");
  if (!(norm(axis) > 0)) throw Error("region.cap.axis must be non-zero");
  const json& h = cap["half_angle"];
  if (!h.is_number() || !(h.get<double>() > 0 && h.get<double>() <= M_PI))
    throw Error("region.cap.half_angle must be a number in (0, pi] (radians)");
  return {axis, h.get<double>()};
}

// The query's optional "factors": [{"axis": [x,y,z], "power": p}, …].
std::vector<Factor> factors_field(const json& q) {
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
  return factors;
}

// region {"cap": {"axis": [x,y,z], "half_angle": radians}}: the cap {u : â·u ≥ cos half_angle},
// half_angle in (0, π], with the query's optional "clip" and "factors", by the closed forms of
// cap_moment.hpp (factor patterns (), (c^n), (c^n, L^1) with a clip c; (), (L^k) without).
double answer_cap_moment(const json& q, const json& cap) {
  const CapRegion c = cap_field(cap);
  std::optional<Vec3> clip;
  if (q.contains("clip")) clip = vector_field(q["clip"], "clip");
  if (q.contains("denominator")) {
    const json& d = q["denominator"];
    if (!d.is_object() || !d.contains("power")) throw Error("denominator must be {\"axis\": [x,y,z], \"power\": q}");
    if (power_field(d["power"], "denominator.power") > 0)
      throw Error("rational moments (a denominator with power > 0) are answered on polygon regions only");
  }
  return cap_moment(c.axis, c.half_angle, clip, factors_field(q));
}

// ∫_A Π_k (a_k·u)^{p_k} / (d·u)^q dσ for q = 1 or 2 over a polygon region (rational_moments.hpp):
// the region must lie strictly on one side of d·u = 0 (else the integral diverges); on the
// negative side the moment is (−1)^q that about −d. Patterns of total degree ≤ 12 go through the
// frame recurrences (any q); (n), (n,1), (n,1,1) with q = 1 and higher n through the
// linearly-varying paper's eqs. 11–13, O(n²) per edge, at most kMaxWork·10 for edges × n².
double answer_rational_moment(const SphericalRegion& region, std::vector<Factor> factors, const Vec3& d, int q) {
  std::erase_if(factors, [](const Factor& f) { return f.power == 0; });
  std::sort(factors.begin(), factors.end(), [](const Factor& a, const Factor& b) { return a.power > b.power; });
  for (const Factor& f : factors)
    if (!(norm(f.axis) > 0)) throw Error("a factor axis must be a non-zero vector");
  if (region.empty()) return 0;
  bool positive = false, negative = false;
  double edges = 0;
  for (const auto& loop : region.loops) {
    edges += double(loop.size());
    for (const Vec3& v : loop) {
      const double side = dot(d, v);
      positive |= side > 0;
      negative |= side < 0;
      if (side == 0 || (positive && negative))
        throw Error("the region must lie strictly on one side of the plane denominator.axis·u = 0: there the "
                    "integral diverges");
    }
  }
  const Vec3 w = positive ? d : -1.0 * d;
  const double sign = positive || q % 2 == 0 ? 1.0 : -1.0;
  int degree = 0;
  for (const Factor& f : factors) degree += f.power;
  RationalMoment m{};
  if (degree <= kMaxFrameMomentDegree) {
    m = rational_moment(region, factors, w, q);
  } else if (q == 1 && (factors.size() == 1 || (factors.size() <= 3 && factors[1].power == 1 &&
                                                (factors.size() == 2 || factors[2].power == 1)))) {
    const int n = factors[0].power;
    // The per-edge table of G(r, t) holds (n + 2)(n + 5) entries: 64 MB in __float128 at n = 2000.
    if (n > 2000) throw Error("rational moments are answered up to power 2000 in the numerator");
    if (edges * double(n + 1) * double(n + 1) > 10 * kMaxWork)
      throw Error("edges × power² = " + std::to_string(edges * double(n + 1) * double(n + 1)) +
                  " exceeds 1e8: the rational moment would take too long");
    const Vec3& v = factors[0].axis;
    m = factors.size() == 1   ? rational_moment_n(region, v, n, w)
        : factors.size() == 2 ? rational_moment_n1(region, v, n, factors[1].axis, w)
                              : rational_moment_n11(region, v, n, factors[1].axis, factors[2].axis, w);
  } else {
    throw Error("rational moments are answered for numerators of total degree ≤ 12 (denominator power 1 or 2) "
                "and for the patterns (n), (n,1), (n,1,1) with denominator power 1");
  }
  if (!std::isfinite(m.value)) throw Error("the rational moment overflows double");
  if (!(m.relative_error <= kAccuracyBound))
    throw Error("the rational moment's terms cancel beyond what __float128 carries (estimated relative error " +
                std::to_string(m.relative_error) + ")");
  return sign * m.value;
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
  int denominator_power = 0;
  Vec3 denominator_axis;
  if (q.contains("denominator")) {
    const json& d = q["denominator"];
    if (!d.is_object() || !d.contains("power")) throw Error("denominator must be {\"axis\": [x,y,z], \"power\": q}");
    denominator_power = power_field(d["power"], "denominator.power");
    if (denominator_power > 2) throw Error("denominator.power must be 0, 1 or 2");
    if (denominator_power > 0) {
      if (!d.contains("axis")) throw Error("denominator.axis is needed when denominator.power > 0");
      denominator_axis = vector_field(d["axis"], "denominator.axis");
      if (!(norm(denominator_axis) > 0)) throw Error("denominator.axis must be non-zero");
    }
  }
  std::vector<Factor> factors = factors_field(q);
  double edges = 0, powers = 1;
  for (const auto& loop : region.loops) edges += double(loop.size());
  for (const Factor& f : factors) powers += f.power;
  if (edges * powers > kMaxWork)
    throw Error("edges × powers = " + std::to_string(edges * powers) + " exceeds 1e7: the query would take too long");
  if (denominator_power > 0) return answer_rational_moment(region, factors, denominator_axis, denominator_power);
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
    const CapRegion c = cap_field(r["cap"]);
    if (method != "quadrature")
      throw Error("sky.method \"fit\" has no closed form over caps (its terms are moments about three axes); use quadrature");
    return cie_sky_irradiance_over_cap(cie, c.axis, c.half_angle, normalized(n), 1e-12).value;
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

// "exitance": {"uniform": M} or {"polynomial": [{"coef": c, "powers": [i, j, k]}, …]}.
ExitancePolynomial exitance_field(const json& x) {
  if (!x.is_object() || x.size() != 1 || !(x.contains("uniform") || x.contains("polynomial")))
    throw Error("exitance must be {\"uniform\": M} or {\"polynomial\": [{\"coef\": c, \"powers\": [i, j, k]}, ...]}");
  if (x.contains("uniform")) {
    if (!x["uniform"].is_number() || !std::isfinite(x["uniform"].get<double>())) throw Error("exitance.uniform must be a finite number");
    return {{x["uniform"].get<double>(), 0, 0, 0}};
  }
  const json& terms = x["polynomial"];
  if (!terms.is_array() || terms.empty()) throw Error("exitance.polynomial must be a non-empty array of terms");
  if (terms.size() > kMaxVertices) throw Error("exitance.polynomial has more than " + std::to_string(kMaxVertices) + " terms");
  ExitancePolynomial M;
  for (std::size_t t = 0; t < terms.size(); ++t) {
    const std::string where = "exitance.polynomial[" + std::to_string(t) + "]";
    const json& term = terms[t];
    if (!term.is_object() || !term.contains("coef") || !term.contains("powers") || !term["powers"].is_array() ||
        term["powers"].size() != 3)
      throw Error(where + " must be {\"coef\": c, \"powers\": [i, j, k]}");
    if (!term["coef"].is_number() || !std::isfinite(term["coef"].get<double>())) throw Error(where + ".coef must be a finite number");
    int powers[3];
    for (int a = 0; a < 3; ++a) {
      powers[a] = power_field(term["powers"][a], where + ".powers[" + std::to_string(a) + "]");
      if (powers[a] > kMaxExitanceDegree) throw Error(where + ": degree above " + std::to_string(kMaxExitanceDegree));
    }
    if (powers[0] + powers[1] + powers[2] > kMaxExitanceDegree)
      throw Error(where + ": total degree above " + std::to_string(kMaxExitanceDegree));
    M.push_back({term["coef"].get<double>(), powers[0], powers[1], powers[2]});
  }
  return M;
}

// {"quantity": "irradiance", "luminaire": polygon, "origin", "normal", "exitance": X,
// "occluders": [polygon, …]?, "gradient": true?}: E = ∫ M(x) cosθ_r cosθ_l /(π r²) dA over the
// part of the luminaire seen from origin in front of its tangent plane (either face of the
// luminaire; no horizon cut), occluders clipped exactly (geometry/visibility.hpp), and with
// "gradient" ∇E with respect to origin, the normal fixed (Arvo 1994 with occluder edges;
// illumination/irradiance_gradient.hpp).
json answer_irradiance(const json& q) {
  if (!q.contains("luminaire")) throw Error("an irradiance query needs a \"luminaire\" polygon");
  const std::vector<Vec3> luminaire = polygon_field(q["luminaire"], "luminaire");
  if (!q.contains("origin")) throw Error("an irradiance query needs an \"origin\"");
  const Vec3 origin = vector_field(q["origin"], "origin");
  if (!(std::max({std::abs(origin.x), std::abs(origin.y), std::abs(origin.z)}) <= kMaxCoordinate))
    throw Error("origin is beyond 1e12 in magnitude");
  const Vec3 normal = vector_field(q.value("normal", json()), "normal");
  if (!(norm(normal) > 0)) throw Error("normal must be non-zero");
  const Vec3 n = normalized(normal);
  if (!q.contains("exitance")) throw Error("an irradiance query needs an \"exitance\"");
  const ExitancePolynomial exitance = exitance_field(q["exitance"]);
  bool gradient = false;
  if (q.contains("gradient")) {
    if (!q["gradient"].is_boolean()) throw Error("gradient must be true or false");
    gradient = q["gradient"].get<bool>();
  }
  Scene scene;
  std::size_t vertices = luminaire.size();
  const auto as_polygon = [](std::vector<Vec3> v, const std::string& name) {
    Polygon p;
    p.vertices = std::move(v);
    p.name = name;
    p.where = {name, 0};
    return p;
  };
  if (q.contains("occluders")) {
    const json& os = q["occluders"];
    if (!os.is_array()) throw Error("occluders must be an array of polygons");
    if (os.size() > kMaxOccluders) throw Error("more than " + std::to_string(kMaxOccluders) + " occluders");
    for (std::size_t i = 0; i < os.size(); ++i) {
      const std::string name = "occluders[" + std::to_string(i) + "]";
      std::vector<Vec3> v = polygon_field(os[i], name);
      vertices += v.size();
      if (vertices > kMaxVertices) throw Error("more than " + std::to_string(kMaxVertices) + " vertices in all");
      // Collinear vertices: a polygon with no area, which hides nothing.
      if (polygon_shape(v).zero_area) continue;
      scene.occluders.push_back(as_polygon(std::move(v), name));
    }
  }
  const double work = double(luminaire.size()) * double(vertices - luminaire.size());
  if (work > kMaxClipWork)
    throw Error("luminaire vertices × occluder vertices = " + std::to_string(std::llround(work)) +
                " exceeds 2e5: the query would take too long");
  json out;
  // A luminaire with no area gives nothing, and so does everything nearby.
  if (polygon_shape(luminaire).zero_area) {
    out["value"] = 0.0;
    if (gradient) out["gradient"] = {0.0, 0.0, 0.0};
    return out;
  }
  scene.apertures.push_back({as_polygon(luminaire, "luminaire"), 1.0});
  const VisibilityEngine engine(scene, GeometryMode::exact);
  VisibilityOptions options;
  options.clip_to_horizon = false;
  options.edge_sources = gradient;
  VisibilityCounters counters;
  const SphericalRegion region = engine.visible_region(origin, n, 0, counters, options);
  if (region.empty()) {
    // Nothing seen: E = 0, and so is its gradient, except where the origin lies in the
    // luminaire's plane (seen edge-on): E grows like the distance to the plane on either side
    // there, and has no gradient.
    const Vec3 N = newell_normal(luminaire), d = origin - luminaire[0];
    if (gradient && std::abs(dot(N, d)) <= 1e-14 * norm(N) * norm(d))
      throw Error("the origin lies in the luminaire's plane: E has no gradient there");
    out["value"] = 0.0;
    if (gradient) out["gradient"] = {0.0, 0.0, 0.0};
    return out;
  }
  double value = 0, relative_error = 0;
  Vec3 g{};
  if (exitance.size() == 1 && exitance[0].i + exitance[0].j + exitance[0].k == 0) {
    // Uniform: Lambert's formula, and the boundary term of the gradient in closed form.
    const double M = exitance[0].coef;
    const Escalated<double> E = lambert_with_accuracy(region, n);
    value = M * E.value / M_PI;
    relative_error = E.relative_error;
    if (gradient) {
      DirectionalRadiance L;
      L.alpha = M / M_PI;
      const IrradianceGradient G = directional_irradiance_gradient(region, origin, n, L);
      g = G.value;
      relative_error = std::max(relative_error, G.relative_error);
    }
  } else if (gradient) {
    const LuminaireGradient G = polynomial_luminaire_gradient(region, origin, n, luminaire[0], newell_normal(luminaire), exitance);
    value = G.value;
    g = G.gradient;
    relative_error = G.relative_error;
  } else {
    const LuminaireIrradiance E = polynomial_luminaire_irradiance(region, origin, n, luminaire[0], newell_normal(luminaire), exitance);
    value = E.value;
    relative_error = E.relative_error;
  }
  if (!std::isfinite(value) || !is_finite(g)) throw Error("the irradiance or its gradient overflows double");
  if (!(relative_error <= kAccuracyBound))
    throw Error("the edge terms cancel beyond what __float128 carries (estimated relative error " +
                std::to_string(relative_error) + ")");
  out["value"] = value;
  if (gradient) out["gradient"] = {g.x, g.y, g.z};
  return out;
}

// The fields of the answer: {"value": v}, and for some queries more.
json answer(const json& q) {
  if (!q.is_object()) throw Error("a query must be a JSON object");
  const std::string quantity = q.value("quantity", "");
  if (quantity == "moment") return {{"value", answer_moment(q)}};
  if (quantity == "sky_irradiance") return {{"value", answer_sky_irradiance(q)}};
  if (quantity == "irradiance") return answer_irradiance(q);
  throw Error(quantity.empty() ? "the query has no \"quantity\"" : "unknown quantity '" + quantity + "'");
}

// A message from the JSON library, which may quote kilobytes of the input: the start of it.
std::string shortened(const std::string& message) {
  return message.size() <= 200 ? message : message.substr(0, 200) + "...";
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
      const json fields = answer(q);  // named: a temporary in the range-init would dangle
      for (const auto& [key, value] : fields.items()) out[key] = value;
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

}  // namespace daylit
