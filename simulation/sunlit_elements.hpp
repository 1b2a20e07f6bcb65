#pragma once
// The sun's first bounce on the radiosity elements, integrated over each element instead of read
// at its nodes. A patch of sunlight through a window is often narrower than the elements around
// it; collocated at the nodes it is sampled, not integrated, and the light it puts on the surfaces
// is then as wrong as the nodes are unlucky (the room sample at 78.6° incidence: 0.54–1.10 of the
// flux through the window, ERC + IRC up to 6 % low; README, 2026-12-07).
//
// Along a parallel beam from the sun (direction s, its disk taken as a point: its penumbra,
// 0.0093 of the distance to the edge that casts it, is left out), the light at x on an element is
// E_dn (n·s) T(x), T(x) the product of the transmittances of the panes the ray x + t s, t > 0,
// crosses and 0 where it meets an opaque polygon: a piecewise constant function over the element.
// It is found exactly (to the roundoff of the 2-D clipping) by projecting every polygon in front of
// the element's plane along s onto it, convex piece by convex piece: an opaque piece is cut out of
// what is still lit, a pane multiplies what lies under it by its transmittance along s. Any number
// of panes in series is counted.
//
// The element's exitance is linear, φ_k = 2λ_k − 1/3 its nodal basis (radiosity_mesh.hpp). Its
// nodes are the points of the degree-2 area rule with equal weights A/3, which integrates the
// product of two linear functions exactly, so the mass matrix ∫ φ_j φ_k dA is (A/3) δ_jk: the L²
// projection of the first bounce onto the element's linear functions is
//   E0_k = (3/A) ∫ E φ_k dA,
// with no system to solve. It keeps the flux (Σ_k (A/3) E0_k = ∫ E dA) and the first moments of
// the light on the element exactly; a node may get a negative value where the light is bunched
// against the opposite edge (φ_k ≥ −1/3), as any L² projection of a step.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/convex_pieces.hpp"
#include "geometry/polygon.hpp"
#include "geometry/scene.hpp"
#include "simulation/radiosity_mesh.hpp"

namespace daylit {

// Every polygon's convex pieces (geometry/convex_pieces.hpp), found once for any number of suns.
std::vector<ConvexPiece> sun_blocker_pieces(const std::vector<Polygon>& polygons);
// The same for a scene's polygons in the order the reflected components number them: the
// occluders, then every aperture's pane.
std::vector<ConvexPiece> sun_blocker_pieces(const Scene& scene);
// Their transmittances along `sun` in that order: 0 for an occluder, each pane's τ or T(|a·s|).
std::vector<double> sun_transmittances(const Scene& scene, const Vec3& sun);

// A part of an element side's light: where the beam passed the same panes. `outer_polygon`: the
// pane it passed farthest from the element (the window the light came in by; the largest height
// above the element's plane), or kDirect where it passed none.
struct SunlitPart {
  static constexpr std::size_t kDirect = std::size_t(-1);
  std::size_t outer_polygon = kDirect;
  std::array<double, 3> integrals{0, 0, 0};  // ∫ T φ_k dA over the part
};

class SunlitElements {
 public:
  // `pieces`: sun_blocker_pieces of the polygons that can block the sun or filter it;
  // `transmittance[i]` polygon i's transmittance along `sun` (0: opaque; 1: an open hole, which
  // filters nothing but names the window the light came in by). `sun`: unit, towards the sun.
  // `scale`: the model's size, for the tolerance that tells a polygon in an element's plane from
  // one in front of it. The pieces must outlive this.
  SunlitElements(const std::vector<ConvexPiece>& pieces, const std::vector<double>& transmittance, const Vec3& sun,
                 double scale);

  // ∫ T φ_k dA over element `element`, the side whose outward normal is `n` (±element.normal; 0
  // where it faces away from the sun), for k = 0, 1, 2, polygon `own` (the element's surface) left
  // out. The first bounce at node k is E_dn (n·s) (3/A) times the k-th.
  std::array<double, 3> basis_integrals(const RadiosityElement& element, const Vec3& n, std::size_t own) const;
  // E_dn (n·s) 3/A: times an integral, the first bounce at that node (the L² projection); 0 for
  // a side facing away.
  double node_factor(const RadiosityElement& element, const Vec3& n, double direct_normal) const noexcept {
    return direct_normal * std::max(dot(n, sun_), 0.0) * 3 / element.area;
  }
  // The same, part by part, summed by the outermost pane passed (the window the light came by).
  std::vector<SunlitPart> parts(const RadiosityElement& element, const Vec3& n, std::size_t own) const;

 private:
  struct Piece {
    const ConvexPiece* piece = nullptr;
    double transmittance = 0;
    double u_min = 0, u_max = 0, v_min = 0, v_max = 0;  // its box across the beam
    double depth_max = 0;                               // its farthest point towards the sun (s·y)
  };
  // The pieces whose boxes across the beam may meet [u0, u1] × [v0, v1], by a uniform grid of
  // cells over all but the largest (large_, always listed), in index order.
  void candidates(double u0, double u1, double v0, double v1, std::vector<std::uint32_t>& out) const;
  int cell_of(double x, double origin, int count) const noexcept;

  std::vector<Piece> pieces_;
  Vec3 sun_, across_u_, across_v_;
  double tolerance_ = 0;
  double grid_u0_ = 0, grid_v0_ = 0, cell_ = 1;
  int cells_u_ = 0, cells_v_ = 0;
  std::vector<std::vector<std::uint32_t>> cells_;
  std::vector<std::uint32_t> large_;  // in index order
};

}  // namespace daylit
