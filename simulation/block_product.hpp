#pragma once
// Products of matrices whose rows are sensors, C = A B, each row of C with digits of its own: the
// same whichever other rows are computed with it (an MPI rank's block of a grid, or the whole
// grid), as DenseLU::solve keeps its columns'. Used by the annual reflections' hourly products
// (annual_reflections.hpp), the largest per-sensor work of an annual run with reflections.
//
// OpenBLAS's dgemm (its kernel chosen for the processor at run time; Eigen's is built for the
// baseline x86-64) treats the places of a block of rows differently, so A is held in whole blocks
// of kProductRows rows aligned to the larger system (row i of A at place (first + i) mod
// kProductRows of its block, zeros elsewhere: the RowBlocks layout), and each block is one call
// on one thread: OpenBLAS splits a product's rows between its threads, so two threads give other
// digits than one (measured), and one thread here is about as fast as Eigen's product on two
// (the office sample's 300-sensor annual run, reflected hours 13.5 s with Eigen on 2 threads,
// 11.8 s with OpenBLAS on 2, 12.2 s on 1).

#include <Eigen/Dense>

#include <cstddef>

namespace daylit {

inline constexpr Eigen::Index kProductRows = 128;

// Where rows first … first + rows − 1 of a larger system lie in whole blocks of kProductRows.
struct RowBlocks {
  Eigen::Index offset = 0;  // the place of the first row in the first block
  Eigen::Index height = 0;  // the blocks' rows together: a multiple of kProductRows
  RowBlocks(Eigen::Index rows, std::size_t first);
};

// A B for A of blocks.height rows (column-major, leading dimension a.outerStride(); blocks as
// above) and B contiguous: one dgemm per block of kProductRows rows, on one thread.
Eigen::MatrixXd block_product(const Eigen::Ref<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>& a,
                              const Eigen::MatrixXd& b);

}  // namespace daylit
