// Which compiled copy of the blocked SIMD field kernel evaluate() (PolyhedronField.hpp)
// runs: runtime CPU dispatch.
//
// The default x86-64 build (GCC or Clang, MAG_NATIVE=OFF, MAG_ARCH below x86-64-v4)
// holds two copies of the blocked kernel (PolyhedronBlocks.hpp):
//
//   path     compiled with                    points per block
//   avx2     the build's -march (x86-64-v3)   4
//   avx512   -march=x86-64-v4                 8
//
// The first evaluate() picks one from the environment variable MAG_KERNEL:
//
//   MAG_KERNEL=auto     (or unset) avx512 where the CPU has the AVX-512 of x86-64-v4
//                       (avx512f, avx512bw, avx512cd, avx512dq, avx512vl), else avx2
//   MAG_KERNEL=avx2     forced (benchmarks, tests)
//   MAG_KERNEL=avx512   forced; a mag::InputError where the CPU lacks AVX-512
//
// and logs the choice at debug level. Other builds (MAG_NATIVE=ON, another MAG_ARCH,
// another compiler or processor) hold one copy, named after what it was compiled for:
// "avx512", "avx2", "sse2" or "generic". The avx2 and avx512 copies give the same bits
// (the same operations per lane, -ffp-contract=off, explicit FMA in both;
// tests/test_mbmKernel.cpp checks it).
//
// setKernelPath() does the same from code (tests, magBench's kernel study); it applies
// to every thread from the next evaluate() call on. Each shared object that links the
// kernel (libmagMBM.so, an app linking magMBMkernel) has its own choice; MAG_KERNEL
// reaches them all.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace mag::mbm {

/// Names of the copies in this build, narrowest first ({"avx2", "avx512"} by default
/// on x86-64).
std::vector<std::string> kernelPaths();

/// Whether this CPU runs the copy `path` (false for a name not in kernelPaths()).
bool kernelPathSupported(std::string_view path);

/// The copy evaluate() uses now; chosen from MAG_KERNEL at the first call unless set.
/// Throws mag::InputError where MAG_KERNEL is not a valid choice on this CPU.
std::string kernelPath();

/// Points per block (SIMD lanes) of the copy evaluate() uses now.
int kernelWidth();

/// Makes evaluate() use the copy `path` ("auto": the widest this CPU runs). Throws
/// mag::InputError for a name not in kernelPaths() or a copy this CPU cannot run.
void setKernelPath(std::string_view path);

} // namespace mag::mbm
