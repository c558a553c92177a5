#pragma once
// Instantiating a BlobTree at time t and flattening it into a FieldProgram.
#include "core/blobtree/blob_tree.h"
#include "core/field/field_program.h"

namespace animorph {

struct CompileOptions {
  // Convolution segments are cut to 0 where their contribution is below
  // cutoffEpsilon * T (their bound). Smaller: exacter field, less culling.
  float cutoffEpsilon = 1e-3f;
};

// Evaluates every track at timeSec and flattens the tree (meta-primitives
// expanded, primitives of one class under one operator grouped into one op).
// The tree must be valid (validateBlobTree); values that animation pushes out
// of range between keys are clamped (radii to >= 0, q to >= 1, scales to non-zero).
FieldProgram compileFieldProgram(const BlobTree& tree, double timeSec, const CompileOptions& options = {});
// The same program built into `out` (whatever it held is replaced), reusing its memory: flattening
// every frame into one kept program allocates nothing once warm.
void compileFieldProgram(const BlobTree& tree, double timeSec, FieldProgram& out, const CompileOptions& options = {});
// The same program refilled into `out` (FieldProgram::beginRefill): out's op list is kept when the tree
// at timeSec flattens to the same one (an animation moving values only), else rebuilt. Returns which.
RefillOutcome refillFieldProgram(const BlobTree& tree, double timeSec, FieldProgram& out,
                                 const CompileOptions& options = {});

// The same tree appended to prog as one operand (prog not finished yet), under
// whatever maps prog has open: how a morph puts a BlobTree beside a stand-in.
// Its operators use prog.threshold, so that must be the tree's T at timeSec.
void appendBlobTree(FieldProgram& prog, const BlobTree& tree, double timeSec, const CompileOptions& options = {});

}  // namespace animorph
