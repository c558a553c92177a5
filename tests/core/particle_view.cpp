// The viewport's particle view (editor/particle_view.h): which BlobTree draws are shown as particles.
#include <catch2/catch.hpp>

#include <algorithm>

#include "demo/dino_dragon.h"
#include "editor/particle_view.h"
#include "util/blob_builders.h"

using namespace animorph;
using namespace animorph::test;

namespace {

Project projectWithPoints(int points, float apart = 0.1f) {
  std::vector<BlobNode> children;
  for (int i = 0; i < points; ++i) children.push_back(pointNode(2 + i, glm::vec3(apart * float(i), 0.5f, 0.0f), 0.2f, 2.0f));
  Actor a;
  a.id = "cloud";
  a.kind = ActorKind::BlobTree;
  a.blobTree = treeOf(operatorNode(NodeType::Blend, 1, std::move(children)), 1.0f);
  Project p;
  p.actors.push_back(a);
  return p;
}

SceneFrame frameAt(double treeTimeSec) {
  SceneFrame f;
  BlobDraw d;
  d.actorId = "cloud";
  d.treeTimeSec = treeTimeSec;
  d.model = glm::mat4(2.0f);
  d.model[3][3] = 1.0f;
  f.blobs.push_back(d);
  return f;
}

// The project's draw keeps its surface (never particles) over `frames` frames whose time changes.
void checkAlwaysSurface(const Project& p, int frames) {
  ParticleView view;
  ParticleViewSettings s;
  for (int k = 0; k < frames; ++k) {
    SceneFrame f = frameAt(0.1 * k);
    CHECK(view.takeMoving(f, p, 0.1 * k, s).empty());
    CHECK(f.blobs.size() == 1);
  }
}

}  // namespace

TEST_CASE("the particle view shows a particle system as particles while its time changes, then its surface",
          "[particles][view]") {
  const Project p = projectWithPoints(100);
  ParticleView view;
  ParticleViewSettings s;
  auto never = [](const std::string&) { return false; };
  auto always = [](const std::string&) { return true; };

  // First seen: the surface.
  SceneFrame f = frameAt(0.0);
  CHECK(view.takeMoving(f, p, 0.0, s).empty());
  CHECK(f.blobs.size() == 1);
  CHECK(view.takeUnready(f, p, never).empty());
  CHECK_FALSE(view.pending());

  // The time changes: particles, no surface draw left for the previews.
  f = frameAt(0.5);
  auto moving = view.takeMoving(f, p, 1.0, s);
  REQUIRE(moving.size() == 1);
  CHECK(f.blobs.empty());
  CHECK(moving[0].actorId == "cloud");
  REQUIRE(moving[0].centres.size() == 100);
  REQUIRE(moving[0].radii.size() == 100);
  CHECK(moving[0].centres[3].x == Approx(0.3f));
  CHECK(moving[0].radii[0] > 0.0f);
  CHECK(moving[0].radii[0] < 0.2f);
  CHECK(moving[0].model[0][0] == 2.0f);
  CHECK(view.pending());

  // Held for less than holdSec: still particles.
  f = frameAt(0.5);
  CHECK(view.takeMoving(f, p, 1.0 + 0.5 * s.holdSec, s).size() == 1);

  // Held long enough: the previews get the draw; until its surface is ready it is still shown as particles.
  f = frameAt(0.5);
  CHECK(view.takeMoving(f, p, 2.0, s).empty());
  CHECK(f.blobs.size() == 1);
  CHECK(view.takeUnready(f, p, never).size() == 1);
  CHECK(f.blobs.empty());
  CHECK(view.pending());
  f = frameAt(0.5);
  CHECK(view.takeMoving(f, p, 2.1, s).empty());
  CHECK(view.takeUnready(f, p, always).empty());
  CHECK(f.blobs.size() == 1);
  CHECK_FALSE(view.pending());
  // Once shown, the surface stays (a later refinement does not bring the particles back).
  f = frameAt(0.5);
  CHECK(view.takeMoving(f, p, 2.2, s).empty());
  CHECK(view.takeUnready(f, p, never).empty());

  // Dragging the playhead without moving it (holding) keeps the particles.
  s.holding = true;
  f = frameAt(0.5);
  CHECK(view.takeMoving(f, p, 3.0, s).size() == 1);

  // Off: always the surface.
  s.holding = false;
  s.enabled = false;
  f = frameAt(0.75);
  CHECK(view.takeMoving(f, p, 4.0, s).empty());
  CHECK(f.blobs.size() == 1);
}

TEST_CASE("a BlobTree of few point primitives is never shown as particles", "[particles][view]") {
  const Project p = projectWithPoints(10);
  checkAlwaysSurface(p, 3);
  CHECK(particleDraw(frameAt(0.0).blobs[0], p, 64).centres.empty());
  CHECK(particleDraw(frameAt(0.0).blobs[0], p, 10).centres.size() == 10);
}

TEST_CASE("points under a frame or a meta-primitive are not particles: a creature keeps its surface while it moves",
          "[particles][view]") {
  // The demo's dinosaur: hundreds of point primitives, each a template of a spline of nodes under
  // its joint's frame (their centres are not places in the tree's space).
  Project p;
  Actor a;
  a.id = "cloud";
  a.kind = ActorKind::BlobTree;
  a.blobTree = makeDinosaur();
  p.actors.push_back(a);
  CHECK(treeParticles(a.blobTree, 0.5).nodeIds.empty());
  checkAlwaysSurface(p, 4);
  CHECK(particleDraw(frameAt(0.0).blobs[0], p, 1).centres.empty());

  // Beside 100 particles under the root's blend, 100 points under a frame: only the first 100 count.
  Project mixed = projectWithPoints(100);
  std::vector<BlobNode> framed;
  for (int i = 0; i < 100; ++i) framed.push_back(pointNode(1000 + i, glm::vec3(0.0f, 5.0f, 0.0f), 0.2f, 2.0f));
  mixed.actors[0].blobTree.root.children.push_back(operatorNode(NodeType::Frame, 999, std::move(framed)));
  const ParticleDraw pd = particleDraw(frameAt(0.0).blobs[0], mixed, 64);
  REQUIRE(pd.centres.size() == 100);
  CHECK(std::all_of(pd.centres.begin(), pd.centres.end(), [](const glm::vec3& c) { return c.y < 1.0f; }));
}

TEST_CASE("particles spread too far for the surface's grid stay particles while the time holds", "[particles][view]") {
  // 100 particles (visible radius < 0.2) 0.5 m apart: 50 m, cells of 0.39 m at 128^3: the grid's
  // corners would miss them. 0.1 m apart: 10 m, 0.08 m cells: the surface resolves them.
  const Project spread = projectWithPoints(100, 0.5f), close = projectWithPoints(100, 0.1f);
  ParticleViewSettings s;
  s.surfaceResolution = 128;
  float cell = 0.0f, radius = 0.0f;
  CHECK(particlesBelowGrid(particleDraw(frameAt(0.0).blobs[0], spread, 64), 128, &cell, &radius));
  CHECK(cell == Approx(50.0f / 128.0f).epsilon(0.02));
  CHECK(radius > 0.0f);
  CHECK(radius < 0.5f * cell);
  CHECK_FALSE(particlesBelowGrid(particleDraw(frameAt(0.0).blobs[0], close, 64), 128));
  CHECK_FALSE(particlesBelowGrid(particleDraw(frameAt(0.0).blobs[0], spread, 64), 0));  // no grid given
  // Points that show only together (each alone under the threshold: visible radius 0) are no
  // particles to lose: the surface (the animorphosis demo's dinosaur has such points).
  ParticleDraw together = particleDraw(frameAt(0.0).blobs[0], spread, 64);
  std::fill(together.radii.begin(), together.radii.end(), 0.0f);
  CHECK_FALSE(particlesBelowGrid(together, 128));

  ParticleView view;
  SceneFrame f = frameAt(0.0);
  auto held = view.takeMoving(f, spread, 10.0, s);
  REQUIRE(held.size() == 1);
  CHECK(f.blobs.empty());  // no surface to polygonise
  CHECK(held[0].centres.size() == 100);
  CHECK(view.note().find("cloud") != std::string::npos);
  CHECK(view.note().find("128^3") != std::string::npos);
  CHECK_FALSE(view.pending());  // it does not turn into a surface by itself
  // Also for a screenshot (which otherwise shows the surface).
  s.settle = true;
  f = frameAt(0.0);
  CHECK(view.takeMoving(f, spread, 20.0, s).size() == 1);

  ParticleView closeView;
  f = frameAt(0.0);
  CHECK(closeView.takeMoving(f, close, 10.0, s).empty());
  CHECK(f.blobs.size() == 1);
  CHECK(closeView.note().empty());
}

TEST_CASE("particles carry their points' colours at the draw's time (keyed colours included)", "[particles][view]") {
  Project p = projectWithPoints(3);
  BlobNode& root = p.actors[0].blobTree.root;
  root.children[0].vec3Param("color") = Vec3Track(glm::vec3(1.0f, 0.0f, 0.0f));
  Vec3Track keyed;
  keyed.setKey(0.0, glm::vec3(0.0f, 0.0f, 1.0f), KeyInterp::Linear);
  keyed.setKey(1.0, glm::vec3(0.0f, 1.0f, 0.0f), KeyInterp::Linear);
  root.children[2].vec3Param("color") = keyed;
  for (double t : {0.0, 0.25, 1.0}) {
    const ParticleDraw d = particleDraw(frameAt(t).blobs[0], p, 3);
    REQUIRE(d.colors.size() == 3);
    CHECK(d.colors[0] == glm::vec3(1.0f, 0.0f, 0.0f));
    CHECK(d.colors[1] == kDefaultBlobColor);  // no colour of its own: the clay tone
    CHECK(d.colors[2].y == Approx(float(t)));
    CHECK(d.colors[2].z == Approx(1.0f - float(t)));
  }
  CHECK(particleDraw(frameAt(1.0).blobs[0], p, 4).colors.empty());  // fewer particles than asked: none
}
