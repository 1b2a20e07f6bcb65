#pragma once
// The transmittance of the directions seen through more than one pane (VisibilityEngine::
// aperture_view with AperturesAre::panes): an interior window and then the façade's, a window and
// then a glass-modified tree. Light that passes several panes is counted once, under the last one
// on the way (the aperture), with the transmittance of every pane it passed.

#include <cstddef>
#include <utility>
#include <vector>

#include "geometry/scene.hpp"
#include "geometry/visibility.hpp"

namespace daylit {

// The panes along a view as one Aperture, so that every kernel that takes an aperture's
// transmittance (the sky component, illuminance) takes theirs, T = Π T_pane (the polynomial's
// axis: the aperture's, or where its T is constant, the first angle-dependent pane's):
//  - constant transmittances multiply;
//  - angle-dependent ones (glass, T(μ) a polynomial in the cosine of incidence) on panes parallel
//    to the aperture's (|a × b| ≤ 1e-9) and the aperture's own multiply as functions of the same
//    cosine; their product is fitted again by materials' degree-≤12 fit, and the combined
//    angular_fit_error is the sum of the factors' fit errors (scaled by the other factors, ≤ 1)
//    plus the refit's;
//  - an angle-dependent pane that is not parallel to the aperture's is taken as a constant over
//    the region: the mean of its extreme transmittances over the region's directions (the
//    extremes of its cosine over the region's loops: vertices, arcs and the pane's normal
//    inside, and the polynomial sampled between), and `spread` is half their difference over
//    that mean: the relative error bound of what the region gives (summed over such panes).
// The range [min, max] of w·u (w unit) over the directions of a region of convex, positively
// oriented loops (what the visibility routine returns): at the vertices, at the interior extremum
// of each great arc (where w's projection on the arc's plane falls inside the arc), and ±1 where
// ±w lies inside a loop.
std::pair<double, double> cosine_range(const SphericalRegion& region, const Vec3& w);

struct PanesThrough {
  Aperture combined;  // polygon: the aperture's (its normal is the polynomial's axis)
  double spread = 0;  // relative bound of the approximated factors (0: exact)
};
PanesThrough panes_through(const Scene& scene, std::size_t aperture, const SphericalRegion& region,
                           const std::vector<std::uint32_t>& panes);

// What a PaneView gives, as two terms to integrate over its region with their signs: +1 the
// aperture with all the panes, −1 the view's `last` pane with the others (the count that pane's
// own view made of these directions: PaneView). `aperture` and `panes` name each term's panes for
// what is evaluated along one direction (the sun: transmittance_along).
struct PaneTerm {
  PanesThrough transmittance;
  double sign = 1;
  std::size_t aperture = 0;
  std::vector<std::uint32_t> panes;
};
std::vector<PaneTerm> pane_terms(const Scene& scene, std::size_t aperture, const PaneView& view);

// The transmittance along a direction u through the aperture and the panes, exactly: each pane's
// T at its own cosine of incidence |w·u| (the sun's centre, where the direction is known; every
// direction of a cubature). The panes' normals are found once, at construction (a 361-gon's
// Newell normal per evaluation was 93 % of a cubature's time).
class TransmittanceAlong {
 public:
  TransmittanceAlong(const Scene& scene, std::size_t aperture, const std::vector<std::uint32_t>& panes);
  double operator()(const Vec3& u) const noexcept;

 private:
  struct Factor {
    Vec3 axis;                           // the pane's unit normal
    const std::vector<double>* angular;  // T(μ)'s coefficients
  };
  double constant_ = 1;  // the product of the constant transmittances
  std::vector<Factor> factors_;
};

double transmittance_along(const Scene& scene, std::size_t aperture, const std::vector<std::uint32_t>& panes, const Vec3& u);

}  // namespace daylit
