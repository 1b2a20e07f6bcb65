#pragma once
// Dense linear least squares by Householder QR in long double, for the small fits (glazing
// transmittance, sky luminance) whose columns are powers and therefore nearly dependent.

#include <vector>

namespace daylit {

// Minimises |A x − b|₂ for A with `rows` × `cols` entries in row-major order (rows ≥ cols).
// Columns are scaled to unit length first (the powers span many decades). Throws nothing;
// a column that is exactly dependent gets coefficient 0.
std::vector<long double> least_squares(std::vector<long double> A, std::vector<long double> b, std::size_t rows,
                                       std::size_t cols);

}  // namespace daylit
