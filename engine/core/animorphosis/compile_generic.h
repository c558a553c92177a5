#pragma once
// C(t) compiled straight into a FieldProgram, without the BlobTree snapshot of
// evaluate_generic.h: the program is byte for byte that of
// compileFieldProgram(instantiateGeneric(c, timing, t), 0, options) -- the same
// ops, primitives and floats in the same order -- at a fraction of the cost.
// The compiler is built once per C: its nodes in pre-order with their children,
// and the memory of their values at one time. compile() then takes every
// node's type at t, and flattens C(t) into a kept program through the BlobTree
// compiler's emitter (blobtree/compile_emit.h) while helper threads evaluate
// the nodes' blended parameters and expand the meta-primitives (spline-of-nodes
// frames, Coons triangles) into that kept memory, in chunks of nodes ahead of
// the emitter; scrubbing allocates nothing once warm.
#include <memory>
#include <vector>

#include "core/animorphosis/animorphosis_timing.h"
#include "core/animorphosis/generic_tree.h"
#include "core/blobtree/compile.h"

namespace animorph {

class GenericProgramCompiler {
 public:
  // c must outlive the compiler (hold it by shared_ptr beside it).
  explicit GenericProgramCompiler(const GenericTree& c);
  ~GenericProgramCompiler();
  GenericProgramCompiler(const GenericProgramCompiler&) = delete;
  GenericProgramCompiler& operator=(const GenericProgramCompiler&) = delete;

  // C at timeline time timeSec into out (whatever it held is replaced, its memory reused).
  // One call at a time per compiler (it keeps the values of the frame it compiles).
  void compile(const AnimorphosisTiming& timing, double timeSec, FieldProgram& out,
               const CompileOptions& options = {});
  // compile() refilling out (FieldProgram::beginRefill): the same program, out's op list kept when C at
  // timeSec has the structure out was last compiled with (a scrub: only values move), else rebuilt.
  // Returns which; lastTiming()'s finishSec is then the refill's finish.
  RefillOutcome refill(const AnimorphosisTiming& timing, double timeSec, FieldProgram& out,
                       const CompileOptions& options = {});
  const GenericTree& tree() const;
  size_t nodeCount() const;

  // Seconds the last compile() spent on the nodes' types (and spline counts), on emitting ops
  // and primitives (the values evaluated meanwhile, partly by the emitter), and in FieldProgram::finish.
  struct Timing {
    double typesSec = 0.0, emitSec = 0.0, finishSec = 0.0;
  };
  const Timing& lastTiming() const;
  // Nodes whose values the last compile() or refill() evaluated. The others kept the values of an
  // earlier frame: their inputs (type, s, the clip time of each side they read whose tracks move)
  // were bit for bit the same, so their values are too (scrubbing, nodes outside their s(u)
  // interval with constant tracks are not evaluated again).
  size_t lastEvaluatedNodes() const;
  // Whether compiles keep the values of nodes whose inputs did not move (on by default; off: every
  // node evaluated every frame, as before, the baseline of `bench animorph-compile`). The program is
  // the same either way.
  void keepValues(bool on);

  struct Impl;  // the nodes and their values (compile_generic.cpp)

 private:
  RefillOutcome build(const AnimorphosisTiming& timing, double timeSec, FieldProgram& out,
                      const CompileOptions& options, bool refill);
  std::unique_ptr<Impl> impl_;
};

}  // namespace animorph
