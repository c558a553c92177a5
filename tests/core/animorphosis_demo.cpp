#include <catch2/catch.hpp>

#include <functional>
#include <optional>
#include <random>
#include <string>

#include "core/animorphosis/auto_correspond.h"
#include "core/animorphosis/evaluate_generic.h"
#include "core/animorphosis/validate_correspondence.h"
#include "core/blobtree/blob_tree_json.h"
#include "core/blobtree/compile.h"
#include "core/blobtree/tree_edit.h"
#include "core/blobtree/validate.h"
#include "demo/animorphosis_demo.h"
#include "demo/dino_dragon.h"
#include "core/project/animorphosis_project.h"
#include "core/project/project_io.h"
#include "core/poly/polygonizer.h"
#include "util/animorph_fixtures.h"
#include "util/mesh_checks.h"

using namespace animorph;
using namespace animorph::test;

namespace {

size_t countType(const BlobNode& n, NodeType t) {
  size_t k = n.type == t ? 1 : 0;
  for (const auto& c : n.children) k += countType(c, t);
  return k;
}

Topology topologyOf(const FieldProgram& program, int resolution, std::optional<Bounds> bounds = std::nullopt) {
  PolygonizeSettings s;
  s.resolution = resolution;
  s.bounds = bounds;
  auto r = polygonize(program, s);
  REQUIRE(r.ok());
  REQUIRE(r->mesh.triangleCount() > 100);
  return weldedTopology(r->mesh.positions, r->mesh.indices);
}

const std::string kDemoProject = std::string(ANIMORPH_SOURCE_DIR) + "/resources/demo/animorphosis.animorph";

}  // namespace

TEST_CASE("animorphosis demo: the dinosaur and the dragon are at the paper's scale, valid and looping",
          "[animorph][demo]") {
  BlobTree dino = makeDinosaur();
  BlobTree dragon = makeDragon();
  INFO("dinosaur " << dino.root.subtreeSize() << " nodes, dragon " << dragon.root.subtreeSize() << " nodes");
  CHECK(dino.root.subtreeSize() >= 2000);
  CHECK(dragon.root.subtreeSize() >= 5000);
  CHECK(validateBlobTree(dino).ok());
  CHECK(validateBlobTree(dragon).ok());
  // About twenty joints; most nodes are meta-primitives and what they copy.
  CHECK(countType(dino.root, NodeType::Frame) == 20);
  size_t dinoMeta = countType(dino.root, NodeType::SplineOfNodes);
  CHECK(2 * dinoMeta > dino.root.subtreeSize() / 2);
  size_t dragonMeta = countType(dragon.root, NodeType::SplineOfNodes) + countType(dragon.root, NodeType::CoonsPatch);
  CHECK(dragonMeta > dragon.root.subtreeSize() / 2);
  CHECK(countType(dragon.root, NodeType::CoonsPatch) >= 4000);
  // Every animated track ends at the loop time, so each clip loops on its period.
  CHECK(animationEndSec(dino) == Approx(kDinosaurLoopSec));
  CHECK(animationEndSec(dragon) == Approx(kDragonLoopSec));
  // The clips loop without a jump: the field at the loop's end is the field at its start.
  for (const BlobTree* tree : {&dino, &dragon}) {
    double loop = tree == &dino ? kDinosaurLoopSec : kDragonLoopSec;
    FieldProgram start = compileFieldProgram(*tree, 0.0);
    FieldProgram end = compileFieldProgram(*tree, loop);
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> u(-1.5f, 1.5f);
    FieldEvaluator ev;
    for (int i = 0; i < 200; ++i) {
      glm::vec3 p(u(rng) * 1.5f, 1.4f + u(rng), u(rng));
      CHECK(ev.evaluatePoint(start, p) == Approx(ev.evaluatePoint(end, p)).margin(1e-4));
    }
  }
}

TEST_CASE("animorphosis demo: the committed project is what make-animorphosis-demo writes, and it validates",
          "[animorph][demo]") {
  auto p = loadProject(kDemoProject);
  REQUIRE(p.ok());
  REQUIRE(checkAnimorphosis(*p).ok());
  auto made = makeAnimorphosisDemoProject();
  REQUIRE(made.ok());
  REQUIRE(p->actors.size() == 2);
  CHECK(blobTreeToJson(p->actors[0].blobTree) == blobTreeToJson(made->actors[0].blobTree));
  CHECK(blobTreeToJson(p->actors[1].blobTree) == blobTreeToJson(made->actors[1].blobTree));
  CHECK(p->animorphosis.graph == made->animorphosis.graph);
  CHECK(p->animorphosis.startSec == kDemoMorphStartSec);
  CHECK(p->animorphosis.endSec == kDemoMorphEndSec);

  auto c = projectGenericTree(*p);
  REQUIRE(c.ok());
  INFO("generic tree: " << c->size() << " nodes, " << c->nullPartners << " null partners, " << c->splitCopies
                        << " split copies, " << p->animorphosis.graph.links.size() << " links");
  CHECK(c->size() >= 7000);
  CHECK(c->splitCopies == 0);
  // Overrides: the flight height, the pelvis (the global s again), the back (wings) and both hips.
  size_t overrides = 0;
  for (const auto& l : p->animorphosis.graph.links) overrides += l.sOverride ? 1 : 0;
  CHECK(overrides == 5);

  // The height is held down for the first third: at u = 0.3 the creature is still on the ground,
  // while the wings (under the back) are already large.
  AnimorphosisTiming timing = animorphosisTiming(*p);
  double t = kDemoMorphStartSec + 0.3 * (kDemoMorphEndSec - kDemoMorphStartSec);
  const GenericNode* flight = &c->root.children.at(0);
  REQUIRE(flight->a.name == "flight");
  CHECK(nodeS(*c, *flight, timing, t) == Approx(0.0f).margin(1e-6));
  const GenericNode* back = nullptr;
  std::function<void(const GenericNode&)> find = [&](const GenericNode& n) {
    if (n.a.name == "back") back = &n;
    for (const auto& k : n.children) find(k);
  };
  find(c->root);
  REQUIRE(back != nullptr);
  CHECK(nodeS(*c, *back, timing, t) > 0.5f);
  CHECK(nodeS(*c, *flight, timing, kDemoMorphEndSec) == 1.0f);
}

TEST_CASE("animorphosis demo: frames across the interval are watertight and manifold, the ends have the topology of "
          "the dinosaur and the dragon",
          "[animorph][demo]") {
  auto p = loadProject(kDemoProject);
  REQUIRE(p.ok());
  auto c = projectGenericTree(*p);
  REQUIRE(c.ok());
  AnimorphosisTiming timing = animorphosisTiming(*p);
  const int res = 40;
  for (double t : {kDemoMorphStartSec, 2.8, 3.6, 4.4, 5.2, kDemoMorphEndSec}) {
    Topology top = topologyOf(compileGeneric(*c, timing, t), res);
    INFO("t = " << t << ": " << top.components << " components, Euler characteristic " << top.eulerCharacteristic()
                << ", " << top.boundaryOrNonManifoldEdges << " open or non-manifold edges");
    CHECK(top.boundaryOrNonManifoldEdges == 0);
    CHECK(top.inconsistentEdges == 0);
  }
  const BlobTree& dino = p->actors[0].blobTree;
  const BlobTree& dragon = p->actors[1].blobTree;
  // C and the creature on the same grid (C's bounds also hold its parts of zero intensity).
  auto sameGrid = [&](const FieldProgram& x, const FieldProgram& y, Topology& tx, Topology& ty) {
    Bounds box = x.tightBounds();
    box.add(y.tightBounds());
    glm::vec3 margin(0.05f * box.diagonal());
    box.min -= margin;
    box.max += margin;
    tx = topologyOf(x, res, box);
    ty = topologyOf(y, res, box);
  };
  Topology first, a, last, b;
  sameGrid(compileGeneric(*c, timing, kDemoMorphStartSec),
           compileFieldProgram(dino, timing.source.localTime(kDemoMorphStartSec)), first, a);
  INFO("dinosaur: " << a.components << " components, Euler characteristic " << a.eulerCharacteristic());
  CHECK(first.components == a.components);
  CHECK(first.eulerCharacteristic() == a.eulerCharacteristic());
  sameGrid(compileGeneric(*c, timing, kDemoMorphEndSec),
           compileFieldProgram(dragon, timing.target.localTime(kDemoMorphEndSec)), last, b);
  INFO("dragon: " << b.components << " components, Euler characteristic " << b.eulerCharacteristic());
  CHECK(last.components == b.components);
  CHECK(last.eulerCharacteristic() == b.eulerCharacteristic());
}

TEST_CASE("animorphosis demo: auto-map recovers the dinosaur and the dragon from perturbed copies of themselves",
          "[animorph][demo]") {
  unsigned seed = 31;
  for (const BlobTree& a : {makeDinosaur(), makeDragon()}) {
    std::mt19937 rng(seed++);
    std::unordered_map<int, int> idMap;
    BlobTree b = perturbedCopy(a, {-2.0f, 0.5f, 1.5f}, 1.4f, rng, idMap, 0.002f);
    AutoCorrespondReport report;
    auto g = autoCorrespond(a, b, {}, {}, &report);
    REQUIRE(g.ok());
    REQUIRE(validateCorrespondence(a, b, *g).ok());
    double recovered = recoveredLinks(a, *g, idMap);
    INFO(a.root.name << ": " << a.root.subtreeSize() << " nodes, " << g->links.size() << " links, recovered "
                     << recovered * 100.0 << "%, mean confidence " << report.meanConfidence);
    CHECK(recovered >= 0.95);
  }
}
