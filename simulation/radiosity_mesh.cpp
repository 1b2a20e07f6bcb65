#include "simulation/radiosity_mesh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>

#include "geometry/convex_pieces.hpp"

namespace daylit {

namespace {

double longest_edge(const RadiosityElement& e) {
  const auto& v = e.vertices;
  return std::max({norm(v[1] - v[0]), norm(v[2] - v[1]), norm(v[0] - v[2])});
}

}  // namespace

RadiosityElement make_element(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& normal, std::size_t surface,
                              int level) {
  RadiosityElement e;
  e.normal = normal;
  e.surface = surface;
  e.level = level;
  const Vec3 twice = cross(b - a, c - a);
  if (dot(twice, normal) >= 0)
    e.vertices = {a, b, c};
  else
    e.vertices = {a, c, b};
  e.area = 0.5 * norm(twice);
  for (int k = 0; k < 3; ++k) {
    // λ_k = ((v_{k+2} − v_{k+1}) × (y − v_{k+1}))·N / (2A) = (N × (v_{k+2} − v_{k+1}))·(y − v_{k+1}) / (2A)
    const Vec3& from = e.vertices[std::size_t((k + 1) % 3)];
    const Vec3& to = e.vertices[std::size_t((k + 2) % 3)];
    e.lambda_gradients[std::size_t(k)] = cross(normal, to - from) / (2 * e.area);
  }
  const double longest = longest_edge(e);
  e.sliver = !(e.area > 1e-12 * longest * longest);
  for (int k = 0; k < 3; ++k) {
    const double w[3] = {k == 0 ? 2.0 / 3 : 1.0 / 6, k == 1 ? 2.0 / 3 : 1.0 / 6, k == 2 ? 2.0 / 3 : 1.0 / 6};
    e.nodes[k] = e.point(w[0], w[1], w[2]);
  }
  return e;
}

std::array<RadiosityElement, 4> split_element(const RadiosityElement& e) {
  const auto& v = e.vertices;
  const Vec3 m01 = 0.5 * (v[0] + v[1]), m12 = 0.5 * (v[1] + v[2]), m20 = 0.5 * (v[2] + v[0]);
  const int l = e.level + 1;
  return {make_element(v[0], m01, m20, e.normal, e.surface, l), make_element(m01, v[1], m12, e.normal, e.surface, l),
          make_element(m20, m12, v[2], e.normal, e.surface, l), make_element(m01, m12, m20, e.normal, e.surface, l)};
}

namespace {

// A size function that asks for less than the input's roundoff cannot loop for ever.
constexpr int kMaxMeshLevel = 16;

// The edges of every surface's elements, surface by surface (so that each surface's ids are
// contiguous), shared where two elements have the same end points.
void index_edges(RadiosityMesh& mesh) {
  mesh.edges.clear();
  mesh.element_edges.assign(mesh.elements.size(), {});
  const auto less = [](const Vec3& a, const Vec3& b) {
    return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
  };
  for (RadiositySurface& s : mesh.surfaces) {
    s.edge_begin = mesh.edges.size();
    std::map<std::array<double, 6>, std::uint32_t> ids;
    for (std::size_t e : s.elements) {
      const auto& v = mesh.elements[e].vertices;
      for (int k = 0; k < 3; ++k) {
        const Vec3 &a = v[std::size_t(k)], &b = v[std::size_t(k + 1) % 3];
        const bool reversed = less(b, a);
        const Vec3 &lo = reversed ? b : a, &hi = reversed ? a : b;
        const auto [it, added] =
            ids.try_emplace({lo.x, lo.y, lo.z, hi.x, hi.y, hi.z}, std::uint32_t(mesh.edges.size()));
        if (added) mesh.edges.push_back({lo, hi});
        mesh.element_edges[e][std::size_t(k)] = {it->second, reversed};
      }
    }
    s.edge_end = mesh.edges.size();
  }
}

}  // namespace

RadiosityMesh mesh_surfaces(const std::vector<Polygon>& polygons, const std::vector<double>& reflectance,
                            const std::function<double(const RadiosityElement&)>& max_edge) {
  RadiosityMesh mesh;
  for (std::size_t i = 0; i < polygons.size(); ++i) {
    if (!(reflectance[i] > 0)) continue;
    const Vec3 newell = newell_normal(polygons[i].vertices);
    if (norm(newell) == 0) continue;  // a degenerate polygon has no area to reflect from
    RadiositySurface s;
    s.occluder = i;
    s.reflectance = reflectance[i];
    s.normal = normalized(newell);
    s.point = polygons[i].vertices.front();
    const std::size_t surface = mesh.surfaces.size();
    std::vector<RadiosityElement> todo;
    for (const ConvexPiece& piece : convex_pieces(polygons[i], i)) {
      const auto& v = piece.vertices;
      for (std::size_t k = 1; k + 1 < v.size(); ++k) {
        RadiosityElement e = make_element(v[0], v[k], v[k + 1], s.normal, surface, 0);
        if (e.area > 0) todo.push_back(e);
      }
    }
    while (!todo.empty()) {
      RadiosityElement e = todo.back();
      todo.pop_back();
      if (e.level < kMaxMeshLevel && longest_edge(e) > max_edge(e)) {
        for (const auto& c : split_element(e)) todo.push_back(c);
        continue;
      }
      s.area += e.area;
      s.elements.push_back(mesh.elements.size());
      mesh.max_level = std::max(mesh.max_level, e.level);
      mesh.elements.push_back(e);
    }
    mesh.surfaces.push_back(std::move(s));
  }
  index_edges(mesh);
  return mesh;
}

std::vector<std::size_t> refine_mesh(RadiosityMesh& mesh, const std::vector<bool>& split) {
  std::vector<RadiosityElement> old = std::move(mesh.elements);
  mesh.elements.clear();
  for (auto& s : mesh.surfaces) s.elements.clear();
  std::vector<std::size_t> parent;
  for (std::size_t i = 0; i < old.size(); ++i) {
    auto add = [&](const RadiosityElement& e) {
      mesh.surfaces[e.surface].elements.push_back(mesh.elements.size());
      mesh.max_level = std::max(mesh.max_level, e.level);
      mesh.elements.push_back(e);
      parent.push_back(i);
    };
    if (i < split.size() && split[i])
      for (const auto& c : split_element(old[i])) add(c);
    else
      add(old[i]);
  }
  index_edges(mesh);
  return parent;
}

}  // namespace daylit
