#pragma once
// A dense LU factorisation with partial pivoting by LAPACK's dgetrf as OpenBLAS implements it
// (blocked, recursive panels, threaded), and solves with it (OpenBLAS's dtrsm on blocks of a fixed
// number of columns, one thread). The reflected
// components' operator (reflection_operator, annual runs) factorises (I − ρK)ᵀ of every live node
// (10,308 on the office sample) and solves it for every sensor: the largest dense work of a run.
// Eigen's PartialPivLU, used before, took 3× as long for the factorisation on 2 threads
// (6,000²: 5.0 s against 1.66 s; 3,000²: 0.57 against 0.20 s; measured 2026-12-05), and its
// triangular solves run on one thread.
//
// The arithmetic of any partial-pivoting LU (Golub and Van Loan §3.4), so its backward stability:
// a column of (I − ρK)ᵀ holds 1 and ρ times a row of K, whose entries sum to about the node's
// view of the room's surfaces (≤ 1 up to the reciprocity's small adjustments), so with ρ < 1 the
// matrix is diagonally dominant by columns, where partial pivoting swaps no rows and the growth
// factor is at most 2 (ibid. §3.4.6).

#include <Eigen/Dense>

#include <vector>

namespace daylit {

class DenseLU {
 public:
  // Factorises `a` (square) in place with `threads` threads; throws daylit::Error where a pivot
  // is exactly 0 (a singular matrix) or LAPACK reports an argument error.
  DenseLU(Eigen::MatrixXd a, int threads);
  // X = A⁻¹ B, where B's columns are columns first_column, first_column + 1, … of a larger
  // system (a grid's sensors, of which an MPI rank solves a block): a column's digits depend on
  // its index in that system only, not on which other columns are solved with it (how the
  // sensors' ranks of an MPI run stay bit-identical to one process).
  Eigen::MatrixXd solve(Eigen::MatrixXd b, std::size_t first_column = 0) const;

 private:
  Eigen::MatrixXd lu_;
  std::vector<int> pivots_;
};

}  // namespace daylit
