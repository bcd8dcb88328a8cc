// Compile-time x86 detection for the map's vector loops.
// SURFACE_NBV_X86: AVX2 intrinsics may be compiled (for functions marked
// target("avx2") and chosen at run time).
// SURFACE_NBV_AVX2_CLONES: a function attribute that makes GCC build an AVX2
// and a default version of a plain loop and pick one when the program loads
// (empty elsewhere).
#pragma once

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define SURFACE_NBV_X86 1
#endif

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define SURFACE_NBV_AVX2_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define SURFACE_NBV_AVX2_CLONES
#endif
