#pragma once
// The discrete radiosity equation M = S + ρ ∘ (K M) over the elements' node values (DESIGN.md §4).

#include <cstdint>
#include <utility>
#include <vector>

namespace daylit {

// One entry of a row of K, packed: 12 bytes where std::pair<std::uint32_t, double> pads to 16. A
// mesh's rows are hundreds of MB, and the reciprocity and the sweeps read them whole, so their
// size is time (and every page of them is faulted in, zeroed, once); x86-64 reads a double at any
// address.
struct [[gnu::packed]] TransportEntry {
  TransportEntry() = default;
  // A constructor, not an aggregate: emplace_back(column, coefficient) then compiles where
  // parenthesised aggregate initialisation does not (clang 14).
  TransportEntry(std::uint32_t column, double coefficient) : first(column), second(coefficient) {}
  std::uint32_t first;  // the column
  double second;        // the coefficient
  friend bool operator==(const TransportEntry& a, const TransportEntry& b) {
    return a.first == b.first && a.second == b.second;
  }
};
static_assert(sizeof(TransportEntry) == 12);
// One row of K: (column, coefficient) entries; M_i's irradiance is Σ coefficient·M_column.
using TransportRow = std::vector<TransportEntry>;

struct RadiositySolution {
  std::vector<double> exitance;
  int sweeps = 0;
  double last_change = 0;  // max |ΔM| of the last sweep, relative to max |M|
  bool converged = false;  // to roundoff within max_sweeps, every value finite
};

// Gauss–Seidel sweeps of M_i ← S_i + ρ_i Σ_j K_ij M_j until a sweep changes no value by more than
// 1e-15 of max |M| (roundoff) or `options.max_sweeps`. The iteration contracts by at most
// max_i ρ_i Σ_j |K_ij| per sweep, below 1 for ρ < 1 and rows that are form factors (Σ_j K_ij ≤ 1,
// plus the roundoff of the linear basis' signed coefficients), so it converges for any
// reflectance below 1.
//
// `options.over_relaxation` ω ≠ 1: successive over-relaxation, M_i ← M_i + ω (GS value − M_i), for a
// reciprocal transport only (make_reciprocal: w_i K_ij = w_j K_ji). Scaled row by row by w_i/ρ_i
// (which leaves the sweeps' values as they are), the rows of ρ > 0 are then A M = W S/ρ with
// A = W/ρ − G, G symmetric (rows of ρ = 0 are M_i = S_i, which the sweeps keep from the start).
// For a symmetric A with a positive diagonal, Gauss–Seidel converges exactly where A is positive
// definite, and then SOR converges for every 0 < ω < 2 (the Ostrowski–Reich theorem; Saad,
// Iterative Methods for Sparse Linear Systems, 2nd ed., §4.2): over-relaxing asks nothing that
// Gauss–Seidel did not. The best ω depends on the spectrum; 1.1 measured: 23 → 17 sweeps on the
// room sample and 23 → 16 on the office at their defaults (1.05: 19, 1.15: 19, 1.2: 22 on the
// room), the results within 2e-14.
struct SweepOptions {
  int max_sweeps = 100000;
  double over_relaxation = 1.0;
  // Where the sweeps start (the source where empty): a solution of the same equation on a coarser
  // mesh, carried over, is nearer the answer than the source is.
  std::vector<double> start;
};
RadiositySolution solve_radiosity(const std::vector<TransportRow>& rows, const std::vector<double>& reflectance,
                                  const std::vector<double>& source, const SweepOptions& options = {});

}  // namespace daylit
