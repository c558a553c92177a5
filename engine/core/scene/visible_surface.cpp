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

// How far inside the core each vertex of mesh is (m, < 0 outside): the core's field (f - T)
// over its gradient's length, the distance to its surface to first order.
std::vector<float> depthInCore(const FieldProgram& core, const TriangleMesh& mesh) {
  std::vector<float> value(mesh.positions.size());
  ActiveProgram all;
  core.specialiseAll(all);
  constexpr size_t kChunk = 1024;
  const size_t chunks = (value.size() + kChunk - 1) / kChunk;
  tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
    thread_local FieldEvaluator eval;
    const size_t first = c * kChunk, n = std::min(kChunk, value.size() - first);
    std::vector<float> x(n), y(n), z(n), gx(n), gy(n), gz(n);
    for (size_t i = 0; i < n; ++i) {
      const glm::vec3& p = mesh.positions[first + i];
      x[i] = p.x, y[i] = p.y, z[i] = p.z;
    }
    float* f = value.data() + first;
    eval.evaluate(core, all, x.data(), y.data(), z.data(), int(n), f, gx.data(), gy.data(), gz.data());
    for (size_t i = 0; i < n; ++i) f[i] /= std::max(1e-6f, glm::length(glm::vec3(gx[i], gy[i], gz[i])));
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
  // Where the two shells run together (the mesh lying on its stand-in near B and C, both to
  // within the polygonisation's error), the core is kept and the mesh cut away, so that one
  // layer is left, not two interleaved: the mesh shows where it is more than `overlap` outside
  // the core, the core where it is less than `overlap` inside the mesh.
  const float overlap = 0.25f * std::max(fr.polygonize.cellSize, 1e-6f);
  // Signed distance of the core's vertices to the mesh: > 0 outside it, < 0 inside.
  const std::vector<float> dist = pointDistancesToMesh(core.positions, mesh);
  const std::vector<uint8_t> inside = pointsInsideMesh(core.positions, mesh);
  std::vector<float> coreValue(core.positions.size());
  for (size_t i = 0; i < coreValue.size(); ++i) {
    const float sd = inside[i] ? -dist[i] : dist[i];
    coreValue[i] = -sd - overlap;  // kept where <= 0
    st.coreOutside = std::max(st.coreOutside, double(sd));
  }
  st.coreVertices = core.positions.size();
  std::vector<float> meshValue = depthInCore(field->program, mesh);
  for (float& v : meshValue) v += overlap;  // kept where <= 0
  TriangleMesh out;
  st.meshTrianglesHidden = appendClippedMesh(mesh, meshValue, out);
  st.coreTrianglesHidden = appendClippedMesh(core, coreValue, out);
  if (stats) *stats = st;
  return out;
}

}  // namespace animorph
