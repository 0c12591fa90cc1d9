#pragma once
// Hot loops compiled twice, for AVX2 and for any x86-64 processor, with the
// copy picked when the program loads (GCC's target_clones). The AVX2 copy
// works on four doubles per instruction. FMA is not enabled, so both copies
// round every multiply and every subtraction alike: the same bits on every
// machine, and a journal replays the same anywhere.

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define ARGIL_AVX2_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define ARGIL_AVX2_CLONES
#endif
