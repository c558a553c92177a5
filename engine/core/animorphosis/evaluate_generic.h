#pragma once
// The generic tree C at a time t: a plain BlobTree snapshot whose every
// parameter is p_C(t) = (1 - s) p_A(tA) + s p_B(tB) (quaternions by slerp),
// compiled by the BlobTree compiler into the FieldProgram the CPU and GPU
// polygonisers and the preview already read. s is the node's s(u): the
// override of its nearest linked ancestor-or-self, else the global one; u <= 0
// gives A(tA) exactly and u >= 1 gives B(tB). A bridged blend / union /
// hyper-blend pair is a hyper-blend with q = (1 - s) q_A + s q_B in between.
#include "core/animorphosis/animorphosis_timing.h"
#include "core/animorphosis/generic_tree.h"
#include "core/blobtree/compile.h"

namespace animorph {

// s of a node of C at timeline time t.
float nodeS(const GenericTree& c, const GenericNode& n, const AnimorphosisTiming& timing, double timeSec);

// T of C at timeline time t: T_A(tA) before, T_B(tB) after, blended by the global s in between.
float genericThreshold(const GenericTree& c, const AnimorphosisTiming& timing, double timeSec);

// C at timeline time t as a BlobTree of constant tracks (ids 1..n in pre-order).
BlobTree instantiateGeneric(const GenericTree& c, const AnimorphosisTiming& timing, double timeSec);

// The same, written into `snapshot` (a previous result for the same C, or an
// empty tree), reusing its memory: scrubbing allocates nothing once every
// node has been seen at its current kind.
void updateGenericSnapshot(const GenericTree& c, const AnimorphosisTiming& timing, double timeSec, BlobTree& snapshot);

// compileFieldProgram of that snapshot (animorphosis/compile_generic.h gives the same program
// without the snapshot, faster).
FieldProgram compileGeneric(const GenericTree& c, const AnimorphosisTiming& timing, double timeSec,
                            const CompileOptions& options = {});

}  // namespace animorph
