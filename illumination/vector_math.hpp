#pragma once
// glibc's vector math (libmvec) for the loops that evaluate one function at many points: the
// circumsolar sum and the Perez normalisation's inner sum (sky/), the hat functions' directions
// (simulation/direction_angles.cpp), the nodes of the η quadrature
// (illumination/log_cosine_integrand.cpp). Only a source file built with DAYLIT_LIBMVEC (GCC on
// x86-64, where glibc ships libmvec; each room's CMakeLists.txt sets it per file, with
// -fno-math-errno and -fopenmp-simd) sees the declarations; elsewhere the loops stay scalar.
//
// glibc declares these vector variants only under -ffast-math (bits/math-vector.h); declaring
// them here lets an `omp simd` loop use them without fast-math's licence to reorder everything
// else. Their results differ from the scalar functions' by rounding only (libmvec's bound: 4 ulp).
// DAYLIT_VECTOR_CLONES compiles a function three times, for AVX-512 (eight doubles a call), AVX2
// (four) and the baseline (two), chosen when the program loads; the AVX-512 clone took the annual
// direct light on the office's 300 sensors from 15.5 to 13.6 s on one core of an AMD EPYC
// (2026-12-06; metrics the same). The variants round differently within the 4 ulp, so the last
// bits of an hourly value may differ between machines of different vector widths (never between
// runs, threads or MPI ranks on one machine).

#if defined(DAYLIT_LIBMVEC)
extern "C" {
__attribute__((simd("notinbranch"))) double exp(double) noexcept;
__attribute__((simd("notinbranch"))) double cos(double) noexcept;
__attribute__((simd("notinbranch"))) double acos(double) noexcept;
__attribute__((simd("notinbranch"))) double asin(double) noexcept;
__attribute__((simd("notinbranch"))) double atan2(double, double) noexcept;
__attribute__((simd("notinbranch"))) double log1p(double) noexcept;
}
#define DAYLIT_VECTOR_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define DAYLIT_VECTOR_CLONES
#endif
