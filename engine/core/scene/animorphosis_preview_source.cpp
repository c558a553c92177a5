#include "core/scene/animorphosis_preview_source.h"

#include <atomic>

namespace animorph {

SharedGenericCompiler::SharedGenericCompiler(std::shared_ptr<const GenericTree> c)
    : tree_(std::move(c)), compiler_(*tree_) {}

RefillOutcome SharedGenericCompiler::compile(const AnimorphosisTiming& timing, double timeSec, FieldProgram& out) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (out.structureIdentity() != structure_.structureIdentity()) out.adoptStructure(structure_);
  const RefillOutcome outcome = compiler_.refill(timing, timeSec, out);
  switch (outcome) {
    case RefillOutcome::Refilled: ++counters_.refills; break;
    case RefillOutcome::FirstCompile: ++counters_.firstCompiles; break;
    case RefillOutcome::StructureChanged: ++counters_.structureChanges; break;
  }
  if (outcome != RefillOutcome::Refilled) structure_.adoptStructure(out);
  return outcome;
}

std::shared_ptr<FieldProgram> SharedGenericCompiler::takeProgram() {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const std::shared_ptr<FieldProgram>& p : pool_)
    if (p.use_count() == 1) {  // only the pool holds it: whoever read it has let it go
      std::atomic_thread_fence(std::memory_order_acquire);
      ++poolCounters_.reused;
      return p;
    }
  ++poolCounters_.made;
  auto p = std::make_shared<FieldProgram>();
  if (pool_.size() < kProgramPool) pool_.push_back(p);
  return p;
}

SharedGenericCompiler::PoolCounters SharedGenericCompiler::poolCounters() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return poolCounters_;
}

SharedGenericCompiler::Counters SharedGenericCompiler::counters() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return counters_;
}

namespace {

class AnimorphosisSource final : public PreviewSource {
 public:
  AnimorphosisSource(std::shared_ptr<SharedGenericCompiler> compiler, const AnimorphosisTiming& timing, double timeSec)
      : compiler_(std::move(compiler)), timing_(timing), timeSec_(timeSec) {}
  bool sameAs(const PreviewSource& other) const override {
    auto* o = dynamic_cast<const AnimorphosisSource*>(&other);
    return o && o->compiler_ == compiler_ && o->timeSec_ == timeSec_;
  }
  // Like a BlobTree's preview: on the last frame's grid while C fits in it, its blocks reused.
  Result<PolygonizeResult> polygonize(int resolution, int threads, const std::atomic<bool>* cancel,
                                      PolygonizeHistory* history) const override {
    std::call_once(compiled_, [&] {
      program_ = compiler_->takeProgram();
      compiler_->compile(timing_, timeSec_, *program_);
    });
    return polygonizePreviewProgram(*program_, resolution, threads, cancel, history);
  }
  Result<PreviewField> field(int) const override {
    // From the pool like polygonize()'s: the GPU's compiled field holds it while it is drawn.
    PreviewField f;
    f.pooledProgram = compiler_->takeProgram();
    f.refill = compiler_->compile(timing_, timeSec_, *f.pooledProgram);
    return f;
  }

 private:
  std::shared_ptr<SharedGenericCompiler> compiler_;
  AnimorphosisTiming timing_;
  double timeSec_;
  mutable std::once_flag compiled_;  // the worker compiles once for both levels
  // From the compiler's pool (SharedGenericCompiler::takeProgram): back to it when this source goes.
  mutable std::shared_ptr<FieldProgram> program_;
};

}  // namespace

std::shared_ptr<const PreviewSource> animorphosisPreviewSource(std::shared_ptr<SharedGenericCompiler> compiler,
                                                               const AnimorphosisTiming& timing, double timeSec) {
  return std::make_shared<const AnimorphosisSource>(std::move(compiler), timing, timeSec);
}

}  // namespace animorph
