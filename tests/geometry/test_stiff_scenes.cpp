// Stiff and extreme scenes (DESIGN.md §5 at the scene level: receivers in the aperture's plane,
// windows seen edge-on, a 1e-12 sr skylight, a 2 km opening 1 mm away, slivers, flush reveals,
// georeferenced copies): the exact path against the independent long-double reference of
// bench/stiff_scenes.hpp, to each case's stated tolerance (relative; absolute, in percentage points,
// where the answer is 0). The float path's results are printed
// beside them (run with -s, or ctest -V), not asserted: it is allowed to fail, and
// `daylit bench stiff` tabulates where it does.

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <string>

#include "bench/stiff_scenes.hpp"
#include "reference_quadrature.hpp"
#include "simulation/sky_component.hpp"

using namespace daylit;

namespace {

// SC in percent, or NaN where the float path gives up (a non-finite value).
double sc(const stiff::StiffCase& c, GeometryMode mode) {
  const VisibilityEngine engine(c.scene, mode);
  VisibilityCounters counters;
  try {
    return sky_component_percent(engine, c.scene, c.sensor, SkyModel::cie_overcast, counters);
  } catch (const Error&) {
    if (mode == GeometryMode::floating) return std::nan("");
    throw;
  }
}

double error_against(double value, long double reference) {
  return reference == 0 ? std::abs(value) : double(std::abs((long double)value - reference) / std::abs(reference));
}

}  // namespace

TEST_CASE("the polar reference agrees with Gauss-Legendre quadrature over the area, and adds up") {
  // A plain window, which the area quadrature of reference_quadrature.hpp handles to ~1e-18,
  // from sensors facing up, tilted, and with the horizon through the window. The last sensor's
  // foot point lies in the window (on the horizon's cut), where the reference works in polar
  // coordinates; elsewhere it integrates over the area.
  const stiff::VisiblePiece whole{stiff::detail::rect_y(0, 0, 2, 1, 2)};
  for (const Vec3 p : {Vec3{1, 2, 0.85}, Vec3{-0.5, 0.7, 0.3}, Vec3{3, 4, 1.4}, Vec3{0.7, 0.6, 1.2}}) {
    for (const Vec3 n : {Vec3{0, 0, 1}, normalized(Vec3{0.3, -0.5, 1})}) {
      const auto ref = stiff::reference_piece(stiff::rvec(p), stiff::rvec(n), whole);
      const long double area = test::integrate_directions(
          test::lvec(p), {0, 0, std::max(1.0L, (long double)p.z)}, {2, 0, 0}, {0, 0, 2 - std::max(1.0L, (long double)p.z)},
          [&](const test::LVec3& u) { return (1 + 2 * u.z) / 3 * (n.x * u.x + n.y * u.y + n.z * u.z); });
      const long double expected = 100 * area / (7 * 3.141592653589793238462643383279502884L / 9);
      INFO("sensor " << p.x << " " << p.y << " " << p.z << ", normal " << n.x << " " << n.y << " " << n.z);
      CHECK(double(std::abs(ref.sc_percent - expected) / expected) < 1e-15);
      CHECK(ref.relative_error < 1e-15);
      // Split into two pieces at x = 0.6: the halves add up to the whole.
      const auto left = stiff::reference_piece(stiff::rvec(p), stiff::rvec(n), {stiff::detail::rect_y(0, 0, 0.6L, 1, 2)});
      const auto right = stiff::reference_piece(stiff::rvec(p), stiff::rvec(n), {stiff::detail::rect_y(0, 0.6L, 2, 1, 2)});
      CHECK(double(std::abs(left.sc_percent + right.sc_percent - ref.sc_percent) / ref.sc_percent) < 1e-16);
    }
  }
}

TEST_CASE("stiff scenes: the exact path keeps the independent reference, the float path is printed") {
  std::printf("%-34s %-24s %-24s %-10s %-24s %-10s\n", "case", "reference", "exact", "rel.err", "float", "rel.err");
  for (const stiff::StiffCase& c : stiff::stiff_cases()) {
    const stiff::ReferenceValue ref = stiff::reference_sky_component(c);
    const double exact = sc(c, GeometryMode::exact), floating = sc(c, GeometryMode::floating);
    std::printf("%-34s %-24.17Lg %-24.17g %-10.2e %-24.17g %-10.2e\n", c.name.c_str(), ref.sc_percent, exact,
                error_against(exact, ref.sc_percent), floating, error_against(floating, ref.sc_percent));
    INFO(c.name << ": " << c.description << "\nreference " << double(ref.sc_percent) << " (estimated relative error "
                << double(ref.relative_error) << "), exact " << exact << ", tolerance " << c.tolerance << " ("
                << c.tolerance_note << ")");
    // The reference must be far more accurate than the tolerance it checks against.
    CHECK(ref.relative_error < 1e-14);
    CHECK(error_against(exact, ref.sc_percent) <= c.tolerance);
  }
}

TEST_CASE("stiff scenes: the certified exact path reproduces the all-rational reference") {
  // The certified interval path rounds directions to 2^-45 of their length at worst (README), so
  // it may differ from the rational reference by a few 1e-14 of the result. On
  // reveal_closes_view the view closes to a line only in decimals: in the input doubles the jamb's
  // edge projects 9.25e-17 m inside the window, and both paths return that true sliver; the
  // rational path's directions round to exactly collinear ones (SC exactly 0), the certified
  // path's need not (1.05e-18 %): hence the absolute 1e-15 percentage points. (Where a view
  // closes exactly, both return no loop: test_visibility.cpp.)
  for (const stiff::StiffCase& c : stiff::stiff_cases()) {
    const double exact = sc(c, GeometryMode::exact), rational = sc(c, GeometryMode::rational);
    INFO(c.name << ": exact " << exact << ", rational " << rational);
    CHECK(std::abs(exact - rational) <= 1e-13 * std::abs(rational) + 1e-15);
  }
}
