#include "report/npy_writer.hpp"

#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include <fmt/format.h>

#include "geometry/error.hpp"

namespace daylit::cli {

std::string npy_header_float32(std::size_t rows, std::size_t columns) {
  std::string dict = fmt::format("{{'descr': '<f4', 'fortran_order': False, 'shape': ({}, {}), }}", rows, columns);
  // magic (6) + version (2) + length (2) + dict + padding + '\n' ≡ 0 (mod 64).
  const std::size_t unpadded = 10 + dict.size() + 1;
  dict.append((64 - unpadded % 64) % 64, ' ');
  dict.push_back('\n');
  std::string header("\x93NUMPY\x01\x00", 8);
  header.push_back(char(dict.size() & 0xff));
  header.push_back(char((dict.size() >> 8) & 0xff));
  return header + dict;
}

void write_npy_float32(const std::string& path, const std::vector<float>& values, std::size_t rows, std::size_t columns) {
  static_assert(std::endian::native == std::endian::little, "the .npy writer writes the host's floats as '<f4'");
  if (values.size() != rows * columns) throw Error(path + ": array size does not match its shape");
  const std::string header = npy_header_float32(rows, columns);
  if (header.size() > 65535 + 10) throw Error(path + ": .npy header too long");
  std::FILE* out = std::fopen(path.c_str(), "wb");
  if (!out) throw Error(path + ": cannot open for writing");
  bool ok = std::fwrite(header.data(), 1, header.size(), out) == header.size();
  if (ok && !values.empty()) ok = std::fwrite(values.data(), sizeof(float), values.size(), out) == values.size();
  if (std::fclose(out) != 0 || !ok) throw Error(path + ": cannot write .npy");
}

}  // namespace daylit::cli
