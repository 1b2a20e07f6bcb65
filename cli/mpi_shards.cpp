// What both builds of cli/mpi_shards.hpp share: the blocks, the sub-grids, and how rank 0 words
// a failure.

#include "cli/mpi_shards.hpp"

#include <algorithm>
#include <iostream>

#include <fmt/format.h>

namespace daylit::cli::mpi {

SensorBlock block(std::size_t count, int r) {
  const std::size_t n = std::size_t(ranks()), k = std::size_t(r);
  const std::size_t base = count / n, longer = count % n;
  const std::size_t begin = k * base + std::min(k, longer);
  return {begin, begin + base + (k < longer ? 1 : 0)};
}

SensorGrid sub_grid(const SensorGrid& grid, SensorBlock b) {
  SensorGrid part;
  part.name = grid.name;
  part.path = grid.path;
  part.first = grid.first + b.begin;
  part.sees_sky_directly = grid.sees_sky_directly;
  part.sensors.assign(grid.sensors.begin() + std::ptrdiff_t(b.begin), grid.sensors.begin() + std::ptrdiff_t(b.end));
  return part;
}

const SensorGrid& rank_block(const SensorGrid& grid, SensorGrid& storage) {
  if (!several()) return grid;
  storage = sub_grid(grid, block(grid.sensors.size()));
  return storage;
}

RankFailure::RankFailure(int c, std::vector<std::string> m)
    : std::runtime_error("another MPI rank failed"), code(c), messages(std::move(m)) {}

nlohmann::json summary_json(const std::vector<ShardedGrid>& grids, const std::vector<std::string>& hosts,
                            const std::vector<std::uint64_t>& threads, const std::string& sharded,
                            const std::string& not_sharded) {
  const int n = int(hosts.size());
  nlohmann::json per_rank = nlohmann::json::array(), per_grid = nlohmann::json::array();
  std::vector<std::size_t> rank_sensors(hosts.size(), 0);
  std::vector<double> rank_time(hosts.size(), 0.0);
  double time_sum = 0;
  for (const ShardedGrid& g : grids) {
    std::vector<std::size_t> sensors;
    for (int r = 0; r < n; ++r) {
      sensors.push_back(block(g.sensors, r).size());
      rank_sensors[std::size_t(r)] += sensors.back();
      rank_time[std::size_t(r)] += g.time_s[std::size_t(r)];
      time_sum += g.time_s[std::size_t(r)];
    }
    per_grid.push_back({{"name", g.name}, {"sensors", g.sensors}, {"sensors_per_rank", sensors},
                        {"compute_time_s_per_rank", g.time_s}});
  }
  for (int r = 0; r < n; ++r)
    per_rank.push_back({{"rank", r},
                        {"host", hosts[std::size_t(r)]},
                        {"threads", threads[std::size_t(r)]},
                        {"sensors", rank_sensors[std::size_t(r)]},
                        {"compute_time_s", rank_time[std::size_t(r)]}});
  return {{"ranks", n},
          {"sharded", sharded},
          {"not_sharded", not_sharded},
          {"blocks", "each rank computes a contiguous block of every grid's sensors (sizes differing by at most one, in "
                     "rank order); rank 0 gathers them in grid order and computes every statistic from the whole grid"},
          {"compute_time_s_is", "each rank's wall time for its blocks, before the gather; the grids' run_time_s are rank "
                                "0's, gather included"},
          {"compute_time_s_sum", time_sum},
          {"per_rank", per_rank},
          {"grids", per_grid}};
}

int report(const RankFailure& failure) {
  // Bad input is read alike by every rank, so usually every rank failed with the same message:
  // say it once, as one process would. A message from some ranks only (a sensor of their block)
  // names them.
  const std::vector<std::string>& m = failure.messages;
  std::vector<bool> said(m.size(), false);
  for (std::size_t r = 0; r < m.size(); ++r) {
    if (m[r].empty() || said[r]) continue;
    std::vector<std::size_t> alike;
    for (std::size_t q = r; q < m.size(); ++q)
      if (m[q] == m[r]) {
        alike.push_back(q);
        said[q] = true;
      }
    if (alike.size() == m.size())
      std::cerr << m[r] << '\n';
    else
      std::cerr << fmt::format("{} [MPI rank{} {} of {}]\n", m[r], alike.size() > 1 ? "s" : "", fmt::join(alike, ", "),
                               m.size());
  }
  return failure.code;
}

}  // namespace daylit::cli::mpi
