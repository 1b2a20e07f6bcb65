#include "simulation/annual_reflections.hpp"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>

#include "illumination/fan_product_rule.hpp"
#include "illumination/gauss_legendre.hpp"
#include "simulation/block_product.hpp"
#include "simulation/direction_angles.hpp"
#include "simulation/pane_transmittance.hpp"
#include "simulation/sunlit_elements.hpp"

namespace daylit {

namespace {

constexpr double kPi = std::numbers::pi;
using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The columns of one channel: the fine grid's sky vertices, the coarse grid's, the far ground.
struct Columns {
  std::size_t fine = 0, coarse = 0;
  std::size_t coarse_at() const noexcept { return fine; }
  std::size_t ground_at() const noexcept { return fine + coarse; }
  std::size_t size() const noexcept { return fine + coarse + 1; }
};

// Per node: (channel × Columns::size() + column, value).
using NodeColumns = std::vector<std::pair<std::uint32_t, double>>;

// The columns one channel's D keeps: those in which some node of the operator has an entry (a
// window's light reaches the nodes only from the sky in front of it: on the office sample 1,213
// of the 3,349), and the ground column always (the sensors' own far ground enters there). Found
// from the nodes alone, so every block of sensors (every MPI rank) keeps the same columns.
struct ChannelColumns {
  std::vector<std::uint32_t> fine, coarse;  // kept direction-grid vertices of either grid, ascending
  std::vector<std::int32_t> position;       // Columns index → its place in D (−1: not kept)
  std::size_t size() const noexcept { return fine.size() + coarse.size() + 1; }
  std::size_t ground_at() const noexcept { return fine.size() + coarse.size(); }
};
std::vector<ChannelColumns> kept_columns(const std::vector<NodeColumns>& q, std::size_t groups, const Columns& columns) {
  const std::size_t width = columns.size();
  std::vector<char> used((groups + 1) * width, 0);
  for (const NodeColumns& node : q)
    for (const auto& [c, v] : node) used[c] = 1;
  std::vector<ChannelColumns> out(groups + 1);
  for (std::size_t g = 0; g <= groups; ++g) {
    ChannelColumns& k = out[g];
    k.position.assign(width, -1);
    for (std::size_t c = 0; c < columns.fine; ++c)
      if (used[g * width + c]) k.fine.push_back(std::uint32_t(c));
    for (std::size_t c = 0; c < columns.coarse; ++c)
      if (used[g * width + columns.coarse_at() + c]) k.coarse.push_back(std::uint32_t(c));
    for (std::size_t i = 0; i < k.fine.size(); ++i) k.position[k.fine[i]] = std::int32_t(i);
    for (std::size_t i = 0; i < k.coarse.size(); ++i)
      k.position[columns.coarse_at() + k.coarse[i]] = std::int32_t(k.fine.size() + i);
    k.position[columns.ground_at()] = std::int32_t(k.ground_at());
  }
  return out;
}

using Rule = quadrature::UnitGaussRule;


// The columns of every node of an operator.
std::vector<NodeColumns> node_columns(const Scene& scene, const ReflectionOperator& op, const DirectionGrid& fine,
                                      const DirectionGrid& coarse, const std::vector<int>& group_of_aperture, std::size_t groups,
                                      const Columns& columns) {
  static const Rule rule = quadrature::gauss_legendre_unit(kReflectionRuleOrder);
  const double max_angle = kReflectionTriangleDeg * kPi / 180;
  const std::size_t width = columns.size(), total = (groups + 1) * width;
  std::vector<NodeColumns> out(op.nodes.size());
  tbb::enumerable_thread_specific<std::vector<double>> scratch([total] { return std::vector<double>(total, 0.0); });
  // One fan triangle's rule nodes: direction, weight, altitude and azimuth.
  constexpr std::size_t kNodes = std::size_t(kReflectionRuleOrder) * std::size_t(kReflectionRuleOrder);
  struct RuleNodes {
    std::array<double, kNodes> x, y, z, weight, altitude, azimuth;
  };
  tbb::enumerable_thread_specific<RuleNodes> nodes_scratch;
  tbb::parallel_for(std::size_t(0), op.nodes.size(), [&](std::size_t k) {
    std::vector<double>& acc = scratch.local();
    const ReflectionNode& node = op.nodes[k];
    for (const LightView& view : node.views) {
      const std::size_t channel = view.aperture >= 0 ? std::size_t(group_of_aperture[std::size_t(view.aperture)]) : groups;
      double* row = acc.data() + channel * width;
      const Aperture* aperture = view.transmitting(scene);
      std::optional<ApertureTransmittance> through;
      if (aperture != nullptr) through.emplace(*aperture);
      // A count taken back (LightView::sign) enters negated.
      const auto transmittance = [&](const Vec3& u) { return view.sign * (through ? (*through)(u) : 1.0); };
      row[columns.ground_at()] += view.sign * view.ground;
      if (view.above.empty()) continue;
      // The sky: the hat functions of both grids, a fan triangle's rule nodes at a time (their
      // altitudes and azimuths in one vector call, once for both grids).
      RuleNodes& nodes = nodes_scratch.local();
      for_each_fan_triangle(view.above, max_angle, [&](const Vec3& a, const Vec3& b, const Vec3& c) {
        std::size_t count = 0;
        for_each_triangle_node(a, b, c, rule, [&](const Vec3& u, double dsigma) {
          nodes.x[count] = u.x;
          nodes.y[count] = u.y;
          nodes.z[count] = u.z;
          nodes.weight[count] = dsigma * dot(node.normal, u) * transmittance(u);
          ++count;
        });
        altitude_azimuth(nodes.x.data(), nodes.y.data(), nodes.z.data(), nodes.altitude.data(), nodes.azimuth.data(),
                         count);
        for (std::size_t i = 0; i < count; ++i) {
          const double w = nodes.weight[i];
          std::size_t v[4];
          double f[4];
          fine.interpolation_at(nodes.altitude[i], nodes.azimuth[i], v, f);
          for (int m = 0; m < 4; ++m) row[v[m]] += w * f[m];
          coarse.interpolation_at(nodes.altitude[i], nodes.azimuth[i], v, f);
          for (int m = 0; m < 4; ++m) row[columns.coarse_at() + v[m]] += w * f[m];
        }
      });
    }
    NodeColumns& entries = out[k];
    for (std::size_t c = 0; c < total; ++c)
      if (acc[c] != 0) {
        entries.emplace_back(std::uint32_t(c), acc[c]);
        acc[c] = 0;
      }
  });
  return out;
}

// D = W Q for one grid, one matrix per channel in whole blocks of rows (RowBlocks: the grid's
// sensors at their places, zeros elsewhere, for block_product); the sensors' own far ground
// through each aperture added to its group's ground column.
std::vector<Eigen::MatrixXd> sensor_columns(const ReflectionOperator& op, std::size_t grid_index,
                                      const std::vector<NodeColumns>& q, const std::vector<int>& group_of_aperture,
                                      std::size_t groups, const Columns& columns, const std::vector<ChannelColumns>& kept,
                                      std::size_t apertures) {
  const std::vector<double>& w = op.response[grid_index];
  const std::vector<double>& ground = op.sensor_ground[grid_index];
  const std::vector<double>& direct_ground = op.sensor_ground_direct[grid_index];
  const std::size_t nodes = op.nodes.size(), sensors = direct_ground.size();
  const std::size_t width = columns.size();
  const RowBlocks blocks(Eigen::Index(sensors), op.response_first[grid_index]);
  std::vector<Eigen::MatrixXd> d;
  for (std::size_t c = 0; c <= groups; ++c) d.push_back(Eigen::MatrixXd::Zero(blocks.height, Eigen::Index(kept[c].size())));
  // Q's entries as (channel, column) once: the loop below visits each sensors-times over.
  struct Entry {
    std::uint32_t channel, column;
    double value;
  };
  std::vector<std::vector<Entry>> entries(nodes);
  for (std::size_t k = 0; k < nodes; ++k)
    for (const auto& [c, v] : q[k]) {
      const std::size_t channel = c / width;
      entries[k].push_back({std::uint32_t(channel), std::uint32_t(kept[channel].position[c % width]), v});
    }
  // A block of sensors at a time: Q (tens of MB) is read once per block, not once per sensor. The
  // block's sums are kept column by column, its sensors side by side (acc[column × block + j]), so
  // that each entry of Q is one vector multiply-add over the block; each sum still takes the nodes
  // and their entries in order, as a sensor's own loop would.
  constexpr std::size_t kSensorBlock = 32;
  tbb::enumerable_thread_specific<std::vector<double>> accumulators(
      [&] { return std::vector<double>((groups + 1) * width * kSensorBlock, 0.0); });
  tbb::parallel_for(std::size_t(0), (sensors + kSensorBlock - 1) / kSensorBlock, [&](std::size_t block) {
    const std::size_t first = block * kSensorBlock, count = std::min(kSensorBlock, sensors - first);
    std::vector<double>& acc = accumulators.local();
    std::array<double, kSensorBlock> wk{};
    for (std::size_t k = 0; k < nodes; ++k) {
      bool any = false;
      for (std::size_t j = 0; j < count; ++j) any |= (wk[j] = w[(first + j) * nodes + k]) != 0;
      if (!any) continue;
      for (const Entry& e : entries[k]) {
        double* a = acc.data() + (std::size_t(e.channel) * width + e.column) * kSensorBlock;
        for (std::size_t j = 0; j < kSensorBlock; ++j) a[j] += wk[j] * e.value;
      }
    }
    for (std::size_t c = 0; c <= groups; ++c)
      for (std::size_t col = 0; col < kept[c].size(); ++col)
        for (std::size_t j = 0; j < count; ++j)
          d[c](blocks.offset + Eigen::Index(first + j), Eigen::Index(col)) = acc[(c * width + col) * kSensorBlock + j];
    std::fill(acc.begin(), acc.end(), 0.0);
    for (std::size_t j = 0; j < count; ++j) {
      const Eigen::Index row = blocks.offset + Eigen::Index(first + j);
      for (std::size_t a = 0; a < apertures; ++a)
        d[std::size_t(group_of_aperture[a])](row, Eigen::Index(kept[std::size_t(group_of_aperture[a])].ground_at())) +=
            ground[(first + j) * apertures + a];
      // The far ground seen directly: light from outdoors, its own channel's.
      d[groups](row, Eigen::Index(kept[groups].ground_at())) += direct_ground[first + j];
    }
  });
  return d;
}

// The sun's first bounce in lux at every node, per channel ([channel](node, column)), for each
// hour of a block that has a sun: integrated over each element side (sunlit_elements.hpp: the L²
// projection of the light on the element, exact in the flux and first moments of its sun patch,
// which a node's sample was not), the light that came in by a window of group g in channel g, what
// came by no window (outdoors) in the last. An hour's polygons across its beam are found once and
// serve every side; the hours run in parallel, each writing its own column.
struct SunHour {
  Vec3 sun;
  double direct_normal_lux = 0;
  Eigen::Index column = 0;
};
void sun_first_bounce(const Scene& scene, const ReflectionOperator& op, const std::vector<ConvexPiece>& pieces,
                      const std::vector<int>& group_of_aperture, std::size_t groups, const std::vector<SunHour>& hours,
                      std::vector<Eigen::MatrixXd>& out) {
  tbb::parallel_for(std::size_t(0), hours.size(), [&](std::size_t h) {
    const SunHour& hour = hours[h];
    const SunlitElements sunlit(pieces, sun_transmittances(scene, hour.sun), hour.sun, op.scale);
    for (std::size_t i = 0; i < op.sides.size(); ++i) {
      const Vec3& n = op.nodes[3 * i].normal;
      const double scale = sunlit.node_factor(op.sides[i], n, hour.direct_normal_lux);
      if (!(scale > 0)) continue;
      for (const SunlitPart& part : sunlit.parts(op.sides[i], n, op.side_polygon[i])) {
        const std::size_t channel = part.outer_polygon == SunlitPart::kDirect
                                        ? groups
                                        : std::size_t(group_of_aperture[part.outer_polygon - scene.occluders.size()]);
        for (std::size_t k = 0; k < 3; ++k)
          out[channel](Eigen::Index(3 * i + k), hour.column) += scale * part.integrals[k];
      }
    }
  });
}

}  // namespace

Vec3 DirectionGrid::direction(std::size_t v) const noexcept {
  const int i = int(v / std::size_t(columns)), j = int(v % std::size_t(columns));
  if (i == rows) return {0, 0, 1};
  const double alt = i * (kPi / 2) / rows, az = j * (2 * kPi) / columns;
  return {std::cos(alt) * std::cos(az), std::cos(alt) * std::sin(az), std::sin(alt)};
}

void DirectionGrid::interpolation_at(double alt, double az, std::size_t vertex_out[4], double weight_out[4]) const noexcept {
  const double fi = alt / (kPi / 2) * rows, fj = az / (2 * kPi) * columns;
  const int i = std::clamp(int(std::floor(fi)), 0, rows - 1);
  const int j = std::clamp(int(std::floor(fj)), 0, columns - 1);
  const double a = std::clamp(fi - i, 0.0, 1.0), b = std::clamp(fj - j, 0.0, 1.0);
  // vertex(i, j) without its general modulo (two integer divisions per vertex, most of this
  // function's time): j ∈ [0, columns − 1] here, so only j + 1 = columns wraps.
  const std::size_t below = std::size_t(i) * std::size_t(columns), above = below + std::size_t(columns);
  const std::size_t left = std::size_t(j), right = j + 1 == columns ? 0 : std::size_t(j + 1);
  vertex_out[0] = below + left;
  vertex_out[1] = below + right;
  vertex_out[2] = above + left;
  vertex_out[3] = above + right;
  weight_out[0] = (1 - a) * (1 - b);
  weight_out[1] = (1 - a) * b;
  weight_out[2] = a * (1 - b);
  weight_out[3] = a * b;
}

ReflectedGrids reflected_hours(const Scene& scene, const ReflectionOperator& fine, const ReflectionOperator* coarse,
                               const std::vector<std::size_t>& grid_indices, const std::vector<int>& group_of_aperture,
                               std::size_t groups, const AnnualSky& sky, double ground_reflectance) {
  std::vector<HourLight> lights(sky.hours.size());
  for (std::size_t h = 0; h < sky.hours.size(); ++h) {
    const AnnualHour& hour = sky.hours[h];
    if (!hour.sky) continue;
    const PerezSky* perez = &*hour.perez;
    const double scale = hour.scale;
    lights[h].luminance = [perez, scale](const Vec3& u) { return scale * perez->luminance_function(u); };
    lights[h].sun = hour.sun;
    lights[h].direct_normal_lux = hour.direct_normal_lux;
    lights[h].horizontal_lux = hour.diffuse_horizontal_lux + hour.direct_normal_lux * std::max(0.0, hour.sun.z);
  }
  return reflected_light(scene, fine, coarse, grid_indices, group_of_aperture, groups, lights, ground_reflectance);
}

std::vector<std::vector<std::size_t>> reflected_batches(const ReflectionOperator& op, std::size_t hours, std::size_t groups,
                                                        std::size_t max_bytes) {
  std::vector<std::vector<std::size_t>> batches;
  std::size_t bytes = 0;
  for (std::size_t g = 0; g < op.sensor_ground_direct.size(); ++g) {
    // ReflectedHours: a float per sensor, hour and channel (groups + 1), and one for the estimate.
    const std::size_t grid_bytes = op.sensor_ground_direct[g].size() * hours * (groups + 2) * sizeof(float);
    if (batches.empty() || bytes + grid_bytes > max_bytes) {
      batches.emplace_back();
      bytes = 0;
    }
    batches.back().push_back(g);
    bytes += grid_bytes;
  }
  return batches;
}

ReflectedGrids reflected_light(const Scene& scene, const ReflectionOperator& fine_op, const ReflectionOperator* coarse_op,
                               const std::vector<std::size_t>& grid_indices, const std::vector<int>& group_of_aperture,
                               std::size_t groups, const std::vector<HourLight>& sky_hours, double ground_reflectance) {
  const auto t0 = std::chrono::steady_clock::now();
  const DirectionGrid fine;
  DirectionGrid coarse;
  coarse.rows = fine.rows / 2;
  coarse.columns = fine.columns / 2;
  const auto coarse_to_fine = [&](std::size_t v) {
    return fine.vertex(2 * int(v / std::size_t(coarse.columns)), 2 * int(v % std::size_t(coarse.columns)));
  };
  const Columns columns{fine.vertices(), coarse.vertices()};
  const std::size_t apertures = scene.apertures.size();
  // The polygons that block or filter the sun, as the operators' sides name them.
  const std::vector<ConvexPiece> sun_pieces = sun_blocker_pieces(scene);

  // What each operator needs: its nodes' columns (once, whatever the grids), each grid's sensors'
  // D = W Q, W itself for the sun.
  struct Mesh {
    const ReflectionOperator* op;
    std::vector<ChannelColumns> kept;       // per channel
    std::vector<std::vector<Eigen::MatrixXd>> d;  // per grid of the batch, per channel: its kept columns
  };
  std::vector<Mesh> meshes;
  for (const ReflectionOperator* op : {&fine_op, coarse_op}) {
    if (op == nullptr) continue;
    Mesh m{op, {}, {}};
    const std::vector<NodeColumns> q = node_columns(scene, *op, fine, coarse, group_of_aperture, groups, columns);
    m.kept = kept_columns(q, groups, columns);
    for (const std::size_t grid_index : grid_indices)
      m.d.push_back(sensor_columns(*op, grid_index, q, group_of_aperture, groups, columns, m.kept, apertures));
    meshes.push_back(std::move(m));
  }

  ReflectedGrids result;
  for (std::size_t gi = 0; gi < grid_indices.size(); ++gi) {
    ReflectedHours out;
    out.sensors = fine_op.sensor_ground_direct[grid_indices[gi]].size();
    out.hours = sky_hours.size();
    out.channels = groups + 1;
    out.lux.assign(out.sensors * out.hours * out.channels, 0.0f);
    out.estimate.assign(out.sensors * out.hours, 0.0f);
    out.outdoors = fine_op.sensor_outdoors[grid_indices[gi]];
    result.grids.push_back(std::move(out));
  }

  std::vector<std::size_t> lit;
  for (std::size_t h = 0; h < sky_hours.size(); ++h)
    if (sky_hours[h].luminance) lit.push_back(h);
  // The sky at the horizon row is its limit from above (a luminance function is 0 at u_z = 0 and
  // below, where the hat functions of the lowest band still reach).
  std::vector<Vec3> directions(fine.vertices());
  for (std::size_t v = 0; v < fine.vertices(); ++v) {
    directions[v] = fine.direction(v);
    if (v < std::size_t(fine.columns)) directions[v] = normalized(directions[v] + Vec3{0, 0, 1e-9});
  }
  // Blocks of hours, a column per hour: the sky on the fine grid's and on the coarse grid's
  // directions and the far ground; the sun's first bounce per node and hour, exact. The fine
  // mesh takes both grids' skies (their difference is one term of the estimate); the coarse mesh,
  // compared with the fine one under the same sky, only the fine grid's. What does not depend on
  // the sensors (the skies, the sun's first bounce) is found once for every grid of the batch.
  const Eigen::Index nf = Eigen::Index(columns.fine), nc = Eigen::Index(columns.coarse);
  constexpr std::size_t kBlock = 128;
  // W's lit columns, gathered per block of hours into storage kept from block to block: at 2,400
  // sensors and 4,000 lit nodes a fresh matrix is 77 MB, above what glibc serves from its heap,
  // so each one was page-faulted in anew (the office's 2,400-sensor run: 11 s of system time).
  std::vector<double> w_lit_storage;
  for (std::size_t start = 0; start < lit.size(); start += kBlock) {
    const std::size_t count = std::min(kBlock, lit.size() - start);
    const Eigen::Index hours = Eigen::Index(count);
    Eigen::MatrixXd sky_fine(nf, hours), sky_coarse(nc, hours);
    Eigen::RowVectorXd ground(hours);
    tbb::parallel_for(std::size_t(0), count, [&](std::size_t b) {
      const HourLight& hour = sky_hours[lit[start + b]];
      const Eigen::Index c = Eigen::Index(b);
      for (std::size_t v = 0; v < fine.vertices(); ++v) sky_fine(Eigen::Index(v), c) = hour.luminance(directions[v]);
      for (std::size_t v = 0; v < coarse.vertices(); ++v)
        sky_coarse(Eigen::Index(v), c) = sky_fine(Eigen::Index(coarse_to_fine(v)), c);
      ground(c) = ground_reflectance * hour.horizontal_lux / kPi;
    });
    std::vector<SunHour> suns;
    for (std::size_t b = 0; b < count; ++b) {
      const HourLight& hour = sky_hours[lit[start + b]];
      // A sun below the horizon lights nothing (the point sun's first bounce: sunlit_elements.hpp).
      if (hour.direct_normal_lux > 0 && hour.sun.z > 0) suns.push_back({hour.sun, hour.direct_normal_lux, Eigen::Index(b)});
    }
    // per mesh, per grid of the batch: sensors × count
    std::vector<std::vector<Eigen::MatrixXd>> totals_fine(meshes.size()), totals_coarse(meshes.size());
    for (std::size_t mi = 0; mi < meshes.size(); ++mi) {
      const Mesh& m = meshes[mi];
      const bool both_grids = mi == 0;
      // The block's skies at the directions each channel keeps.
      std::vector<Eigen::MatrixXd> sky_fine_kept, sky_coarse_kept;
      for (const ChannelColumns& k : m.kept) {
        sky_fine_kept.push_back(sky_fine(k.fine, Eigen::all));
        if (both_grids) sky_coarse_kept.push_back(sky_coarse(k.coarse, Eigen::all));
      }
      const std::size_t n = m.op->nodes.size();
      std::vector<Eigen::MatrixXd> sun(groups + 1, Eigen::MatrixXd::Zero(Eigen::Index(n), hours));
      if (!suns.empty()) sun_first_bounce(scene, *m.op, sun_pieces, group_of_aperture, groups, suns, sun);
      // The nodes the sun reaches in the block, per channel (a window's sun patch: most nodes get none).
      std::vector<std::vector<Eigen::Index>> lit_nodes(groups + 1);
      for (std::size_t g = 0; g <= groups; ++g)
        for (Eigen::Index k = 0; k < Eigen::Index(n); ++k)
          if (!sun[g].row(k).isZero(0)) lit_nodes[g].push_back(k);
      for (std::size_t gi = 0; gi < grid_indices.size(); ++gi) {
        ReflectedHours& out = result.grids[gi];
        // The products' rows: the grid's sensors at their places in whole blocks (block_product).
        const RowBlocks blocks(Eigen::Index(out.sensors), m.op->response_first[grid_indices[gi]]);
        Eigen::MatrixXd total_fine = Eigen::MatrixXd::Zero(blocks.height, hours), total_coarse;
        if (both_grids) total_coarse = total_fine;
        for (std::size_t g = 0; g <= groups; ++g) {
          const Eigen::MatrixXd& d = m.d[gi][g];
          const ChannelColumns& k = m.kept[g];
          const Eigen::Index kf = Eigen::Index(k.fine.size()), kc = Eigen::Index(k.coarse.size());
          const Eigen::Index ground_at = Eigen::Index(k.ground_at());
          Eigen::MatrixXd r_fine = block_product(d.leftCols(kf), sky_fine_kept[g]), r_coarse;
          r_fine += d.col(ground_at) * ground;
          if (both_grids) {
            r_coarse = block_product(d.middleCols(kf, kc), sky_coarse_kept[g]);
            r_coarse += d.col(ground_at) * ground;
          }
          // The sun's part: W times the sun's first bounce on the nodes it reaches.
          if (!lit_nodes[g].empty()) {
            const Eigen::Map<const RowMatrix> w(m.op->response[grid_indices[gi]].data(), Eigen::Index(out.sensors),
                                                Eigen::Index(n));
            const Eigen::Index sensors = Eigen::Index(out.sensors), columns = Eigen::Index(lit_nodes[g].size());
            const std::size_t size = std::size_t(blocks.height) * std::size_t(columns);
            if (w_lit_storage.size() < size) w_lit_storage.resize(size);
            Eigen::Map<Eigen::MatrixXd> w_lit(w_lit_storage.data(), blocks.height, columns);
            w_lit.topRows(blocks.offset).setZero();
            // In tiles of 64 × 64: W is row-major and w_lit column-major, and a plain gather read
            // one value of each 84 KB row of W per step (the office's 10,524 nodes).
            constexpr Eigen::Index kTile = 64;
            const std::vector<Eigen::Index>& at = lit_nodes[g];
            for (Eigen::Index s0 = 0; s0 < sensors; s0 += kTile)
              for (Eigen::Index j0 = 0; j0 < columns; j0 += kTile)
                for (Eigen::Index s = s0; s < std::min(sensors, s0 + kTile); ++s)
                  for (Eigen::Index j = j0; j < std::min(columns, j0 + kTile); ++j)
                    w_lit(blocks.offset + s, j) = w(s, at[std::size_t(j)]);
            w_lit.bottomRows(blocks.height - blocks.offset - sensors).setZero();
            const Eigen::MatrixXd sun_lit = sun[g](lit_nodes[g], Eigen::all);
            const Eigen::MatrixXd rs = block_product(w_lit, sun_lit);
            r_fine += rs;
            if (both_grids) r_coarse += rs;
          }
          total_fine += r_fine;
          if (both_grids) total_coarse += r_coarse;
          if (mi == 0)
            for (std::size_t s = 0; s < out.sensors; ++s)
              for (std::size_t b = 0; b < count; ++b)
                out.lux[(s * out.hours + lit[start + b]) * out.channels + g] =
                    float(r_fine(blocks.offset + Eigen::Index(s), Eigen::Index(b)));
        }
        totals_fine[mi].push_back(std::move(total_fine));
        totals_coarse[mi].push_back(std::move(total_coarse));
      }
    }
    for (std::size_t gi = 0; gi < grid_indices.size(); ++gi) {
      ReflectedHours& out = result.grids[gi];
      const Eigen::Index offset = RowBlocks(Eigen::Index(out.sensors), fine_op.response_first[grid_indices[gi]]).offset;
      for (std::size_t s = 0; s < out.sensors; ++s)
        for (std::size_t b = 0; b < count; ++b) {
          const Eigen::Index i = offset + Eigen::Index(s), c = Eigen::Index(b);
          double e = std::abs(totals_fine[0][gi](i, c) - totals_coarse[0][gi](i, c));
          if (meshes.size() > 1) e += std::abs(totals_fine[0][gi](i, c) - totals_fine[1][gi](i, c));
          out.estimate[s * out.hours + lit[start + b]] = float(e);
        }
    }
  }
  result.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace daylit
