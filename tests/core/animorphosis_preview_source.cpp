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
    REQUIRE(f->program.ops.size() == ref.ops.size());
    REQUIRE(f->program.primitiveCount() == ref.primitiveCount());
    CHECK(f->program.bounds().min == ref.bounds().min);
    CHECK(f->program.bounds().max == ref.bounds().max);
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
  CHECK(after->program.primitiveCount() > before->program.primitiveCount());
  CHECK(cache.compiler()->counters().firstCompiles == 1);
  CHECK(cache.compiler()->counters().refills == 0);
}
