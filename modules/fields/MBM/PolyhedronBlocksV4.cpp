// The blocked SIMD field kernel compiled for x86-64-v4 (AVX-512, 8 lanes; see
// PolyhedronBlocks.hpp), run only where the CPU has AVX-512 (KernelPath.cpp).
// CMakeLists.txt gives this file -march=x86-64-v4; it must include nothing but
// PolyhedronBlocks.inc (see the one-definition-rule note there).
#if !defined(__AVX512F__)
#error "PolyhedronBlocksV4.cpp must be compiled with -march=x86-64-v4"
#endif
#define MAG_MBM_BLOCKS_NS x86_64_v4
#include "PolyhedronBlocks.inc"
