// The blocked SIMD field kernel compiled with the build's flags (x86-64-v3 by default:
// AVX2, 4 lanes; see PolyhedronBlocks.hpp).
#define MAG_MBM_BLOCKS_NS baseline
#include "PolyhedronBlocks.inc"
