#include <catch2/catch.hpp>

#include <algorithm>

#include "core/animorphosis/compile_generic.h"
#include "core/project/animorphosis_project.h"
#include "core/scene/animorphosis_scene.h"
#include "demo/animorphosis_demo.h"

using namespace animorph;

namespace {

// The first node without children under n (a primitive).
const BlobNode* firstLeaf(const BlobNode& n) {
  if (n.children.empty()) return &n;
  for (const BlobNode& k : n.children)
    if (const BlobNode* leaf = firstLeaf(k)) return leaf;
  return nullptr;
}

int largestId(const BlobNode& n) {
  int id = n.id;
  for (const BlobNode& k : n.children) id = std::max(id, largestId(k));
  return id;
}

}  // namespace

TEST_CASE("preview: scrubbing C(t) refills without compiling (counted), an edit compiles",
          "[animorph][preview][refill]") {
  auto p = makeAnimorphosisDemoProject();
  REQUIRE(p.ok());
  AnimorphosisCache cache;
  const int owner = 0;
  auto c = cache.get(*p, &owner, 1);
  REQUIRE(c);
  const AnimorphosisTiming timing = animorphosisTiming(*p);
  const double mid = 0.5 * (kDemoMorphStartSec + kDemoMorphEndSec);
  GenericProgramCompiler fresh(*c);
  // A scrub: 12 frames 1/30 s apart in the middle of the morph, each a new source whose field (the GPU
  // preview's compile) comes through the cache's shared compiler.
  int outcomes[3] = {0, 0, 0};
  for (int k = 0; k < 12; ++k) {
    const double t = mid + k / 30.0;
    auto source = cache.previewSource(*p, t);
    REQUIRE(source);
    auto f = source->field(96);
    REQUIRE(f.ok());
    REQUIRE(f->refill.has_value());
    ++outcomes[int(*f->refill)];
    FieldProgram ref;
    fresh.compile(timing, t, ref);
    REQUIRE(f->fieldProgram().ops.size() == ref.ops.size());
    REQUIRE(f->fieldProgram().primitiveCount() == ref.primitiveCount());
    CHECK(f->fieldProgram().bounds().min == ref.bounds().min);
    CHECK(f->fieldProgram().bounds().max == ref.bounds().max);
  }
  INFO(outcomes[0] << " refilled, " << outcomes[1] << " first compiles, " << outcomes[2] << " structure changes");
  CHECK(outcomes[int(RefillOutcome::FirstCompile)] == 1);
  CHECK(outcomes[int(RefillOutcome::Refilled)] >= 10);
  SharedGenericCompiler::Counters n = cache.compiler()->counters();
  CHECK(n.refills == uint64_t(outcomes[int(RefillOutcome::Refilled)]));
  CHECK(n.firstCompiles == 1);
  CHECK(n.structureChanges == uint64_t(outcomes[int(RefillOutcome::StructureChanged)]));
  // The CPU preview worker's compile (polygonize) refills through the same compiler.
  auto cpu = cache.previewSource(*p, mid + 0.5);
  auto mesh = cpu->polygonize(32, 1, nullptr, nullptr);
  REQUIRE(mesh.ok());
  CHECK(mesh->mesh.triangleCount() > 0);
  CHECK(cache.compiler()->counters().refills + cache.compiler()->counters().structureChanges ==
        n.refills + n.structureChanges + 1);
  auto before = cache.previewSource(*p, mid)->field(96);
  REQUIRE(before.ok());

  // An edit of the source tree (one more primitive): a new C, compiled fully.
  Actor* source = nullptr;
  for (Actor& a : p->actors)
    if (a.id == p->animorphosis.sourceActorId) source = &a;
  REQUIRE(source);
  const BlobNode* leaf = firstLeaf(source->blobTree.root);
  REQUIRE(leaf);
  BlobNode extra = *leaf;
  extra.id = largestId(source->blobTree.root) + 1;
  source->blobTree.root.children.push_back(extra);
  auto edited = cache.get(*p, &owner, 2);
  INFO(cache.error());
  REQUIRE(edited);
  auto after = cache.previewSource(*p, mid)->field(96);
  REQUIRE(after.ok());
  REQUIRE(after->refill.has_value());
  CHECK(*after->refill == RefillOutcome::FirstCompile);
  CHECK(after->fieldProgram().primitiveCount() > before->fieldProgram().primitiveCount());
  CHECK(cache.compiler()->counters().firstCompiles == 1);
  CHECK(cache.compiler()->counters().refills == 0);
}

TEST_CASE("preview: the CPU worker's C(t) sources reuse a pooled program only once nobody holds it",
          "[animorph][preview][refill][pool]") {
  auto p = makeAnimorphosisDemoProject();
  REQUIRE(p.ok());
  auto c = projectGenericTree(*p);
  REQUIRE(c.ok());
  auto shared = std::make_shared<SharedGenericCompiler>(std::make_shared<const GenericTree>(*c));
  const AnimorphosisTiming timing = animorphosisTiming(*p);
  const double mid = 0.5 * (kDemoMorphStartSec + kDemoMorphEndSec);
  // Held programs are never handed out again: two held at once are two programs.
  std::shared_ptr<FieldProgram> a = shared->takeProgram(), b = shared->takeProgram();
  CHECK(a != b);
  CHECK(shared->poolCounters().made == 2);
  FieldProgram* aAddress = a.get();
  a.reset();  // let go: the next take reuses it
  std::shared_ptr<FieldProgram> again = shared->takeProgram();
  CHECK(again.get() == aAddress);
  CHECK(shared->poolCounters().reused == 1);
  again.reset();
  b.reset();
  // A scrub through sources polygonised one after another (the worker lets each go before the
  // next): every frame after the first reuses a program, and meshes equal a fresh compile's.
  GenericProgramCompiler fresh(*c);
  fresh.keepValues(false);
  const uint64_t madeBefore = shared->poolCounters().made;
  for (int k = 0; k < 4; ++k) {
    const double t = mid + k / 30.0;
    auto source = animorphosisPreviewSource(shared, timing, t);
    auto mesh = source->polygonize(24, 1, nullptr, nullptr);
    REQUIRE(mesh.ok());
    FieldProgram ref;
    fresh.compile(timing, t, ref);
    auto refMesh = polygonizePreviewProgram(ref, 24, 1, nullptr, nullptr);
    REQUIRE(refMesh.ok());
    CHECK(mesh->mesh.triangleCount() > 0);
    CHECK(mesh->mesh == refMesh->mesh);
  }
  CHECK(shared->poolCounters().made == madeBefore);  // the two programs made above served every frame
  // A source still held keeps its program: the next source gets another one.
  auto held = animorphosisPreviewSource(shared, timing, mid);
  REQUIRE(held->polygonize(24, 1, nullptr, nullptr).ok());
  auto next = animorphosisPreviewSource(shared, timing, mid + 0.1);
  REQUIRE(next->polygonize(24, 1, nullptr, nullptr).ok());
  const SharedGenericCompiler::PoolCounters n = shared->poolCounters();
  CHECK(n.reused >= 5);
  CHECK(n.made == madeBefore);
}
