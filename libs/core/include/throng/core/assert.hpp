// THRONG_ASSERT — invariant checks inside the core. Boundaries validate and return diagnostics;
// inside, a broken invariant is a bug. On unless THRONG_DISABLE_ASSERTS is defined (Release builds
// keep them: they are cheap and outside the innermost loops).
#pragma once
#include <cstdio>
#include <cstdlib>

#if defined(THRONG_DISABLE_ASSERTS)
#define THRONG_ASSERT(cond) ((void)0)
#else
#define THRONG_ASSERT(cond)                                                                  \
  do {                                                                                       \
    if (!(cond)) {                                                                           \
      std::fprintf(stderr, "%s:%d: assertion failed: %s\n", __FILE__, __LINE__, #cond);      \
      std::abort();                                                                          \
    }                                                                                        \
  } while (false)
#endif
