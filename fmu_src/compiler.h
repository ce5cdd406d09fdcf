/*
 * The attributes the code's speed rests on, once, each with why.  Each FMU
 * binary is compiled as one unit (CMake's fmu_add), so the compiler sees
 * every body on a step's path; these say what its heuristics get wrong
 * there (docs/benchmarks.md has the measurements).  Other compilers than
 * gcc and clang get plain C: the same results, slower.
 *
 * OC_ALWAYS_INLINE  on a static function that is a piece of a larger body:
 *   the law's step (its trial, stick test, slip solve and commit), the
 *   patch's sums, the rig's step over a known contact.  As calls, they
 *   would spill the registers the body keeps live; gcc inlines most of them
 *   on its own, clang (which builds the shipped binaries) leaves the slip
 *   solve a call, and gcc -O2 the rig's step at a second call site.
 * OC_HOT  on the definitions of the functions a step passes through (set
 *   inputs, the model's update and do_step, get outputs): inlined into the
 *   FMI entry points, where a chain of five calls per entry point showed in
 *   the time of a stick step.  Their declarations stay plain, so that a
 *   unit without the body (the tests' libraries) calls them as usual.  gcc
 *   wants inline beside always_inline; clang must not have it (an extern
 *   function defined inline is inline-only in C99).
 * OC_NOINLINE  a rare branch kept out of a hot function (a further step
 *   with held inputs), whose every call would otherwise pay for the
 *   registers the rare branch needs.
 * OC_LIKELY(c)  a condition nearly always true, tested by a branch the
 *   processor predicts, so that the work after it need not wait for the
 *   test (clang makes the slip solve's start test a select otherwise).
 * OC_VECTORS  1 where GCC/Clang vector extensions (two doubles a vector:
 *   SSE2 on x86-64, NEON on aarch64; no intrinsics, no -march) carry the
 *   slip solve's lanes (law/lanes.h) and the rolling cells' pairs
 *   (cells/transport.c); -DOC_SCALAR_LANES or another compiler: 0, the
 *   same numbers in plain C.
 */
#ifndef OC_COMPILER_H
#define OC_COMPILER_H

#if defined(__GNUC__) || defined(__clang__)
#define OC_ALWAYS_INLINE __attribute__((always_inline)) inline
#define OC_NOINLINE __attribute__((noinline))
#define OC_LIKELY(c) __builtin_expect(!!(c), 1)
#else
#define OC_ALWAYS_INLINE inline
#define OC_NOINLINE
#define OC_LIKELY(c) (c)
#endif

#if (defined(__GNUC__) || defined(__clang__)) && !defined(OC_SCALAR_LANES)
#define OC_VECTORS 1
#else
#define OC_VECTORS 0
#endif

#if defined(__clang__)
#define OC_HOT __attribute__((always_inline))
#elif defined(__GNUC__)
#define OC_HOT __attribute__((always_inline)) inline
#else
#define OC_HOT
#endif

#endif
