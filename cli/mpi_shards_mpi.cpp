// cli/mpi_shards.hpp over MPI (DAYLIT_MPI=ON): MPI_COMM_WORLD, non-blocking collectives waited on
// by polling with sleeps, and the agreement that opens every exchange.

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <thread>

#include "cli/mpi_shards.hpp"
#include "geometry/error.hpp"

namespace daylit::cli::mpi {

namespace {

int world_rank = 0, world_size = 1;
bool initialised_here = false;

// Waits for a non-blocking collective. A blocking one would spin (OpenMPI polls its transports
// at full speed), and a rank that waits while another computes alone (rank 0's reflected
// components, the blocks of a slower rank) would take a core from it on a shared node. Sleeps
// from 50 µs up to 5 ms between tests: at most a few ms of latency per exchange, of which a run
// has a handful per grid.
void wait(MPI_Request& request) {
  auto pause = std::chrono::microseconds(50);
  for (;;) {
    int done = 0;
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return;
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::microseconds(5000));
  }
}

// The agreement every exchange begins with: the largest exit code over the ranks. Non-zero: the
// failing ranks' messages go to rank 0 and every rank throws RankFailure with the agreed code.
void agree(int code, const std::string& message) {
  int agreed = 0;
  MPI_Request request;
  MPI_Iallreduce(&code, &agreed, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD, &request);
  wait(request);
  if (agreed == 0) return;
  const int length = int(message.size());
  std::vector<int> lengths(root() ? std::size_t(world_size) : 0);
  MPI_Igather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD, &request);
  wait(request);
  std::vector<int> offsets(lengths.size(), 0);
  for (std::size_t r = 1; r < lengths.size(); ++r) offsets[r] = offsets[r - 1] + lengths[r - 1];
  std::string all(lengths.empty() ? 0 : std::size_t(offsets.back() + lengths.back()), '\0');
  MPI_Igatherv(message.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR, 0,
               MPI_COMM_WORLD, &request);
  wait(request);
  std::vector<std::string> messages;
  for (std::size_t r = 0; r < lengths.size(); ++r) messages.push_back(all.substr(std::size_t(offsets[r]), std::size_t(lengths[r])));
  throw RankFailure(agreed, std::move(messages));
}

template <typename T> MPI_Datatype datatype();
template <> MPI_Datatype datatype<double>() { return MPI_DOUBLE; }
template <> MPI_Datatype datatype<float>() { return MPI_FLOAT; }

// Rank r's block of `total` values, `width` of T each, concatenated in rank order on rank 0.
template <typename T>
std::vector<T> gather_blocks(const T* local, std::size_t local_count, std::size_t total, std::size_t width) {
  // MPI counts in int; every rank has the same total, so every rank throws alike, before any exchange.
  if (width > 0 && total > std::size_t(std::numeric_limits<int>::max()) / width)
    throw Error("too many values (" + std::to_string(total) + " x " + std::to_string(width) +
                ") to gather in one MPI call: split the grid");
  agree(0, "");
  std::vector<int> counts, offsets;
  if (root())
    for (int r = 0; r < world_size; ++r) {
      const SensorBlock b = block(total, r);
      counts.push_back(int(b.size() * width));
      offsets.push_back(int(b.begin * width));
    }
  std::vector<T> all(root() ? total * width : 0);
  MPI_Request request;
  MPI_Igatherv(local, int(local_count * width), datatype<T>(), all.data(), counts.data(), offsets.data(), datatype<T>(),
               0, MPI_COMM_WORLD, &request);
  wait(request);
  return all;
}

// Whether an MPI launcher started this process. Without one, MPI_Init would make a singleton
// (OpenMPI: about 0.4 s of start-up here, and a launcher's machinery on a machine that may lack
// it) only to say that there is one rank; such a run skips MPI and is the default build's. The
// variables are those the launchers set for MPI_Init to find its job: OpenMPI's mpirun
// (OMPI_COMM_WORLD_SIZE), PMIx (PMIX_RANK: OpenMPI under srun --mpi=pmix, prterun) and PMI-1/2
// (PMI_RANK, PMI_SIZE: srun --mpi=pmi2, MPICH's hydra).
bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(name)) return true;
  return false;
}

}  // namespace

Session::Session(int& argc, char**& argv) {
  if (!launched_by_mpi()) return;
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  initialised_here = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &world_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &world_size);
}

Session::~Session() {
  if (initialised_here) MPI_Finalize();
}

bool built_with_mpi() { return true; }
int rank() { return world_rank; }
int ranks() { return world_size; }

std::vector<double> gather(const std::vector<double>& local, std::size_t total) {
  if (world_size == 1) return local;
  return gather_blocks(local.data(), local.size(), total, 1);
}

std::vector<Vec3> gather(const std::vector<Vec3>& local, std::size_t total) {
  if (world_size == 1) return local;
  std::vector<double> flat;
  for (const Vec3& v : local) flat.insert(flat.end(), {v.x, v.y, v.z});
  const std::vector<double> all = gather_blocks(flat.data(), local.size(), total, 3);
  std::vector<Vec3> out;
  for (std::size_t i = 0; i + 2 < all.size(); i += 3) out.push_back({all[i], all[i + 1], all[i + 2]});
  return out;
}

std::vector<float> gather(const std::vector<float>& local, std::size_t total, std::size_t width) {
  if (world_size == 1) return local;
  if (local.size() != block(total).size() * width) throw Error("mpi::gather: the rows do not fill this rank's block");
  return gather_blocks(local.data(), block(total).size(), total, width);
}

std::vector<double> gather_per_rank(double value) {
  if (world_size == 1) return {value};
  return gather_blocks(&value, 1, std::size_t(world_size), 1);  // block(ranks, r) is rank r alone
}

std::vector<std::uint64_t> gather_per_rank(std::uint64_t value) {
  if (world_size == 1) return {value};
  agree(0, "");
  std::vector<std::uint64_t> all(root() ? std::size_t(world_size) : 0);
  MPI_Request request;
  MPI_Igather(&value, 1, MPI_UINT64_T, all.data(), 1, MPI_UINT64_T, 0, MPI_COMM_WORLD, &request);
  wait(request);
  return all;
}

std::uint64_t sum(std::uint64_t local) {
  if (world_size == 1) return local;
  std::uint64_t total = 0;
  for (std::uint64_t v : gather_per_rank(local)) total += v;
  return root() ? total : local;
}

std::vector<std::uint64_t> sum_on_every_rank(const std::vector<std::uint64_t>& local) {
  if (world_size == 1) return local;
  if (local.size() > std::size_t(std::numeric_limits<int>::max()))
    throw Error("too many values (" + std::to_string(local.size()) + ") to sum in one MPI call");
  agree(0, "");
  std::vector<std::uint64_t> total(local.size(), 0);
  MPI_Request request;
  MPI_Iallreduce(local.data(), total.data(), int(local.size()), MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD, &request);
  wait(request);
  return total;
}

VisibilityCounters sum(const VisibilityCounters& local) {
  if (world_size == 1) return local;
  std::uint64_t VisibilityCounters::*const fields[] = {
      &VisibilityCounters::pairs,           &VisibilityCounters::pairs_not_facing,
      &VisibilityCounters::pairs_unobstructed, &VisibilityCounters::pairs_covered,
      &VisibilityCounters::pairs_clipped,   &VisibilityCounters::pairs_rational,
      &VisibilityCounters::occluders_box_culled, &VisibilityCounters::occluders_tested,
      &VisibilityCounters::occluders_clipped, &VisibilityCounters::occluders_skipped,
      &VisibilityCounters::panes_beyond,    &VisibilityCounters::panes_in_front,
      &VisibilityCounters::panes_crossing};
  static_assert(sizeof(VisibilityCounters) == sizeof(fields) / sizeof(fields[0]) * sizeof(std::uint64_t),
                "a counter was added to VisibilityCounters: add it here too");
  std::vector<std::uint64_t> mine, total(std::size(fields), 0);
  for (auto field : fields) mine.push_back(local.*field);
  agree(0, "");
  MPI_Request request;
  MPI_Ireduce(mine.data(), total.data(), int(mine.size()), MPI_UINT64_T, MPI_SUM, 0, MPI_COMM_WORLD, &request);
  wait(request);
  if (!root()) return local;
  VisibilityCounters out;
  for (std::size_t k = 0; k < std::size(fields); ++k) out.*fields[k] = total[k];
  return out;
}

std::vector<std::string> hosts() {
  if (world_size == 1) return {};  // the summary names hosts only when several ranks ran
  char name[MPI_MAX_PROCESSOR_NAME] = {};
  int length = 0;
  MPI_Get_processor_name(name, &length);
  agree(0, "");
  std::vector<char> all(root() ? std::size_t(world_size) * MPI_MAX_PROCESSOR_NAME : 0);
  MPI_Request request;
  MPI_Igather(name, MPI_MAX_PROCESSOR_NAME, MPI_CHAR, all.data(), MPI_MAX_PROCESSOR_NAME, MPI_CHAR, 0, MPI_COMM_WORLD,
              &request);
  wait(request);
  std::vector<std::string> out;
  for (int r = 0; root() && r < world_size; ++r) out.emplace_back(all.data() + std::size_t(r) * MPI_MAX_PROCESSOR_NAME);
  return out;
}

int finish(int code, const std::string& message) {
  if (world_size == 1) {
    if (!message.empty()) std::cerr << message << '\n';
    return code;
  }
  try {
    agree(code, message);
  } catch (const RankFailure& failure) {
    return report(failure);
  }
  return 0;
}

}  // namespace daylit::cli::mpi
