#pragma once
// The CPU polygoniser's (poly/polygonizer.h) interval tests of a block's 4^3 sub-blocks: once a
// block's first tested sub-blocks proved nothing, it takes the rest as live untested (a live
// sub-block whose interval proves one sign makes no triangle, so the mesh is the same; see
// polygonizer.cpp, kSubTestsWithoutCull). Process-wide, for tests and benchmarks that check the
// skip without timing it.
#include <cstdint>

namespace animorph {

// Sub-block interval tests left out since the process started, over every call and thread (a relaxed
// atomic: read it between polygonisations).
uint64_t subBlockTestsSkippedTotal();

// Whether later polygonisations may leave sub-block tests out (default true); false tests every
// sub-block, as before 2026-11-30 (the reference a test compares meshes with). Set it between
// polygonisations, not during one.
void setSubBlockTestSkipping(bool enabled);

}  // namespace animorph
