#!/usr/bin/env bash
# Installs what daylit needs to build and test on Debian 12 (bookworm) or later.
set -euo pipefail
packages=(
  g++ cmake ninja-build pkg-config
  libcgal-dev libgmp-dev libmpfr-dev   # exact geometry (CGAL over GMP rationals), correct rounding
  libeigen3-dev                        # dense matrices: the reflected components as a linear map (annual runs)
  libopenblas-openmp-dev               # that map's dense LU (LAPACK's dgetrf), OpenMP threads as Eigen's
  libgsl-dev                           # the Clausen integral; adaptive Gauss–Kronrod quadrature
  libtbb-dev                           # threads
  libopenimageio-dev fonts-dejavu-core # falsecolour images and their legends
  libcli11-dev nlohmann-json3-dev libfmt-dev
  libgeographiclib-dev                 # site placement: WGS84, UTM, local east-north-up frames
  catch2                               # tests (v2)
  libtinyobjloader-dev                 # tests: an independent OBJ reader (its double build) to check daylit's against
  time                                 # tests: peak memory of runs over millions of lines
  python3                              # tests: the layering check, summary checks in CLI tests
  libopenmpi-dev openmpi-bin           # optional: -DDAYLIT_MPI=ON, sensors sharded over MPI ranks (CI tests it)
  clang-14 libclang-rt-14-dev llvm-14  # CI: libFuzzer targets (fuzz/), its runtime, llvm-symbolizer
)
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${packages[@]}" > /dev/null
echo "setup: installed ${#packages[@]} packages"
