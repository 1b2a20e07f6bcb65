#pragma once
// The discrete radiosity equation M = S + ρ ∘ (K M) over the elements' node values (DESIGN.md §4).

#include <cstdint>
#include <utility>
#include <vector>

namespace daylit {

// One row of K: (column, coefficient) pairs; M_i's irradiance is Σ coefficient·M_column.
using TransportRow = std::vector<std::pair<std::uint32_t, double>>;

struct RadiositySolution {
  std::vector<double> exitance;
  int sweeps = 0;
  double last_change = 0;  // max |ΔM| of the last sweep, relative to max |M|
  bool converged = false;  // to roundoff within max_sweeps, every value finite
};

// Gauss–Seidel sweeps of M_i ← S_i + ρ_i Σ_j K_ij M_j until a sweep changes no value by more than
// 1e-15 of max |M| (roundoff) or `max_sweeps`. The iteration contracts by at most
// max_i ρ_i Σ_j |K_ij| per sweep, below 1 for ρ < 1 and rows that are form factors (Σ_j K_ij ≤ 1,
// plus the roundoff of the linear basis' signed coefficients), so it converges for any
// reflectance below 1.
RadiositySolution solve_radiosity(const std::vector<TransportRow>& rows, const std::vector<double>& reflectance,
                                  const std::vector<double>& source, int max_sweeps = 100000);

}  // namespace daylit
