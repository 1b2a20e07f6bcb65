#pragma once
// NumPy's .npy format, version 1.0 (numpy.lib.format, "NEP 1: a simple file format for NumPy
// arrays"): the magic string "\x93NUMPY", the version bytes 1 and 0, a little-endian uint16 header
// length, an ASCII Python dict literal {'descr': '<f4', 'fortran_order': False, 'shape': (R, C), }
// padded with spaces and ended by '\n' so that the data start at a multiple of 64 bytes, then the
// array in C (row-major) order. numpy.load(path) reads it; so does any reader of the format.

#include <cstddef>
#include <string>
#include <vector>

namespace daylit::cli {

// The header of a row-major float32 array of rows × columns, as written before the data.
std::string npy_header_float32(std::size_t rows, std::size_t columns);

// Writes values (rows × columns, row-major) as little-endian float32. Throws daylit::Error when the
// file cannot be written or the sizes disagree.
void write_npy_float32(const std::string& path, const std::vector<float>& values, std::size_t rows, std::size_t columns);

}  // namespace daylit::cli
