#pragma once
// The animorphosis' C(t) as a PreviewSource: compiled straight from the
// generic tree (animorphosis/compile_generic.h) on the thread that polygonises it
// -- the preview worker, or the GPU path's field() -- with no BlobTree
// snapshot and no validation (C is built from validated trees; its program is
// the snapshot's, bit for bit, so the preview's meshes are the same).
#include <memory>
#include <mutex>

#include "core/animorphosis/compile_generic.h"
#include "core/poly/preview_polygonizer.h"

namespace animorph {

// The compiler of one C, shared by the sources of its frames: compiles are serialised (the
// compiler keeps the values of the frame it compiles), each into the caller's program.
class SharedGenericCompiler {
 public:
  explicit SharedGenericCompiler(std::shared_ptr<const GenericTree> c);
  void compile(const AnimorphosisTiming& timing, double timeSec, FieldProgram& out);
  const std::shared_ptr<const GenericTree>& tree() const { return tree_; }

 private:
  std::shared_ptr<const GenericTree> tree_;
  std::mutex mutex_;
  GenericProgramCompiler compiler_;
};

// C at timeline time timeSec. Two sources are the same when they share the compiler (so C and its
// project revision) and the time.
std::shared_ptr<const PreviewSource> animorphosisPreviewSource(std::shared_ptr<SharedGenericCompiler> compiler,
                                                               const AnimorphosisTiming& timing, double timeSec);

}  // namespace animorph
