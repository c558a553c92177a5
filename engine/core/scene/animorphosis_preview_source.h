#pragma once
// The animorphosis' C(t) as a PreviewSource: compiled straight from the
// generic tree (animorphosis/compile_generic.h) on the thread that polygonises it
// -- the preview worker, or the GPU path's field() -- with no BlobTree
// snapshot and no validation (C is built from validated trees; its program is
// the snapshot's, bit for bit, so the preview's meshes are the same).
#include <memory>
#include <mutex>
#include <vector>

#include "core/animorphosis/compile_generic.h"
#include "core/poly/preview_polygonizer.h"

namespace animorph {

// The compiler of one C, shared by the sources of its frames: compiles are serialised (the
// compiler keeps the values of the frame it compiles), each into the caller's program. A scrub
// changes C(t)'s values, rarely its structure: each compile refills the structure of the last one
// (FieldProgram::adoptStructure, GenericProgramCompiler::refill) instead of building the op list.
class SharedGenericCompiler {
 public:
  explicit SharedGenericCompiler(std::shared_ptr<const GenericTree> c);
  // C at timeSec into out (a fresh program, or one it compiled before), equal to a fresh compile.
  // Returns how: Refilled (the last compile's structure kept), else FirstCompile or StructureChanged.
  RefillOutcome compile(const AnimorphosisTiming& timing, double timeSec, FieldProgram& out);
  const std::shared_ptr<const GenericTree>& tree() const { return tree_; }
  // The compiles so far by how they ended.
  struct Counters {
    uint64_t refills = 0;           // the structure kept: only values computed
    uint64_t firstCompiles = 0;     // nothing kept yet
    uint64_t structureChanges = 0;  // C(t)'s op list differed from the last one's: built afresh
  };
  Counters counters() const;
  // A program for the next frame's compile: one of the compiler's kept programs that nobody else
  // holds any more (its memory and structure reused: no allocation, no structure copied once warm),
  // else a new one, kept while fewer than kProgramPool are. The caller holds it while it reads it.
  std::shared_ptr<FieldProgram> takeProgram();
  static constexpr size_t kProgramPool = 8;
  // Programs takeProgram handed out again (reused) and made (new), so far.
  struct PoolCounters {
    uint64_t reused = 0, made = 0;
  };
  PoolCounters poolCounters() const;

 private:
  std::shared_ptr<const GenericTree> tree_;
  mutable std::mutex mutex_;
  GenericProgramCompiler compiler_;
  FieldProgram structure_;  // the last compile's structure (its values empty): what the next one refills
  Counters counters_;
  std::vector<std::shared_ptr<FieldProgram>> pool_;  // takeProgram's kept programs
  PoolCounters poolCounters_;
};

// C at timeline time timeSec. Two sources are the same when they share the compiler (so C and its
// project revision) and the time.
std::shared_ptr<const PreviewSource> animorphosisPreviewSource(std::shared_ptr<SharedGenericCompiler> compiler,
                                                               const AnimorphosisTiming& timing, double timeSec);

}  // namespace animorph
