#pragma once
// Exact visible regions of apertures seen from receivers (DESIGN.md §2). The interface is plain:
// doubles in, loops of direction vectors out; CGAL stays inside visibility.cpp.

#include <cstdint>
#include <memory>

#include "geometry/scene.hpp"
#include "geometry/spherical_region.hpp"

namespace daylit {

enum class GeometryMode {
  exact,     // exact predicates; constructions in interval arithmetic, certified, with exact
             // rationals wherever an interval cannot decide; output rounded once
  floating,  // the same algorithm in double precision, for comparison
  rational,  // the same algorithm in exact (lazy) rationals throughout, no interval stage: the
             // slow reference that the exact mode's certified shortcuts must reproduce
};

// The order in which the occluder pieces' shadows are subtracted from an aperture piece. Both
// give the same set of directions; the partition into loops differs, and with it the last digits
// of every sum over the loops (a few 1e-14 relative; bench scenes measures by how much).
enum class SubtractionOrder {
  // The order of the culling hierarchy, as the engine had until 2026-12: results to the last bit
  // as before (the partition into loops, and so every kernel's rounding, depends on the order).
  as_built,
  // The default. Nearest occluder piece first; a shadow whose bounding box (in double, with a
  // margin that covers its rounding) misses a remaining visible piece's is not subtracted from
  // it, so occluders hidden behind others cost a box test; and whenever the pieces have doubled
  // since the last merge, and once at the end, two pieces that share a whole edge merge where
  // their union is certainly convex (ShadowClipper::merge_pieces), so that the cuts a shadow's
  // edge lines leave across what stays visible do not multiply. Honeybee's lab_building: one window's view 44,264 loops as built,
  // 6,737 without the merging, far fewer with it; the whole model 28 s on 2 cores, was ~15 min.
  front_to_back,
};

// What the visibility routine did and what it left out; summed over threads.
struct VisibilityCounters {
  std::uint64_t pairs = 0;               // sensor–aperture-piece pairs evaluated
  std::uint64_t pairs_not_facing = 0;    // piece behind the receiver, below its horizon, or edge-on
  std::uint64_t pairs_unobstructed = 0;  // no occluder survived culling: no exact construction at all
  std::uint64_t pairs_covered = 0;       // one occluder polygon hides the whole piece: decided by
                                         // exact predicates, nothing clipped (an empty region)
  std::uint64_t pairs_clipped = 0;       // occluders clipped and subtracted
  std::uint64_t pairs_rational = 0;      // of those, pairs where interval arithmetic could not certify
                                         // every decision, so exact rationals were used
  std::uint64_t occluders_box_culled = 0;    // occluder pieces (or BVH subtrees' pieces) culled by boxes
  std::uint64_t occluders_tested = 0;        // occluder pieces that reached the exact predicates
  std::uint64_t occluders_clipped = 0;       // occluder pieces that survived and were clipped
  std::uint64_t occluders_skipped = 0;       // of those, shadows skipped by boxes (front_to_back)
  std::uint64_t panes_beyond = 0;            // other apertures' pieces beyond the aperture (they block)
  std::uint64_t panes_in_front = 0;          // and in front of it (they transmit: ApertureView::behind)
  std::uint64_t panes_crossing = 0;          // of those in front, pieces that cross the aperture's plane

  VisibilityCounters& operator+=(const VisibilityCounters& o) {
    pairs += o.pairs;
    pairs_not_facing += o.pairs_not_facing;
    pairs_unobstructed += o.pairs_unobstructed;
    pairs_covered += o.pairs_covered;
    pairs_clipped += o.pairs_clipped;
    pairs_rational += o.pairs_rational;
    occluders_box_culled += o.occluders_box_culled;
    occluders_tested += o.occluders_tested;
    occluders_clipped += o.occluders_clipped;
    occluders_skipped += o.occluders_skipped;
    panes_beyond += o.panes_beyond;
    panes_in_front += o.panes_in_front;
    panes_crossing += o.panes_crossing;
    return *this;
  }
};

// What a visible region is cut to and what it carries.
struct VisibilityOptions {
  // Cut to the directions above the horizontal plane through the receiver: right for skies (what
  // is below the horizon is ground), wrong for luminaires, which may be seen below it.
  bool clip_to_horizon = true;
  // Fill SphericalRegion::edge_sources: the 3-D line of every edge, for gradients (Arvo 1994).
  // Costs a small array per loop; the default leaves the fast path as it is.
  bool edge_sources = false;
  // The index (in Scene::occluders) of an occluder that does not block: the luminaire itself when
  // every surface of a model is both a luminaire and an occluder (radiosity, DESIGN.md §4), so
  // that a surface does not hide itself. kNoOccluder: every occluder blocks.
  static constexpr std::size_t kNoOccluder = std::size_t(-1);
  std::size_t excluded_occluder = kNoOccluder;
  // The occluder the receiver lies on (kNoOccluder: none), which does not block either, or, past
  // the occluders (Scene::occluders.size() + a), aperture a's pane, which filters none of the
  // other apertures' views (AperturesAre::panes). A point
  // of a polygon computed in floating point lies off its plane by roundoff, on either side: one
  // behind it (measured: two of every three nodes of the office's window jambs, x = 0.8 − 1 ulp)
  // would see its own polygon in front of it, covering the whole hemisphere it faces.
  std::size_t receiver_occluder = kNoOccluder;
  // Whether occluders beyond the aperture's plane (seen from the receiver) block: true for skies,
  // whose light comes from beyond the window; false for luminaires, which nothing behind them can
  // hide. With false the region is exactly the directions to points x of the aperture whose open
  // segment (p, x) meets no occluder: occluder pieces on the far side of the aperture piece's
  // plane, or touching it from there, are culled, and pieces that cross it are clipped to the
  // receiver's side of it before they are projected (the new vertices lie on that input plane
  // and are certified as those on the cone's planes are).
  bool occluders_beyond = true;
};

// What a scene's apertures are to each other.
enum class AperturesAre {
  // Sky openings, each open or filled with a transmitting pane (glass, trans, BSDF): where other
  // panes lie between the receiver and aperture A, the view through A is seen through them as
  // well (ApertureView::behind), and the counts of PaneView make light that passes several panes
  // (an interior window, then the façade; a window, then a glass-modified tree) count once, with
  // the transmittance of every pane on the way.
  panes,
  // Luminaires that do not see each other (the surfaces of a radiosity solution, each queried
  // alone): none hides or filters another.
  independent,
};

// Directions through aperture A that also pass other apertures' panes between the receiver and A.
// The engine does not cut a view at the panes beyond it (that would clip every far pane's shadow
// into every view, at great cost where panes sit in holes of walls): each pane's view counts the
// sky past it, and the directions that go on through further panes are counted again by the
// last pane's view, with every pane on the way. So what a region here gives is
//     E(A and `panes`) − E(`last` and the other panes),
// the second the count that `last`, the pane of `panes` nearest A, made of the same directions.
// Along a ray through panes P1 … Pk (from the receiver) the views count T1, T1T2 − T1, …,
// T1⋯Tk − T1⋯Tk−1: in all T1⋯Tk, each direction once.
struct PaneView {
  SphericalRegion region;
  std::vector<std::uint32_t> panes;  // those other apertures (Scene::apertures indices), ascending
  std::uint32_t last = 0;            // of them, the one nearest A (all others lie on the receiver's side of it)
};
struct ApertureView {
  SphericalRegion region;        // through A alone: what visible_region returns
  std::vector<PaneView> behind;  // through A and other panes in front of it, by pane set
  bool empty() const noexcept { return region.empty() && behind.empty(); }
};

class VisibilityEngine {
 public:
  // Splits apertures and occluders into convex pieces and builds the culling hierarchy.
  // Throws daylit::Error for polygons that cross themselves.
  // With more than one aperture and AperturesAre::panes, every aperture's pieces also take part in
  // the others' visibility (ApertureView).
  VisibilityEngine(const Scene& scene, GeometryMode mode, SubtractionOrder order = SubtractionOrder::front_to_back,
                   AperturesAre apertures = AperturesAre::panes);
  ~VisibilityEngine();
  VisibilityEngine(VisibilityEngine&&) noexcept;
  VisibilityEngine& operator=(VisibilityEngine&&) noexcept;

  std::size_t aperture_count() const noexcept;
  std::size_t occluder_piece_count() const noexcept;
  std::size_t aperture_piece_count() const noexcept;
  GeometryMode mode() const noexcept;
  SubtractionOrder order() const noexcept;

  // The directions from receiver p (normal n, unit) that pass through aperture `aperture`, lie in
  // front of the receiver's tangent plane and above the horizontal plane through p, and meet no
  // occluder on the way (in front of or beyond the aperture), nor, with AperturesAre::panes, any
  // other aperture's pane in front of it. Returned as positively oriented loops (a partition of the region);
  // empty when nothing is visible. Thread-safe.
  SphericalRegion visible_region(const Vec3& p, const Vec3& n, std::size_t aperture,
                                 VisibilityCounters& counters) const;
  // The same with options: without the horizon cut and without the occluders beyond the aperture
  // (the region of a luminaire), and with the source of every edge. Edge sources are the same in
  // all three geometry modes (the combinatorics are exact in all but degenerate float cases).
  SphericalRegion visible_region(const Vec3& p, const Vec3& n, std::size_t aperture, VisibilityCounters& counters,
                                 const VisibilityOptions& options) const;
  // The same region, and the directions through the aperture that pass other panes in front of it
  // (AperturesAre::panes): together, every direction by which the sky reaches p with this aperture
  // as the last pane on the way. The pane sets partition those directions: each direction is in
  // the region of exactly the set of panes its ray crosses.
  ApertureView aperture_view(const Vec3& p, const Vec3& n, std::size_t aperture, VisibilityCounters& counters,
                             const VisibilityOptions& options = {}) const;
  // Whether any aperture can lie in front of another (AperturesAre::panes and more than one).
  bool panes_interact() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace daylit
