#pragma once
// The ranks of an MPI run (`mpirun -n N daylit df ...`, issue 13 part 3): which block of a grid's
// sensors this process computes, how the blocks reach rank 0 in grid order, and how the ranks
// agree that a run failed. Distribution only, no mathematics: every per-sensor result is a
// function of that sensor alone (sky_component, illuminance: the visibility engine keeps no state
// between queries), so computing the blocks apart and concatenating them in rank order gives the
// single process's vectors bit for bit; whatever sums over sensors (grid statistics) is computed
// on rank 0 from the gathered vector, never from per-rank partial sums. Counters are integers,
// whose sums do not depend on their order. The one coupling between sensors, annual's LM-83
// blinds rule (how many of the grid's sensors are sunlit in each hour), is such a count:
// sum_on_every_rank makes it the whole grid's on every rank before the hourly pass.
//
// Two implementations, chosen by CMake: mpi_shards_mpi.cpp (DAYLIT_MPI=ON; OpenMPI through
// MPI::MPI_CXX) and mpi_shards_serial.cpp (the default build: one rank, every call the identity).
// The commands call the same functions either way, and with one rank (no mpirun, or mpirun -n 1)
// they do exactly what they did before MPI: the block is the whole grid and nothing is exchanged.
//
// Failure protocol. Every exchange begins with an agreement (an all-reduce of an exit code): a
// rank that threw does not reach its next exchange but calls finish() with its code from main's
// handler, whose agreement is matched by the healthy ranks' next one; they then throw RankFailure,
// which main reports (rank 0 prints every distinct message once) without agreeing again. Every
// rank calls finish() exactly once at the end, so a failure on rank 0 after the last exchange
// (writing the outputs) still gives every rank the same non-zero exit code, and no rank waits in
// an exchange that another has left. Waiting ranks sleep between polls instead of spinning, so
// that rank 0 working alone (the reflected components) keeps the node's cores.

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/sensor_grid.hpp"
#include "geometry/vec3.hpp"
#include "geometry/visibility.hpp"

#include <nlohmann/json.hpp>

namespace daylit::cli::mpi {

// Initialises MPI for the life of main (MPI_Init_thread, MPI_THREAD_FUNNELED: only the main thread
// calls MPI; TBB's workers never do) and finalises it, where an MPI launcher (mpirun, srun)
// started the process; otherwise, and in the default build, nothing: one rank.
class Session {
 public:
  Session(int& argc, char**& argv);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
};

bool built_with_mpi();  // DAYLIT_MPI: mpi_shards_mpi.cpp (`daylit bench scenes` runs it under mpirun)
int rank();        // 0 … ranks() − 1
int ranks();       // 1 without MPI or without mpirun
inline bool root() { return rank() == 0; }
inline bool several() { return ranks() > 1; }

// A half-open block [begin, end) of a grid's sensor indices.
struct SensorBlock {
  std::size_t begin = 0, end = 0;
  std::size_t size() const { return end - begin; }
};
// Rank r's block of `count` sensors: contiguous, in rank order, sizes differing by at most one
// (the first count % ranks() blocks one longer). Empty where there are more ranks than sensors.
SensorBlock block(std::size_t count, int r);
inline SensorBlock block(std::size_t count) { return block(count, rank()); }
// The grid's sensors of a block, same name and path; with one rank, the whole grid.
SensorGrid sub_grid(const SensorGrid& grid, SensorBlock block);
// This rank's block of a grid: the grid itself where one rank computes it all (no copy: a grid
// may hold millions of sensors, and the bad-input test bounds df's memory per sensor), else its
// sub_grid, kept in `storage`.
const SensorGrid& rank_block(const SensorGrid& grid, SensorGrid& storage);

// Every rank's block of a grid's per-sensor values, concatenated in rank order on rank 0 (the
// whole grid's values, as one process computes them); empty on the other ranks. `local` holds
// this rank's block(total) values.
std::vector<double> gather(const std::vector<double>& local, std::size_t total);
std::vector<Vec3> gather(const std::vector<Vec3>& local, std::size_t total);
// The same for rows of `width` values per sensor (an annual grid's [sensor × hours] floats):
// `local` holds this rank's block(total) rows; on rank 0 the total × width values. Throws
// daylit::Error, on every rank alike, where total × width exceeds what one MPI call can count.
std::vector<float> gather(const std::vector<float>& local, std::size_t total, std::size_t width);
// One value per rank, on rank 0, in rank order; empty elsewhere.
std::vector<double> gather_per_rank(double value);
std::vector<std::uint64_t> gather_per_rank(std::uint64_t value);
// Summed over the ranks, on rank 0; this rank's own elsewhere.
std::uint64_t sum(std::uint64_t local);
// Summed element by element over the ranks, on every rank (the vectors as long on every rank):
// annual's blinds counts, which every rank's hourly pass needs.
std::vector<std::uint64_t> sum_on_every_rank(const std::vector<std::uint64_t>& local);
// Counters summed over the ranks, on rank 0 (integers: exact in any order); this rank's own elsewhere.
VisibilityCounters sum(const VisibilityCounters& local);
// The host (MPI_Get_processor_name) of every rank, on rank 0; empty elsewhere and with one rank.
std::vector<std::string> hosts();

// The summary's "mpi" object (written only when several ranks ran): how many, on which hosts,
// what was sharded and what not, and per rank its sensors and the seconds it computed them in
// (per grid, and summed over the grids and ranks). ShardedGrid::time_s is gather_per_rank() of
// the rank's compute time for the grid; `hosts` is hosts(), `threads` gather_per_rank() of each
// rank's TBB threads (they differ where the nodes or the launcher's bindings do).
struct ShardedGrid {
  std::string name;
  std::size_t sensors = 0;
  std::vector<double> time_s;  // per rank
};
nlohmann::json summary_json(const std::vector<ShardedGrid>& grids, const std::vector<std::string>& hosts,
                            const std::vector<std::uint64_t>& threads, const std::string& sharded,
                            const std::string& not_sharded);

// Another rank failed: thrown by an exchange or by finish() once the ranks have agreed on it.
struct RankFailure : std::runtime_error {
  int code;                           // the agreed exit code: the largest of the ranks' codes
  std::vector<std::string> messages;  // on rank 0: every failing rank's message, by rank ("" where none)
  RankFailure(int code, std::vector<std::string> messages);
};

// The end of a run on every rank: `code` 0 (success) or the exit code of this rank's failure with
// its message ("error: ..."). Returns the exit code the ranks agree on; rank 0 prints the
// messages of the failing ranks (each distinct one once, with its ranks where not all of them
// failed alike); the others print nothing. With one rank: prints `message` and returns `code`.
int finish(int code, const std::string& message);
// main's handler for a RankFailure: rank 0 prints its messages as finish() does; returns its code.
int report(const RankFailure& failure);

}  // namespace daylit::cli::mpi
