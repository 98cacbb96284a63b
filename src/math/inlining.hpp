// Inlining control for the automatically differentiated kernels.
//
// The dual-number operations and the 3-vector helpers over them (vec3.hpp,
// frames.hpp) are tiny; a kernel is fast only when they all inline into it,
// so that the compiler keeps the values in registers and drops the zero
// fills of temporaries. GCC's heuristics give up on that inside the larger
// kernels (the vertex Hessian is a few hundred dual operations), and the
// calls then cost about as much as the arithmetic. So:
//   XSHELL_DUAL_INLINE  forces one operation inline;
//   XSHELL_FLATTEN      inlines everything a kernel calls, recursively.
#pragma once

//
// Sanitizer builds do not flatten: instrumented, a flattened vertex Hessian
// takes GCC more than twenty minutes to compile.
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(undefined_behavior_sanitizer)
#define XSHELL_SANITIZED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define XSHELL_SANITIZED 1
#endif

#if defined(__GNUC__)
#define XSHELL_DUAL_INLINE __attribute__((always_inline)) inline
#else
#define XSHELL_DUAL_INLINE inline
#endif

#if defined(__GNUC__) && !defined(XSHELL_SANITIZED)
#define XSHELL_FLATTEN __attribute__((flatten))
#else
#define XSHELL_FLATTEN
#endif
