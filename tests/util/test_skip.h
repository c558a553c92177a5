#pragma once
// A test case that cannot run (a tool, a package or a shared asset is missing) reports a skip to
// CTest, never a pass. Catch2 2.13 has no SKIP(): ANIMORPH_SKIP prints a fixed marker that the
// test registrations match with SKIP_REGULAR_EXPRESSION (tests/CMakeLists.txt), then returns from
// the test case. Use it only at the top level of a TEST_CASE body (it returns from the function).
#include <iostream>
#include <sstream>

// The marker CTest matches; keep it equal to ANIMORPH_SKIP_MARKER in tests/CMakeLists.txt.
#define ANIMORPH_SKIP_MARKER "ANIMORPH_TEST_SKIPPED:"

#define ANIMORPH_SKIP(reason)                                                        \
  do {                                                                               \
    std::ostringstream animorph_skip_reason_;                                        \
    animorph_skip_reason_ << reason;                                                 \
    std::cout << "\n" ANIMORPH_SKIP_MARKER " " << animorph_skip_reason_.str() << std::endl; \
    return;                                                                          \
  } while (false)
