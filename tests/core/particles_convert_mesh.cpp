// Convert to particles from a triangle mesh's inside (particles/mesh_inside.h) and from a
// character's stand-in or posed mesh (doc/particle_commands.h characterParticlesActor).
#include <catch2/catch.hpp>

#include <atomic>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "core/blobtree/compile.h"
#include "core/doc/actor_commands.h"
#include "core/doc/document.h"
#include "core/doc/particle_commands.h"
#include "core/io/gltf_import.h"
#include "core/particles/character_shape.h"
#include "core/particles/mesh_inside.h"
#include "core/poly/mesh_checks.h"
#include "core/poly/polygonizer.h"
#include "core/scene/scene_frame.h"
#include "util/manifold_checks.h"
#include "util/morph_fixtures.h"
#include "util/test_skip.h"

using namespace animorph;

namespace {

// An axis-aligned box, counter-clockwise seen from outside (inward when flipped).
TriangleMesh boxMesh(glm::vec3 lo, glm::vec3 hi, bool flipped = false) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) m.positions.push_back({i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z});
  const uint32_t faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& f : faces) {
    const uint32_t tri[6] = {f[0], f[1], f[2], f[0], f[2], f[3]};
    for (int k = 0; k < 6; ++k) m.indices.push_back(tri[flipped ? 5 - k : k]);
  }
  return m;
}

// A latitude-longitude sphere (shared poles and seam: closed), counter-clockwise outside.
TriangleMesh sphereMesh(glm::vec3 centre, float radius, int rings, int sectors) {
  TriangleMesh m;
  m.positions.push_back(centre + glm::vec3(0.0f, radius, 0.0f));
  for (int r = 1; r < rings; ++r)
    for (int s = 0; s < sectors; ++s) {
      const float th = float(M_PI) * float(r) / float(rings), ph = 2.0f * float(M_PI) * float(s) / float(sectors);
      m.positions.push_back(centre + radius * glm::vec3(std::sin(th) * std::cos(ph), std::cos(th), -std::sin(th) * std::sin(ph)));
    }
  m.positions.push_back(centre - glm::vec3(0.0f, radius, 0.0f));
  const uint32_t south = uint32_t(m.positions.size() - 1);
  auto at = [&](int r, int s) { return uint32_t(1 + (r - 1) * sectors + (s % sectors)); };
  for (int s = 0; s < sectors; ++s) {
    m.indices.insert(m.indices.end(), {0u, at(1, s), at(1, s + 1)});
    m.indices.insert(m.indices.end(), {south, at(rings - 1, s + 1), at(rings - 1, s)});
    for (int r = 1; r + 1 < rings; ++r)
      m.indices.insert(m.indices.end(), {at(r, s), at(r + 1, s), at(r + 1, s + 1), at(r, s), at(r + 1, s + 1), at(r, s + 1)});
  }
  return m;
}

// Polygonised at res over box grown by 5 % of its diagonal.
double grownVolume(const FieldProgram& program, Bounds box, int res) {
  box.min -= glm::vec3(0.05f * box.diagonal());
  box.max += glm::vec3(0.05f * box.diagonal());
  return test::polygonisedVolume(program, box, res);
}

// The particle tree's volume polygonised at res around its own bounds and the shape's.
double particleVolume(const BlobTree& tree, const Bounds& shape, int res) {
  FieldProgram p = compileFieldProgram(tree, 0.0);
  Bounds box = shape;
  box.add(p.tightBounds());
  return grownVolume(p, box, res);
}

SampleLattice lattice(glm::vec3 origin, float spacing, int n) { return {origin, spacing, glm::ivec3(n)}; }

// Every lattice point farther than margin from the box's faces is classified as the box says.
void checkBoxInside(const std::vector<uint8_t>& inside, const SampleLattice& g, glm::vec3 lo, glm::vec3 hi) {
  size_t wrong = 0, checked = 0;
  for (int z = 0; z < g.dims.z; ++z)
    for (int y = 0; y < g.dims.y; ++y)
      for (int x = 0; x < g.dims.x; ++x) {
        const glm::vec3 p = g.point(x, y, z);
        const glm::vec3 d = glm::min(p - lo, hi - p);  // > 0 inside along each axis
        const float m = std::min({d.x, d.y, d.z});
        if (std::abs(m) < 1e-4f) continue;  // on a face
        ++checked;
        wrong += (m > 0.0f) != (inside[g.index(x, y, z)] != 0);
      }
  CHECK(checked > 0);
  CHECK(wrong == 0);
}

}  // namespace

TEST_CASE("particles: a closed mesh's inside on a lattice is exact, on and off its faces", "[particles][convert][mesh]") {
  const glm::vec3 lo(-0.5f), hi(0.5f, 0.3f, 0.5f);
  // Faces between lattice points, then through them (rays run along faces and edges), both orientations.
  for (float spacing : {0.07f, 0.1f})
    for (bool flipped : {false, true}) {
      MeshInside mesh(boxMesh(lo, hi, flipped));
      CHECK(mesh.closed());
      CHECK(mesh.info().triangles == 12);
      CHECK(mesh.info().volume == Approx(0.8).epsilon(1e-5));
      const SampleLattice g = lattice(glm::vec3(-1.0f), spacing, int(2.0f / spacing) + 1);
      INFO("spacing " << spacing << (flipped ? ", inward" : ", outward"));
      checkBoxInside(mesh.insideOnLattice(g), g, lo, hi);
    }
  // Two overlapping closed boxes: their union (winding 2 where they overlap is inside too).
  TriangleMesh two = boxMesh(glm::vec3(-0.5f), glm::vec3(0.2f));
  TriangleMesh b = boxMesh(glm::vec3(-0.1f), glm::vec3(0.5f));
  for (uint32_t& i : b.indices) i += uint32_t(two.positions.size());
  two.positions.insert(two.positions.end(), b.positions.begin(), b.positions.end());
  two.indices.insert(two.indices.end(), b.indices.begin(), b.indices.end());
  MeshInside both(two);
  const SampleLattice g = lattice(glm::vec3(-0.73f), 0.061f, 25);
  const std::vector<uint8_t> in = both.insideOnLattice(g);
  size_t wrong = 0;
  for (int z = 0; z < 25; ++z)
    for (int y = 0; y < 25; ++y)
      for (int x = 0; x < 25; ++x) {
        const glm::vec3 p = g.point(x, y, z);
        const bool inA = glm::all(glm::greaterThan(p, glm::vec3(-0.5f))) && glm::all(glm::lessThan(p, glm::vec3(0.2f)));
        const bool inB = glm::all(glm::greaterThan(p, glm::vec3(-0.1f))) && glm::all(glm::lessThan(p, glm::vec3(0.5f)));
        wrong += (inA || inB) != (in[g.index(x, y, z)] != 0);
      }
  CHECK(wrong == 0);
}

TEST_CASE("particles: a mesh with a hole reports its boundary edges and is still filled", "[particles][convert][mesh]") {
  const glm::vec3 lo(-0.5f), hi(0.5f);
  TriangleMesh open = boxMesh(lo, hi);
  open.indices.erase(open.indices.begin() + 18, open.indices.begin() + 24);  // the top face (+y)
  MeshInside mesh(open);
  CHECK_FALSE(mesh.closed());
  CHECK(mesh.info().boundaryEdges == 4);
  const SampleLattice g = lattice(glm::vec3(-0.93f), 0.09f, 22);
  // A ray along y leaves through the hole; those along x and z still find the inside.
  checkBoxInside(mesh.insideOnLattice(g), g, lo, hi);
  // Seam duplicates (same positions, other indices) are welded: no boundary edge.
  TriangleMesh split = boxMesh(lo, hi);
  const size_t n = split.positions.size();
  split.positions.insert(split.positions.end(), split.positions.begin(), split.positions.end());
  for (size_t t = 0; t < split.indices.size(); t += 6)
    for (size_t k = t; k < t + 3; ++k) split.indices[k] += uint32_t(n);  // one triangle of each face
  CHECK(MeshInside(split).closed());
}

TEST_CASE("particles: a sphere mesh and a box mesh convert to N..N+1 % particles keeping the volume within 2 %",
          "[particles][convert][mesh]") {
  struct Case {
    const char* name;
    TriangleMesh mesh;
    int count;
    double slack;  // most particles made / asked
  };
  TriangleMesh turned = boxMesh(glm::vec3(-0.3f, 0.0f, -0.2f), glm::vec3(0.3f, 0.4f, 0.1f));
  const glm::mat3 turn = glm::mat3(glm::rotate(glm::mat4(1.0f), 0.7f, glm::normalize(glm::vec3(1.0f, 2.0f, 3.0f))));
  for (glm::vec3& p : turned.positions) p = turn * p;
  // A box along the lattice's axes loses or gains whole layers of points as the spacing changes
  // (and a shift of the lattice moves whole layers too): 2,052 for 2,000 asked.
  for (const Case& c : {Case{"sphere", sphereMesh(glm::vec3(0.2f, 1.0f, -0.3f), 0.4f, 48, 96), 3000, 1.01},
                        Case{"turned box", turned, 2000, 1.01},
                        Case{"box along the axes", boxMesh(glm::vec3(-0.3f, 0.0f, -0.2f), glm::vec3(0.3f, 0.4f, 0.1f)),
                             2000, 1.03}}) {
    MeshInside mesh(c.mesh);
    REQUIRE(mesh.closed());
    auto shape = meshParticleShape(mesh);
    REQUIRE(shape);
    ConvertToParticlesSettings s;
    s.count = c.count;
    auto conv = convertToParticles(*shape, s);
    REQUIRE(conv);
    const auto& rep = conv->report;
    INFO(c.name << ": " << rep.particles << " particles, mesh " << mesh.info().volume << " m^3, grid "
                << rep.shapeVolume << " m^3");
    CHECK(rep.particles >= size_t(c.count));
    CHECK(double(rep.particles) <= c.slack * c.count);
    CHECK(conv->tree.root.children.size() == rep.particles);
    CHECK(std::abs(rep.shapeVolume - mesh.info().volume) <= 0.02 * mesh.info().volume);
    const double v = particleVolume(conv->tree, mesh.info().bounds, 96);
    INFO("particles polygonised at 96^3: " << v << " m^3");
    CHECK(std::abs(v - mesh.info().volume) <= 0.02 * mesh.info().volume);
  }
}

TEST_CASE("particles: a character's stand-in and posed mesh convert to a new particle actor",
          "[particles][convert][character]") {
  const std::string dir = ANIMORPH_SHARED_ASSETS;
  const Project* morph = test::tentaclePlateMorph(dir);
  if (!morph) {
    ANIMORPH_SKIP(dir << "/tentacle.glb not present: skipped");
  }
  auto tentacle = importGltf(dir + "/tentacle.glb");
  REQUIRE(tentacle);
  const Actor& character = morph->actors.at(0);
  REQUIRE(character.kind == ActorKind::Gltf);
  REQUIRE(morph->morph.findActor(character.id));
  const double t = 0.5;

  // The character converted from `from` to count particles: a new BlobTree actor, N..N + 1 %.
  CharacterParticlesReport rep;
  auto convert = [&](ParticleSource from, int count) {
    ConvertToParticlesSettings s;
    s.count = count;
    auto a = characterParticlesActor(*morph, character.id, *tentacle, t, from, s, &rep);
    REQUIRE(a);
    CHECK(a->kind == ActorKind::BlobTree);
    CHECK(a->transform == character.transform);
    CHECK_FALSE(morph->findActor(a->id));  // a new id
    CHECK(rep.convert.particles >= size_t(count));
    CHECK(double(rep.convert.particles) <= 1.01 * count);
    return *a;
  };

  SECTION("stand-in: within 2 % of the stand-in's polygonised volume") {
    const Actor a = convert(ParticleSource::Standin, 2000);
    CHECK_FALSE(rep.standinFitted);  // the morph's stand-in
    const AnimationClip* clip = character.clip < int(tentacle->clips.size()) ? &tentacle->clips[size_t(character.clip)] : nullptr;
    REQUIRE(clip);
    const FieldProgram standin = posedStandinProgram(
        *tentacle, morph->morph.findActor(character.id)->standin, clip, float(actorClipTimeSec(character, *clip, t)));
    Bounds box = standin.tightBounds();
    const double v0 = grownVolume(standin, box, 96);
    const double v1 = particleVolume(a.blobTree, box, 96);
    INFO("stand-in " << v0 << " m^3, particles " << v1 << " m^3");
    CHECK(std::abs(v1 - v0) <= 0.02 * v0);
  }
  SECTION("mesh: filled, its boundary edges reported") {
    const Actor a = convert(ParticleSource::Mesh, 1500);
    INFO(rep.triangles << " triangles, " << rep.boundaryEdges << " boundary edges, mesh " << rep.meshVolume
                       << " m^3, grid " << rep.convert.shapeVolume << " m^3");
    CHECK(rep.triangles == tentacle->totalTriangles());
    if (rep.boundaryEdges == 0) {
      CHECK(std::abs(rep.convert.shapeVolume - rep.meshVolume) <= 0.02 * rep.meshVolume);
      const double v = particleVolume(a.blobTree, Bounds{}, 96);
      CHECK(std::abs(v - rep.meshVolume) <= 0.03 * rep.meshVolume);
    }
  }
  SECTION("one undo step adding the actor; cancel makes no actor and leaves the document as it was") {
    Document d;
    d.reset(*morph, "");
    const Project before = d.project();
    std::atomic<bool> cancel{true};
    ConvertToParticlesSettings s;
    s.count = 500;
    s.cancel = &cancel;
    auto cancelled = characterParticlesActor(d.project(), character.id, *tentacle, t, ParticleSource::Mesh, s);
    REQUIRE_FALSE(cancelled);
    CHECK(cancelled.error().find("cancelled") != std::string::npos);
    CHECK(d.project() == before);
    cancel = false;
    auto a = characterParticlesActor(d.project(), character.id, *tentacle, t, ParticleSource::Standin, s);
    REQUIRE(a);
    const std::string id = a->id;
    d.execute(addActorCommand(std::move(*a)));
    CHECK(d.project().actors.size() == before.actors.size() + 1);
    CHECK(*d.project().findActor(character.id) == *before.findActor(character.id));
    d.undo();
    CHECK(d.project() == before);
    CHECK_FALSE(d.project().findActor(id));
    // Not a character: refused, naming the actor.
    auto refused = characterParticlesActor(d.project(), "nobody", *tentacle, t, ParticleSource::Mesh, s);
    REQUIRE_FALSE(refused);
    CHECK(refused.error().find("'nobody'") != std::string::npos);
  }
}
