#pragma once
/* TURGOR_VECTOR_CLONES before a function with a loop the compiler vectorises: GCC on x86-64 builds it
   three times, for AVX-512, AVX2 and the baseline (SSE2), and picks one when the program starts
   (target_clones, an ifunc). No multiply-add is fused (the build passes -ffp-contract=off: AVX-512
   brings FMA with it), so every clone gives the same bits (element by element, the same operations
   in the same order). Off under the sanitizers and other compilers: the baseline loop only. */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
  #define TURGOR_VECTOR_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
  /* where the clones are made, a hand-written AVX version of a loop may be too: a function with
     TURGOR_AVX_TARGET, called where TURGOR_HAS_AVX() says the CPU runs it */
  #define TURGOR_AVX_PATHS  1
  #define TURGOR_AVX_TARGET __attribute__((target("avx")))
  #define TURGOR_HAS_AVX()  __builtin_cpu_supports("avx")
#else
  #define TURGOR_VECTOR_CLONES
#endif
