// Eigen for the project's translation units: include this header, never an
// <Eigen/...> header directly (tests/CMakeLists.txt checks it).
//
// Eigen is a system header (its imported target), so its own warnings never
// show; but with -march=native on an AVX-512 CPU, GCC 12 inlines Eigen's
// packet code (ptranspose, predux, the GEMM packing) into our functions and
// then reports -Wmaybe-uninitialized / -Wuninitialized at GCC's own
// avx512fintrin.h (`__Y` of _mm512_extractf64x4_pd, an intrinsic that reads
// no uninitialised value): false positives, ~470 lines per clean build. GCC
// decides whether to report by the diagnostic state at the warning's
// location, which lies in the intrinsics header that Eigen/Core includes
// first; so the two warnings are ignored here, around Eigen's headers only,
// and stay on for every line of the project's own code.
#pragma once

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#endif
// clang-format off
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <unsupported/Eigen/AutoDiff>
// clang-format on
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
