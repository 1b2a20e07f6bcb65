// The sun's first bounce integrated over the radiosity elements (simulation/sunlit_elements.hpp):
// the basis integrals of a lit part bounded by a shadow's edge against their closed forms, and the
// flux and first moment a window's beam puts on a room against the beam's own.

#include <catch2/catch.hpp>

#include <cmath>

#include "simulation/reflected_components.hpp"
#include "simulation/sunlit_elements.hpp"
#include "test_scenes.hpp"
#include "window_room.hpp"

using namespace daylit;
using daylit::test::polygon;

namespace {

// The element (0,0,0), (1,0,0), (0,1,0), facing +z: λ_0 = 1 − x − y, λ_1 = x, λ_2 = y, A = 1/2.
RadiosityElement unit_element() { return make_element({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, 0, 0); }

// The sun 45° from the zenith towards +x: a point at height h casts its shadow h further to −x.
const Vec3 kSun = normalized(Vec3{1, 0, 1});

// A horizontal square at height 1 over x ∈ [1.5, 3] casts its shadow on x ∈ [0.5, 2] at z = 0.
Polygon roof_over_half() { return polygon({{1.5, -1, 1}, {3, -1, 1}, {3, 2, 1}, {1.5, 2, 1}}, "roof"); }

// Closed forms over the lit quadrilateral (0,0), (0.5,0), (0.5,0.5), (0,1) = {x ≤ 1/2} of the
// triangle: ∫1 = 3/8, ∫x = 1/12, ∫y = 7/48, so ∫φ_k = 2∫λ_k − (1/3)(3/8) = 1/6, 1/24, 1/6. Over the
// whole triangle each ∫φ_k is A/3 = 1/6, so over the shaded part 0, 1/8, 0.
constexpr double kLit[3] = {1.0 / 6, 1.0 / 24, 1.0 / 6};
constexpr double kShaded[3] = {0, 1.0 / 8, 0};

// The sunlit parts for kSun past `polygons` of the given transmittances (the pieces kept alongside).
struct Sunlit {
  std::vector<ConvexPiece> pieces;
  SunlitElements elements;
  Sunlit(const std::vector<Polygon>& polygons, const std::vector<double>& transmittance)
      : pieces(sun_blocker_pieces(polygons)), elements(pieces, transmittance, kSun, 1.0) {}
  std::array<double, 3> operator()(const RadiosityElement& el, const Vec3& n, std::size_t own) const {
    return elements.basis_integrals(el, n, own);
  }
};

// Each integral is a handful of area and centroid sums of O(1) numbers: roundoff of a few ulp.
constexpr double kRoundoff = 1e-14;

}  // namespace

TEST_CASE("sunlit elements: in full sun each basis function integrates to A/3") {
  const Sunlit sunlit({}, {});
  const auto b = sunlit(unit_element(), {0, 0, 1}, 0);
  for (double v : b) CHECK(v == Approx(1.0 / 6).epsilon(kRoundoff));
}

TEST_CASE("sunlit elements: a shadow's edge across the element leaves the closed forms of the lit part") {
  const RadiosityElement el = unit_element();
  SECTION("an opaque roof: the shaded part gives nothing") {
    const Sunlit sunlit({roof_over_half()}, {0.0});
    const auto b = sunlit(el, {0, 0, 1}, 99);
    for (int k = 0; k < 3; ++k) CHECK(b[std::size_t(k)] == Approx(kLit[k]).margin(kRoundoff));
  }
  SECTION("a pane of 0.4: the shaded part passes 0.4 of its light; two panes stacked, 0.4 × 0.5") {
    const Sunlit one({roof_over_half()}, {0.4});
    Polygon higher = roof_over_half();
    for (Vec3& v : higher.vertices) v = v + Vec3{1, 0, 1};  // one higher, shifted along the beam: the same shadow
    const Sunlit two({roof_over_half(), higher}, {0.4, 0.5});
    const auto b1 = one(el, {0, 0, 1}, 99);
    const auto b2 = two(el, {0, 0, 1}, 99);
    for (int k = 0; k < 3; ++k) {
      CHECK(b1[std::size_t(k)] == Approx(kLit[k] + 0.4 * kShaded[k]).margin(kRoundoff));
      CHECK(b2[std::size_t(k)] == Approx(kLit[k] + 0.2 * kShaded[k]).margin(kRoundoff));
    }
    // Part by part: the light under both came in by the higher pane (polygon 1), the rest directly.
    const std::vector<SunlitPart> parts = two.elements.parts(el, {0, 0, 1}, 99);
    REQUIRE(parts.size() == 2);
    for (const SunlitPart& part : parts) {
      const bool direct = part.outer_polygon == SunlitPart::kDirect;
      CHECK((direct || part.outer_polygon == 1));
      for (int k = 0; k < 3; ++k)
        CHECK(part.integrals[std::size_t(k)] == Approx(direct ? kLit[k] : 0.2 * kShaded[k]).margin(kRoundoff));
    }
  }
  SECTION("an open hole filters nothing but names the window the light came by") {
    const Sunlit open({roof_over_half()}, {1.0});
    const std::vector<SunlitPart> parts = open.elements.parts(el, {0, 0, 1}, 99);
    REQUIRE(parts.size() == 2);
    for (const SunlitPart& part : parts)
      for (int k = 0; k < 3; ++k)
        CHECK(part.integrals[std::size_t(k)] ==
              Approx(part.outer_polygon == SunlitPart::kDirect ? kLit[k] : kShaded[k]).margin(kRoundoff));
  }
  SECTION("what cannot cast a shadow casts none: the element's own polygon, one in its plane, one behind it") {
    const Polygon own = polygon({{-5, -5, 0}, {5, -5, 0}, {5, 5, 0}, {-5, 5, 0}}, "own floor");
    const Polygon flush = polygon({{0.2, -1, 0}, {3, -1, 0}, {3, 2, 0}, {0.2, 2, 0}}, "a neighbour in the plane");
    Polygon below = roof_over_half();
    for (Vec3& v : below.vertices) v.z = -1;
    const Sunlit sunlit({own, flush, below}, {0.0, 0.0, 0.0});
    const auto b = sunlit(el, {0, 0, 1}, 0);
    for (double v : b) CHECK(v == Approx(1.0 / 6).epsilon(kRoundoff));
    CHECK(Sunlit({roof_over_half()}, {0.0})(el, {0, 0, 1}, 0)[1] == Approx(1.0 / 6).epsilon(kRoundoff));  // polygon 0 is "own": left out
  }
  SECTION("a polygon far larger than the others (a site's ground, a canopy) is found for every element") {
    // The roof among a hundred small tiles far away and a 2 km ground below; then a 2 km canopy
    // above, which shades everything.
    std::vector<Polygon> polygons{roof_over_half(), polygon({{-1000, -1000, -1}, {1000, -1000, -1}, {1000, 1000, -1}, {-1000, 1000, -1}}, "ground")};
    for (int i = 0; i < 100; ++i) {
      const double x = 50 + 2 * (i % 10), y = 50 + 2 * (i / 10);
      polygons.push_back(polygon({{x, y, 1}, {x + 1, y, 1}, {x + 1, y + 1, 1}, {x, y + 1, 1}}, "tile"));
    }
    const Sunlit site(polygons, std::vector<double>(polygons.size(), 0.0));
    const auto b = site(el, {0, 0, 1}, 99);
    for (int k = 0; k < 3; ++k) CHECK(b[std::size_t(k)] == Approx(kLit[k]).margin(kRoundoff));
    polygons.push_back(polygon({{-1000, -1000, 5}, {1000, -1000, 5}, {1000, 1000, 5}, {-1000, 1000, 5}}, "canopy"));
    const Sunlit covered(polygons, std::vector<double>(polygons.size(), 0.0));
    for (double v : covered(el, {0, 0, 1}, 99)) CHECK(v == 0);
  }
  SECTION("the side facing away from the sun gets nothing") {
    const Sunlit sunlit({}, {});
    for (double v : sunlit(el, {0, 0, -1}, 0)) CHECK(v == 0);
  }
}

TEST_CASE("sunlit elements: a window's beam puts on a closed room exactly its flux and first moment, on any mesh") {
  // The sun due south (−y) at 45°: the 1 × 1 m window of the 2 m window room (x 0.5..1.5, z
  // 0.6..1.6) passes E_dn cos 45° · 1 m², all of which lands on the floor at x 0.5..1.5, y 0.6..1.6
  // (centroid y = 1.1). The first bounce at the nodes (radiosity_system) is the L² projection of
  // the light on each element, which keeps ∫E and ∫E·y exactly; collocated at the nodes it sampled
  // the patch (coarse mesh: 2 floor triangles, 6 nodes).
  const test::WindowRoom room;
  const VisibilityEngine engine(room.scene, GeometryMode::exact);
  const Vec3 sun = normalized(Vec3{0, -1, 1});
  const double e_dn = 1000, beam = e_dn * std::sqrt(0.5);
  for (double size : {2.0, 0.7, 0.3}) {
    ReflectionOptions o;
    o.element_size = size;
    o.ground_reflectance = 0;
    o.light = [](const SphericalRegion&, const Vec3&, const Aperture*) { return 0.0; };  // the sun alone
    o.light_horizontal = beam;
    o.sun = ReflectionOptions::Sun{sun, e_dn};
    const RadiositySystem sys = radiosity_system(room.scene, room.reflectance, engine, {}, o);
    double inside = 0, floor = 0, floor_y = 0;
    for (std::size_t u = 0; u < sys.first_bounce.size(); ++u) {
      const RadiosityElement& el = sys.mesh.elements[u / 6];
      const Vec3 n = u / 3 % 2 == 0 ? el.normal : -1.0 * el.normal;
      const Vec3 node = el.nodes[u % 3];
      if (dot(n, Vec3{1, 1, 1} - node) <= 0) continue;  // an outer side (the south wall's is in the sun)
      const double flux = el.area / 3 * sys.first_bounce[u];
      inside += flux;
      if (el.surface == 0) {
        floor += flux;
        floor_y += flux * node.y;  // ∫ φ_k y dA = (A/3) y_k: the degree-2 rule is exact for it
      }
    }
    INFO("element size " << size);
    // Area and centroid sums over a few hundred parts of O(1): roundoff well inside 1e-12.
    CHECK(inside == Approx(beam).epsilon(1e-12));
    CHECK(floor == Approx(beam).epsilon(1e-12));
    CHECK(floor_y == Approx(1.1 * beam).epsilon(1e-12));
  }
}

TEST_CASE("sunlit elements: a sun grazing the element at 1e-6 rad still leaves the closed forms (stiff)") {
  // s = (cos ε, 0, sin ε): a point at height h casts its shadow h/tan ε further to −x, so a roof at
  // height 1e-6 over x ∈ [1.5, 3] shades x ∈ [0.5, 2] up to O(ε²). The projection multiplies the
  // roof's coordinates' roundoff by 1/tan ε = 1e6 (1e-10 absolute on the shadow's edge), and the
  // edge moves by ε² relative: 1e-9 covers both.
  const double eps = 1e-6;
  const Vec3 sun{std::cos(eps), 0, std::sin(eps)};
  const Polygon roof = polygon({{1.5, -1, 1e-6}, {3, -1, 1e-6}, {3, 2, 1e-6}, {1.5, 2, 1e-6}}, "roof");
  const std::vector<ConvexPiece> pieces = sun_blocker_pieces({roof});
  const SunlitElements sunlit(pieces, {0.0}, sun, 1.0);
  const auto b = sunlit.basis_integrals(unit_element(), {0, 0, 1}, 99);
  for (int k = 0; k < 3; ++k) CHECK(b[std::size_t(k)] == Approx(kLit[k]).margin(1e-9));
  // Below 1e-9 rad the side is left out: at most 1e-9 of E_dn per unit area.
  const SunlitElements flat(pieces, {0.0}, Vec3{1, 0, 1e-12}, 1.0);
  for (double v : flat.basis_integrals(unit_element(), {0, 0, 1}, 99)) CHECK(v == 0);
}
