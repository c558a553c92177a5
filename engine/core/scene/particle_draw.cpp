#include "core/scene/particle_draw.h"

#include <algorithm>

#include "core/math/bounds.h"

namespace animorph {

namespace {

// The draw's tree; the animorphosis' C(t) snapshot stays alive in its cache until the next frame's.
const BlobTree* drawTree(const BlobDraw& d, const Project& project) {
  if (auto own = d.ownTree()) return own.get();
  const Actor* a = project.findActor(d.actorId);
  return a && a->kind == ActorKind::BlobTree ? &a->blobTree : nullptr;
}

// Whether the tree has at least `enough` particles (points reached through operators only).
bool hasParticles(const BlobTree& tree, size_t enough) {
  size_t c = 0;
  forEachParticleNode(tree.root, [&](const BlobNode&) { ++c; });
  return c >= enough;
}

}  // namespace

const BlobTree* particleTree(const BlobDraw& draw, const Project& project, size_t minParticles) {
  const BlobTree* tree = drawTree(draw, project);
  return tree && hasParticles(*tree, minParticles) ? tree : nullptr;
}

ParticleDraw particleDraw(const BlobDraw& draw, const Project& project, size_t minParticles) {
  ParticleDraw out;
  out.actorId = draw.actorId;
  out.model = draw.model;
  const BlobTree* tree = particleTree(draw, project, minParticles);
  if (!tree) return out;
  TreeParticles tp = treeParticles(*tree, draw.treeTimeSec);
  out.centres = std::move(tp.set.position);
  out.radii = std::move(tp.set.radius);
  out.colors.reserve(out.centres.size());
  forEachParticleNode(tree->root, [&](const BlobNode& n) { out.colors.push_back(n.vec3Param("color").evaluate(draw.treeTimeSec)); });
  return out;
}

bool particlesBelowGrid(const ParticleDraw& draw, int resolution, float* cellSize, float* medianRadius) {
  if (resolution <= 0 || draw.centres.empty()) return false;
  Bounds b;
  for (size_t i = 0; i < draw.centres.size(); ++i) {
    const float r = i < draw.radii.size() ? draw.radii[i] : 0.0f;
    b.add(draw.centres[i] - glm::vec3(r));
    b.add(draw.centres[i] + glm::vec3(r));
  }
  const glm::vec3 size = b.size();
  const float cell = std::max({size.x, size.y, size.z}) / float(resolution);
  std::vector<float> radii = draw.radii;
  radii.resize(draw.centres.size(), 0.0f);
  std::nth_element(radii.begin(), radii.begin() + long(radii.size() / 2), radii.end());
  const float median = radii[radii.size() / 2];
  if (cellSize) *cellSize = cell;
  if (medianRadius) *medianRadius = median;
  // A median of 0: points that show only together (each alone stays under the threshold, as in a
  // creature's blend), not separate particles: their surface is what the grid must resolve.
  return median > 0.0f && median < 0.5f * cell;
}

}  // namespace animorph
