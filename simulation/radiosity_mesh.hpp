#pragma once
// The elements of a radiosity solution (DESIGN.md §4): every reflecting polygon cut into
// triangles, each carrying on each of its two sides an exitance that varies linearly over it,
// fixed by its values at three collocation nodes strictly inside the triangle.

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "geometry/polygon.hpp"

namespace daylit {

// One triangle of a reflecting surface. Vertices run counter-clockwise about `normal`, the unit
// Newell normal of the polygon it came from (side +1; side −1 faces the other way).
//
// Nodes: barycentric (2/3, 1/6, 1/6) and its permutations. They are the points of the degree-2
// area rule with equal weights A/3 (Strang and Fix), so ∫_T M dA = A·(M_0 + M_1 + M_2)/3 exactly for
// the linear M the element carries, and they lie strictly inside, away from the surface's edges
// where the irradiance has its derivative singularities. The Lagrange basis for them is
// φ_k = 2 λ_k − 1/3 (λ the barycentric coordinates): φ_k(node_j) = δ_kj.
struct RadiosityElement {
  std::array<Vec3, 3> vertices;
  Vec3 normal;              // unit
  std::size_t surface = 0;  // index into RadiosityMesh::surfaces
  int level = 0;            // times split from the surface's first triangulation
  double area = 0;
  std::array<Vec3, 3> nodes;
  // ∇λ_k = N × (v_{k+2} − v_{k+1}) / (2A), constant over the element: kept, since the transport
  // asks for it at every receiver (make_element).
  std::array<Vec3, 3> lambda_gradients;
  // A sliver: collinear vertices to roundoff (polygons with points along their edges leave them
  // in the fan triangulation), area below 1e-12 of the longest edge squared. Its basis gradients
  // (∝ 1/A) mean nothing and what it could give is below 1e-12 of its neighbours': the transport
  // takes it as giving nothing.
  bool sliver = false;

  // λ_k at y (y's foot on the plane; any y), and its constant gradient in the plane.
  double barycentric(int k, const Vec3& y) const noexcept {
    return dot(lambda_gradients[std::size_t(k)], y - vertices[std::size_t((k + 1) % 3)]);
  }
  const Vec3& barycentric_gradient(int k) const noexcept { return lambda_gradients[std::size_t(k)]; }
  // φ_k(y) = 2 λ_k(y) − 1/3 and ∇φ_k.
  double basis(int k, const Vec3& y) const noexcept { return 2 * barycentric(k, y) - 1.0 / 3; }
  Vec3 basis_gradient(int k) const noexcept { return 2.0 * barycentric_gradient(k); }
  // The point of barycentric coordinates (b0, b1, b2).
  Vec3 point(double b0, double b1, double b2) const noexcept {
    return b0 * vertices[0] + b1 * vertices[1] + b2 * vertices[2];
  }
};

// A reflecting polygon of the scene: a luminaire and an occluder at once.
struct RadiositySurface {
  std::size_t occluder = 0;  // index into the polygons meshed (reflected_components: Scene::occluders, then the panes)
  double reflectance = 0;    // in (0, 1)
  Vec3 normal;               // unit Newell normal
  Vec3 point;                // a vertex: the plane is normal·(y − point) = 0
  double area = 0;
  std::vector<std::size_t> elements;
  std::size_t edge_begin = 0, edge_end = 0;  // its elements' edges: ids edge_begin ≤ id < edge_end
};

// The edges of the elements: edge k of an element runs from vertices[k] to vertices[(k + 1) % 3].
// Elements of one surface that have an edge with the same two end points share it (a T-junction,
// where a larger element meets two smaller ones, shares nothing). Each edge runs its own way from
// the lexicographically smaller end point (x, then y, then z) to the larger.
struct MeshEdge {
  Vec3 from, to;
};
struct ElementEdge {
  std::uint32_t id = 0;
  bool reversed = false;  // the element runs it from `to` to `from`
};

struct RadiosityMesh {
  std::vector<RadiositySurface> surfaces;
  std::vector<RadiosityElement> elements;
  std::vector<MeshEdge> edges;
  std::vector<std::array<ElementEdge, 3>> element_edges;  // per element
  int max_level = 0;
};

// Element built from three vertices (turned counter-clockwise about `normal`), nodes included.
RadiosityElement make_element(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& normal, std::size_t surface,
                              int level);

// The four children of the midpoint split (same orientation; level + 1).
std::array<RadiosityElement, 4> split_element(const RadiosityElement& e);

// Meshes every polygon with reflectance[i] > 0: its convex pieces (geometry/convex_pieces.hpp,
// seams of holes cancelled) fanned into triangles, each split at its midpoints until its longest
// edge is at most max_edge(element) (model units; graded meshes make it grow with the distance
// from what matters). Polygons of reflectance 0 are left out: they only occlude. Throws
// daylit::Error for a polygon that crosses itself.
RadiosityMesh mesh_surfaces(const std::vector<Polygon>& polygons, const std::vector<double>& reflectance,
                            const std::function<double(const RadiosityElement&)>& max_edge);

// Replaces the elements flagged in `split` by their four children (surfaces' lists and the
// edges updated). Returns, per element of the refined mesh, the index of the element of the
// mesh before that it is or came from (its parent: children of one element are consecutive,
// elements keep their order).
std::vector<std::size_t> refine_mesh(RadiosityMesh& mesh, const std::vector<bool>& split);

}  // namespace daylit
