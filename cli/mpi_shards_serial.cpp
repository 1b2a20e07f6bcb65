// cli/mpi_shards.hpp without MPI (the default build, DAYLIT_MPI=OFF): one rank, which computes
// every sensor and exchanges nothing.

#include <iostream>

#include "cli/mpi_shards.hpp"

namespace daylit::cli::mpi {

Session::Session(int&, char**&) {}
Session::~Session() = default;

bool built_with_mpi() { return false; }
int rank() { return 0; }
int ranks() { return 1; }

std::vector<double> gather(const std::vector<double>& local, std::size_t) { return local; }
std::vector<Vec3> gather(const std::vector<Vec3>& local, std::size_t) { return local; }
std::vector<float> gather(const std::vector<float>& local, std::size_t, std::size_t) { return local; }
std::vector<double> gather_per_rank(double value) { return {value}; }
std::vector<std::uint64_t> gather_per_rank(std::uint64_t value) { return {value}; }
std::uint64_t sum(std::uint64_t local) { return local; }
std::vector<std::uint64_t> sum_on_every_rank(const std::vector<std::uint64_t>& local) { return local; }
VisibilityCounters sum(const VisibilityCounters& local) { return local; }
std::vector<std::string> hosts() { return {}; }

int finish(int code, const std::string& message) {
  if (!message.empty()) std::cerr << message << '\n';
  return code;
}

}  // namespace daylit::cli::mpi
