#pragma once
// Scenes for the reflected components with exact answers, and the 4 × 5 × 3 m side-lit room: what
// `daylit bench reflections` measures the path tracer (and, once it lands, the radiosity) on, and
// what tests/bench/test_path_tracer.cpp holds the path tracer to.
//
// The exact values use Howell's configuration factor from a point to a parallel rectangle (DESIGN.md
// §9, checked there against Lambert's formula to 1e-16), integrated where needed by composite
// Gauss–Legendre quadrature in long double over a floor's area: nothing of the path tracer, of the
// visibility engine or of the kernels. Header-only, as stiff_scenes.hpp is, so that the CLI and the
// tests both include it.

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "bench/stiff_scenes.hpp"
#include "geometry/scene.hpp"
#include "geometry/sensor_grid.hpp"
#include "sky/sky_model.hpp"

namespace daylit::reflection_cases {

// A grey Radiance plastic of reflectance ρ (spec 0): surface_reflectance gives ρ back, the
// luminance weights summing to 1.
inline Material grey_plastic(const std::string& name, double rho) {
  return Material{name, "plastic", {}, {rho, rho, rho, 0, 0}, {}};
}

// The rectangle corner, corner + u, corner + u + v, corner + v (normal u × v).
inline Polygon rectangle(const Vec3& corner, const Vec3& u, const Vec3& v, const std::string& material,
                         const std::string& name) {
  return Polygon{{corner, corner + u, corner + u + v, corner + v}, name, material, {}};
}

// Howell's factor from an element at the origin (normal +z) to the rectangle z = c, x ∈ [0, a],
// y ∈ [0, b], as a function of A = a/c and B = b/c (DESIGN.md §9). Odd in A and in B, so that
// signed sums of it give any rectangle parallel to the element.
inline long double howell_corner(long double A, long double B) {
  const long double sa = std::sqrt(1 + A * A), sb = std::sqrt(1 + B * B);
  return (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2 * std::numbers::pi_v<long double>);
}

// Factor from an element at (x, y), normal towards the plane at distance c, to the rectangle
// [x0, x1] × [y0, y1] in that plane.
inline long double parallel_rectangle_factor(long double x, long double y, long double c, long double x0,
                                             long double x1, long double y0, long double y1) {
  return howell_corner((x1 - x) / c, (y1 - y) / c) - howell_corner((x0 - x) / c, (y1 - y) / c) -
         howell_corner((x1 - x) / c, (y0 - y) / c) + howell_corner((x0 - x) / c, (y0 - y) / c);
}

// ∫∫ f over [x0, x1] × [y0, y1]: 20-point Gauss–Legendre on a panels × panels grid.
template <class F>
long double rectangle_integral(const F& f, long double x0, long double x1, long double y0, long double y1, int panels) {
  long double sum = 0;
  for (int i = 0; i < panels; ++i) {
    const long double a = x0 + (x1 - x0) * i / panels, b = x0 + (x1 - x0) * (i + 1) / panels;
    for (int j = 0; j < panels; ++j) {
      const long double c = y0 + (y1 - y0) * j / panels, d = y0 + (y1 - y0) * (j + 1) / panels;
      sum += stiff::detail::gauss_legendre([&](long double x) {
        return stiff::detail::gauss_legendre([&](long double y) { return f(x, y); }, c, d);
      }, a, b);
    }
  }
  return sum;
}

// A scene, its sensors, and the exact components (percent) where they are known.
struct ReflectionCase {
  std::string name;
  std::string description;
  Scene scene;
  std::vector<Sensor> sensors;
  SkyModel sky = SkyModel::uniform;
  double ground_reflectance = 0.2;
  bool exact = false;  // whether the fields below hold closed forms (else they are empty)
  std::vector<double> sc, erc, irc;
};

// A square plate (two-sided, ρ = 0.6) of side 2 m, 1 m above a horizontal sensor plane, alone under
// the uniform sky over the far ground (ρ_g = 0.2); sensors facing up under its centre, its edge and
// beside it. The plate's underside sees only the far ground, of luminance ρ_g·E_out/π, so its
// exitance is uniform, ρ·ρ_g·E_out; what it reflects down meets no surface again. Hence, with F
// Howell's factor from the sensor to the plate: SC = 100 (1 − F), ERC = 0, IRC = 100 ρ ρ_g F, all
// at the first bounce, and every later bounce exactly 0.
inline ReflectionCase canopy_case() {
  ReflectionCase c;
  c.name = "canopy";
  c.description = "2 m plate 1 m above upward sensors, uniform sky, far ground 0.2: IRC = 100 rho rho_g F";
  const double rho = 0.6, side = 2, height = 1;
  c.scene.materials["plate"] = grey_plastic("plate", rho);
  c.scene.occluders.push_back(rectangle({-side / 2, -side / 2, height}, {side, 0, 0}, {0, side, 0}, "plate", "plate"));
  c.exact = true;
  for (const double x : {0.0, 0.5, 1.0, 1.7}) {
    c.sensors.push_back({{x, 0.25 * x, 0}, {0, 0, 1}});
    const double f = double(parallel_rectangle_factor(x, 0.25 * x, height, -side / 2, side / 2, -side / 2, side / 2));
    c.sc.push_back(100 * (1 - f));
    c.erc.push_back(0);
    c.irc.push_back(100 * rho * c.ground_reflectance * f);
  }
  return c;
}

// A 4 × 5 × 3 m box whose whole ceiling is an opening (transmittance 1), black walls, a floor of
// ρ_f = 0.5, under the uniform sky of luminance 1 (E_out = π). The floor sees through the opening
// the sky only, so E_floor(x) = π·F(x → opening) (Howell); what the floor reflects meets black
// walls or leaves, and nothing lights the floor again. A sensor facing down at height h sees the
// floor and black walls: IRC = (100/π)·(ρ_f/π)·∫_floor π F(x) cos cos / r² dA
// = (100 ρ_f/π) ∫ F(x) h²/r⁴ dA, by quadrature (20-point Gauss–Legendre on 8 × 8 panels: the
// integrand is smooth, h ≥ 1 m); first bounce only. A sensor facing up sees the opening and black
// walls: SC = 100·F(p → opening), IRC = ERC = 0.
inline ReflectionCase open_ceiling_box_case() {
  ReflectionCase c;
  c.name = "open_ceiling_box";
  c.description = "4x5x3 m box, ceiling open, walls black, floor 0.5, uniform sky: IRC by Howell's F over the floor";
  const double W = 4, D = 5, H = 3, rho = 0.5;
  c.scene.materials["floor"] = grey_plastic("floor", rho);
  c.scene.materials["black"] = grey_plastic("black", 0);
  c.scene.occluders = {rectangle({0, 0, 0}, {W, 0, 0}, {0, D, 0}, "floor", "floor"),
                       rectangle({0, 0, 0}, {0, 0, H}, {W, 0, 0}, "black", "south"),
                       rectangle({0, D, 0}, {W, 0, 0}, {0, 0, H}, "black", "north"),
                       rectangle({0, 0, 0}, {0, D, 0}, {0, 0, H}, "black", "west"),
                       rectangle({W, 0, 0}, {0, 0, H}, {0, D, 0}, "black", "east")};
  Aperture opening;
  opening.polygon = rectangle({0, 0, H}, {0, D, 0}, {W, 0, 0}, "void", "opening");  // normal −z, into the box
  c.scene.apertures.push_back(opening);
  c.exact = true;
  const auto floor_factor = [&](long double x, long double y) { return parallel_rectangle_factor(x, y, H, 0, W, 0, D); };
  for (const Vec3 p : {Vec3{2, 2.5, 1.5}, Vec3{1, 1, 1.0}, Vec3{3, 4, 2.2}}) {
    c.sensors.push_back({p, {0, 0, -1}});
    const long double h = p.z;
    const long double integral = rectangle_integral([&](long double x, long double y) {
      const long double r2 = (x - p.x) * (x - p.x) + (y - p.y) * (y - p.y) + h * h;
      return floor_factor(x, y) * h * h / (r2 * r2);
    }, 0, W, 0, D, 8);
    c.sc.push_back(0);
    c.erc.push_back(0);
    c.irc.push_back(double(100 * rho * integral / std::numbers::pi_v<long double>));
  }
  for (const Vec3 p : {Vec3{2, 2.5, 0.85}, Vec3{0.5, 4.2, 2.0}}) {
    c.sensors.push_back({p, {0, 0, 1}});
    c.sc.push_back(double(100 * parallel_rectangle_factor(p.x, p.y, H - p.z, 0, W, 0, D)));
    c.erc.push_back(0);
    c.irc.push_back(0);
  }
  return c;
}

// The 4 × 5 × 3 m side-lit room of DESIGN.md §4 (x 0..4, y 0..5, z 0..3), its window an opening
// (transmittance 1) of 2 × 1.5 m in the south wall (y = 0, x 1..3, z 0.9..2.4), floor 0.2, walls
// 0.5, ceiling 0.7, far ground 0.2, no exterior obstruction or ground surface, the CIE overcast
// sky; walls of zero thickness. 80 upward sensors at 0.85 m on a 0.5 m grid (x 0.25..3.75,
// y 0.25..4.75). No closed form: the bench's reference is a long path-traced run.
inline ReflectionCase side_lit_room_case() {
  ReflectionCase c;
  c.name = "room_4x5x3";
  c.description = "4x5x3 m room, 2x1.5 m opening, floor 0.2, walls 0.5, ceiling 0.7, ground 0.2, CIE overcast";
  c.sky = SkyModel::cie_overcast;
  const double W = 4, D = 5, H = 3;
  c.scene.materials["floor"] = grey_plastic("floor", 0.2);
  c.scene.materials["wall"] = grey_plastic("wall", 0.5);
  c.scene.materials["ceiling"] = grey_plastic("ceiling", 0.7);
  auto& o = c.scene.occluders;
  o.push_back(rectangle({0, 0, 0}, {W, 0, 0}, {0, D, 0}, "floor", "floor"));
  o.push_back(rectangle({0, 0, H}, {0, D, 0}, {W, 0, 0}, "ceiling", "ceiling"));
  o.push_back(rectangle({0, D, 0}, {W, 0, 0}, {0, 0, H}, "wall", "north"));
  o.push_back(rectangle({0, 0, 0}, {0, D, 0}, {0, 0, H}, "wall", "west"));
  o.push_back(rectangle({W, 0, 0}, {0, 0, H}, {0, D, 0}, "wall", "east"));
  // The window wall (y = 0, normal +y into the room) as four rectangles around the opening.
  const double x0 = 1, x1 = 3, z0 = 0.9, z1 = 2.4;
  o.push_back(rectangle({0, 0, 0}, {0, 0, z0}, {W, 0, 0}, "wall", "south_below"));
  o.push_back(rectangle({0, 0, z1}, {0, 0, H - z1}, {W, 0, 0}, "wall", "south_above"));
  o.push_back(rectangle({0, 0, z0}, {0, 0, z1 - z0}, {x0, 0, 0}, "wall", "south_west"));
  o.push_back(rectangle({x1, 0, z0}, {0, 0, z1 - z0}, {W - x1, 0, 0}, "wall", "south_east"));
  Aperture window;
  window.polygon = rectangle({x0, 0, z0}, {0, 0, z1 - z0}, {x1 - x0, 0, 0}, "void", "window");
  c.scene.apertures.push_back(window);
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 8; ++i) c.sensors.push_back({{0.25 + 0.5 * i, 0.25 + 0.5 * j, 0.85}, {0, 0, 1}});
  return c;
}

}  // namespace daylit::reflection_cases
