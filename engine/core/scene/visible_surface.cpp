#include "core/scene/visible_surface.h"

#include <algorithm>
#include <limits>

#include <tbb/parallel_for.h>

#include "core/standin_morph/mesh_distance.h"
#include "core/scene/standin_core.h"
#include "core/poly/clip_mesh.h"
#include "core/poly/inside_mesh.h"

namespace animorph {

namespace {

// The part of shell `from` made of the triangles [first, end) of m, vertices renumbered.
TriangleMesh shellOf(const TriangleMesh& m, size_t first, size_t end) {
  TriangleMesh out;
  std::vector<uint32_t> map(m.positions.size(), UINT32_MAX);
  const bool normals = m.normals.size() == m.positions.size(), colors = m.colors.size() == m.positions.size();
  for (size_t i = 3 * first; i < 3 * end; ++i) {
    const uint32_t v = m.indices[i];
    if (map[v] == UINT32_MAX) {
      map[v] = uint32_t(out.positions.size());
      out.positions.push_back(m.positions[v]);
      if (normals) out.normals.push_back(m.normals[v]);
      if (colors) out.colors.push_back(m.colors[v]);
    }
    out.indices.push_back(map[v]);
  }
  return out;
}

// The core's field (f - T, > 0 inside the core) at every vertex of mesh.
std::vector<float> coreFieldAt(const FieldProgram& core, const TriangleMesh& mesh) {
  std::vector<float> value(mesh.positions.size());
  ActiveProgram all;
  core.specialiseAll(all);
  constexpr size_t kChunk = 1024;
  const size_t chunks = (value.size() + kChunk - 1) / kChunk;
  tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
    thread_local FieldEvaluator eval;
    const size_t first = c * kChunk, n = std::min(kChunk, value.size() - first);
    std::vector<float> x(n), y(n), z(n);
    for (size_t i = 0; i < n; ++i) {
      const glm::vec3& p = mesh.positions[first + i];
      x[i] = p.x, y[i] = p.y, z[i] = p.z;
    }
    eval.evaluate(core, all, x.data(), y.data(), z.data(), int(n), value.data() + first);
  });
  return value;
}

}  // namespace

void splitStandinCore(const MorphFrame& fr, TriangleMesh& mesh, TriangleMesh& core) {
  const size_t n = fr.mesh.triangleCount(), k = std::min(fr.coreTriangles, n);
  mesh = shellOf(fr.mesh, 0, n - k);
  core = shellOf(fr.mesh, n - k, n);
}

TriangleMesh visibleSurface(const MorphRuntime& rt, const MorphFrame& fr, VisibleSurfaceStats* stats) {
  VisibleSurfaceStats st;
  st.coreOutside = -std::numeric_limits<double>::infinity();
  const bool expand = fr.stage == MorphStage::Expand;
  std::optional<MorphImplicitField> field;
  if (fr.coreTriangles > 0 && (expand || fr.stage == MorphStage::Collapse))
    field = standinCoreField(rt, fr.timeSec, expand, fr.progress);
  if (!field) {
    if (stats) *stats = st;
    return fr.mesh;
  }
  TriangleMesh mesh, core;
  splitStandinCore(fr, mesh, core);
  // Signed distance of the core's vertices to the mesh: > 0 outside it (kept), < 0 inside (cut away).
  const std::vector<float> dist = pointDistancesToMesh(core.positions, mesh);
  const std::vector<uint8_t> inside = pointsInsideMesh(core.positions, mesh);
  std::vector<float> coreValue(core.positions.size());
  for (size_t i = 0; i < coreValue.size(); ++i) {
    const float sd = inside[i] ? -dist[i] : dist[i];
    coreValue[i] = -sd;
    st.coreOutside = std::max(st.coreOutside, double(sd));
  }
  st.coreVertices = core.positions.size();
  TriangleMesh out;
  st.meshTrianglesHidden = appendClippedMesh(mesh, coreFieldAt(field->program, mesh), out);
  st.coreTrianglesHidden = appendClippedMesh(core, coreValue, out);
  if (stats) *stats = st;
  return out;
}

}  // namespace animorph
