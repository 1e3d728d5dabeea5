#pragma once
// The bug channel: a broken invariant aborts with a message. Never used for user input.
#include <cstdio>
#include <cstdlib>

#define SHADELAB_CHECK(cond, msg)                                                          \
  do {                                                                                     \
    if (!(cond)) {                                                                         \
      std::fprintf(stderr, "%s:%d: check failed: %s: %s\n", __FILE__, __LINE__, #cond, msg); \
      std::abort();                                                                        \
    }                                                                                      \
  } while (0)
