// GPU polygoniser on lavapipe against the CPU polygoniser on the same grid:
// triangle counts within 0.5 %, vertex-to-nearest-vertex distance (an upper
// bound of the symmetric Hausdorff distance between the vertex sets) within
// 0.05 cell, closed manifolds, normals, culled == dense, buffer growth from tiny
// capacities, morphs (interpolation and space-time blending), the indirect draw
// through the scene renderer, and unsupported programs. Validation on, no errors.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <random>
#include <set>
#include <unordered_map>

#include "core/animorphosis/evaluate_generic.h"
#include "core/blobtree/compile.h"
#include "core/project/animorphosis_project.h"
#include "demo/animorphosis_demo.h"
#include "demo/blob_creature.h"
#include "demo/dino_dragon.h"
#include "gpu_fixture.h"
#include "gpu/polygonizer/gpu_field_program.h"
#include "gpu/polygonizer/gpu_polygonizer.h"
#include "core/poly/solid_noise.h"
#include "morph_field.h"
#include "gpu/present/offscreen_target.h"
#include "core/poly/marching_cubes_table.h"
#include "core/poly/mesh_checks.h"
#include "core/poly/polygonizer.h"
#include "poly_constants.h"
#include "gpu/render/scene_renderer.h"
#include "util/blob_builders.h"
#include "util/manifold_checks.h"
#include "util/test_skip.h"

using namespace animorph;
using namespace animorph::gpu;
using namespace animorph::test;

namespace {

struct Rig {
  std::unique_ptr<Context> ctx;
  std::unique_ptr<GpuPolygonizer> poly;
};

Rig makeRig() {
  Rig r;
  r.ctx = makeTestContext();
  auto p = GpuPolygonizer::create(*r.ctx);
  INFO(p.error());
  REQUIRE(p.ok());
  r.poly = std::move(*p);
  return r;
}

TriangleMesh gpuMesh(GpuPolygonizer& poly, const GpuField& field, const GpuPolygonizeSettings& s,
                     GpuPolygonizeStats* stats = nullptr) {
  auto st = poly.polygonize(field, s);
  INFO(st.error());
  REQUIRE(st.ok());
  if (stats) *stats = *st;
  auto mesh = poly.readBack();
  INFO(mesh.error());
  REQUIRE(mesh.ok());
  REQUIRE(mesh->triangleCount() == st->triangles);
  return std::move(*mesh);
}

TriangleMesh cpuMesh(const FieldProgram& p, int res, const std::optional<Bounds>& bounds, bool cull = true) {
  PolygonizeSettings s;
  s.resolution = res;
  s.bounds = bounds;
  s.culling = cull;
  auto r = polygonize(p, s);
  INFO(r.error());
  REQUIRE(r.ok());
  return std::move(r->mesh);
}

// Largest distance from a point of `from` to its nearest point of `to`; searches
// one cell of size h around each point, so it reports at least h when nothing is that close.
float maxNearestDistance(const std::vector<glm::vec3>& from, const std::vector<glm::vec3>& to, float h) {
  auto key = [&](const glm::ivec3& c) {
    return (uint64_t(uint32_t(c.x) & 0x1fffff) << 42) | (uint64_t(uint32_t(c.y) & 0x1fffff) << 21) |
           uint64_t(uint32_t(c.z) & 0x1fffff);
  };
  std::unordered_map<uint64_t, std::vector<uint32_t>> cells;
  for (uint32_t i = 0; i < to.size(); ++i) cells[key(glm::ivec3(glm::floor(to[i] / h)))].push_back(i);
  float worst = 0.0f;
  for (const glm::vec3& p : from) {
    glm::ivec3 c(glm::floor(p / h));
    float best = h;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          auto it = cells.find(key(c + glm::ivec3(dx, dy, dz)));
          if (it == cells.end()) continue;
          for (uint32_t j : it->second) best = std::min(best, glm::length(to[j] - p));
        }
    worst = std::max(worst, best);
  }
  return worst;
}

// The GPU mesh agrees with the reference: triangle counts within 0.5 %, vertex
// sets within 0.05 cell of each other both ways, closed manifold.
void requireAgrees(const TriangleMesh& gpu, const TriangleMesh& ref, float cell) {
  double n = double(ref.triangleCount());
  INFO("GPU " << gpu.triangleCount() << " triangles, reference " << ref.triangleCount());
  CHECK(std::abs(double(gpu.triangleCount()) - n) <= 0.005 * n);
  if (ref.triangleCount() == 0 || gpu.triangleCount() == 0) {
    CHECK(gpu.triangleCount() == ref.triangleCount());
    return;
  }
  CHECK(maxNearestDistance(gpu.positions, ref.positions, cell) <= 0.05f * cell);
  CHECK(maxNearestDistance(ref.positions, gpu.positions, cell) <= 0.05f * cell);
  requireClosedManifold(gpu);
}

// GPU vertices found at a CPU vertex (same position to 1e-3 cell), and how many of
// those have a unit normal within 3 degrees of the CPU's.
std::pair<size_t, size_t> normalAgreement(const TriangleMesh& gpu, const TriangleMesh& cpu, float cell) {
  std::unordered_map<uint64_t, glm::vec3> cpuNormal;
  auto key = [&](const glm::vec3& q) {
    glm::ivec3 c(glm::round(q / (1e-3f * cell)));
    return (uint64_t(uint32_t(c.x) & 0x1fffff) << 42) | (uint64_t(uint32_t(c.y) & 0x1fffff) << 21) |
           uint64_t(uint32_t(c.z) & 0x1fffff);
  };
  for (size_t i = 0; i < cpu.positions.size(); ++i) cpuNormal[key(cpu.positions[i])] = cpu.normals[i];
  size_t matched = 0, close = 0;
  for (size_t i = 0; i < gpu.positions.size(); ++i) {
    auto it = cpuNormal.find(key(gpu.positions[i]));
    if (it == cpuNormal.end()) continue;
    ++matched;
    close += std::abs(glm::length(gpu.normals[i]) - 1.0f) < 1e-3f &&
             glm::dot(gpu.normals[i], it->second) > std::cos(glm::radians(3.0f));
  }
  return {matched, close};
}

// Triangles as sorted position triples: compares meshes whatever their vertex numbering.
std::vector<std::array<float, 9>> triangleSet(const TriangleMesh& m) {
  std::vector<std::array<float, 9>> out;
  for (size_t t = 0; t < m.indices.size(); t += 3) {
    std::array<glm::vec3, 3> v = {m.positions[m.indices[t]], m.positions[m.indices[t + 1]],
                                  m.positions[m.indices[t + 2]]};
    auto less = [](const glm::vec3& a, const glm::vec3& b) {
      return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
    };
    int first = less(v[1], v[0]) ? (less(v[2], v[1]) ? 2 : 1) : (less(v[2], v[0]) ? 2 : 0);
    std::array<float, 9> k;
    for (int i = 0; i < 3; ++i)
      for (int a = 0; a < 3; ++a) k[size_t(3 * i + a)] = v[size_t((first + i) % 3)][a];  // keeps the winding
    out.push_back(k);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// A chain of n convolution segments heading up +z; radii scaled, the whole shifted.
BlobTree chainTree(int n, unsigned seed, float radiusScale = 1.0f, glm::vec3 shift = glm::vec3(0.0f)) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  BlobNode root = makeBlobNode(NodeType::Blend, 1);
  glm::vec3 p(0.3f * u(rng), 0.3f * u(rng), -0.35f);
  for (int i = 0; i < n; ++i) {
    glm::vec3 q = p + 0.1f * glm::normalize(glm::vec3(u(rng), u(rng), 1.2f));
    root.children.push_back(convSegmentNode(2 + i, p + shift, q + shift, radiusScale * (0.05f + 0.015f * u(rng)), 12.0f));
    p = q;
  }
  return treeOf(root, 1.0f);
}

Bounds cube(float half) {
  Bounds b;
  b.add(glm::vec3(-half));
  b.add(glm::vec3(half));
  return b;
}

// Marching cubes of an arbitrary field sampled on the GPU polygoniser's grid
// for a bounds override: the reference for morphs, which the CPU polygoniser
// (one program) cannot express. Same boundary rule, interpolation and table.
TriangleMesh referenceMesh(const std::function<float(const glm::vec3&)>& f, const Bounds& box, int res,
                           float boundaryValue) {
  float L = std::max({box.size().x, box.size().y, box.size().z});
  float h = L / float(res);
  int n[3];
  for (int a = 0; a < 3; ++a) n[a] = std::max(1, int(std::lround(box.size()[a] / h)));
  glm::vec3 origin = box.center() - 0.5f * h * glm::vec3(float(n[0]), float(n[1]), float(n[2]));
  const int cx = n[0] + 1, cy = n[1] + 1, cz = n[2] + 1;
  std::vector<float> v(size_t(cx) * cy * cz);
  auto corner = [&](int i, int j, int k) { return origin + h * glm::vec3(float(i), float(j), float(k)); };
  for (int k = 0; k < cz; ++k)
    for (int j = 0; j < cy; ++j)
      for (int i = 0; i < cx; ++i) {
        float x = f(corner(i, j, k));
        if (i == 0 || j == 0 || k == 0 || i == n[0] || j == n[1] || k == n[2]) x = std::min(x, boundaryValue);
        v[size_t((k * cy + j) * cx + i)] = x;
      }
  auto val = [&](int i, int j, int k) { return v[size_t((k * cy + j) * cx + i)]; };
  const MarchingCubesTable& table = marchingCubesTable();
  TriangleMesh mesh;
  std::unordered_map<uint64_t, uint32_t> vertexOf;
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        int mask = 0;
        for (int c = 0; c < 8; ++c)
          if (val(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1)) >= 0.0f) mask |= 1 << c;
        for (int q = 0; table.triangles[size_t(mask)][size_t(q)] != 255; ++q) {
          int e = table.triangles[size_t(mask)][size_t(q)];
          int c0 = table.edgeCorners[size_t(e)][0], axis = table.edgeAxis[size_t(e)];
          int gi = i + (c0 & 1), gj = j + ((c0 >> 1) & 1), gk = k + ((c0 >> 2) & 1);
          uint64_t key = ((uint64_t(gk) * uint64_t(cy) + uint64_t(gj)) * uint64_t(cx) + uint64_t(gi)) * 3 + uint64_t(axis);
          auto it = vertexOf.find(key);
          if (it == vertexOf.end()) {
            int gi1 = gi + (axis == 0), gj1 = gj + (axis == 1), gk1 = gk + (axis == 2);
            float f0 = val(gi, gj, gk), f1 = val(gi1, gj1, gk1);
            float t = std::clamp(f0 / (f0 - f1), 1e-3f, 1.0f - 1e-3f);
            glm::vec3 p0 = corner(gi, gj, gk), p1 = corner(gi1, gj1, gk1);
            mesh.positions.push_back(p0 + t * (p1 - p0));
            it = vertexOf.emplace(key, uint32_t(mesh.positions.size() - 1)).first;
          }
          mesh.indices.push_back(it->second);
        }
      }
  return mesh;
}

// Which op codes, primitive classes, skeleton kinds and map kinds a program uses.
struct Coverage {
  std::set<int> ops, classes, skeletons, maps;
  void add(const FieldProgram& p) {
    for (const FieldOp& op : p.ops) {
      ops.insert(int(op.code));
      if (op.code == OpCode::Prims) classes.insert(int(op.primClass));
    }
    for (const SkeletalPrimitive& s : p.skeletal) skeletons.insert(int(s.skeleton.kind));
    for (const SpaceMap& m : p.maps) maps.insert(int(m.kind));
  }
};

}  // namespace

TEST_CASE("GPU polygoniser matches the CPU on a convolution chain, culled and dense", "[gpu][gpupoly]") {
  Rig r = makeRig();
  FieldProgram p = compileFieldProgram(chainTree(20, 7), 0.0);
  GpuPolygonizeSettings s;
  s.resolution = 64;
  GpuPolygonizeStats culledStats, denseStats;
  TriangleMesh culled = gpuMesh(*r.poly, GpuField::single(p), s, &culledStats);
  TriangleMesh cpu = cpuMesh(p, 64, std::nullopt);
  REQUIRE(cpu.triangleCount() > 2000);
  float cell = culledStats.cellSize;
  requireAgrees(culled, cpu, cell);
  CHECK(analyzeMesh(culled).components == analyzeMesh(cpu).components);
  CHECK(std::abs(meshVolume(culled) - meshVolume(cpu)) <= 1e-3 * std::abs(meshVolume(cpu)));

  s.culling = false;
  TriangleMesh dense = gpuMesh(*r.poly, GpuField::single(p), s, &denseStats);
  CHECK(denseStats.blocksActive == denseStats.blocksTotal);
  CHECK(culledStats.blocksActive < culledStats.blocksTotal);
  CHECK(triangleSet(dense) == triangleSet(culled));  // same field values, bit for bit
  s.culling = true;
  // The specialised variant (convolution only, one program) and the generic interpreter.
  CHECK(culledStats.features != AM_FEAT_ALL);
  CHECK(culledStats.features == (AM_FEAT_OP_BIT(AM_OP_PRIMS) | AM_FEAT_CLASS_BIT(AM_PRIM_CONVOLUTION) |
                                 AM_FEAT_COMBINE_BIT(AM_COMBINE_SINGLE)));
  {
    s.specialise = false;
    GpuPolygonizeStats st;
    TriangleMesh generic = gpuMesh(*r.poly, GpuField::single(p), s, &st);
    CHECK(st.features == AM_FEAT_ALL);
    // The same surface up to rounding, not bit for bit: a GPU compiler contracts multiply-adds
    // differently in the two programs (lavapipe gives identical triangles, an NVIDIA H100 does not).
    requireAgrees(generic, culled, cell);
    CHECK(analyzeMesh(generic).components == analyzeMesh(culled).components);
    CHECK(std::abs(meshVolume(generic) - meshVolume(culled)) <= 1e-4 * std::abs(meshVolume(culled)));
    s.specialise = true;
  }
  {
    // The multi-group scan (arrays beyond AM_POLY_SCAN_SINGLE_MAX) against the one-workgroup scan.
    s.singleWorkgroupScan = false;
    TriangleMesh grouped = gpuMesh(*r.poly, GpuField::single(p), s);
    CHECK(triangleSet(grouped) == triangleSet(culled));
    CHECK(grouped.positions == culled.positions);  // same slots, same vertex order
    s.singleWorkgroupScan = true;
  }
  // The fine passes in rows of workgroups (a 512^3 grid can have more active blocks than a
  // device dispatches in one row): rows of 7, and of 1, give the same mesh, with either scan.
  REQUIRE(culledStats.blocksActive > 14);
  for (uint32_t row : {7u, 1u})
    for (bool single : {true, false}) {
      s.dispatchRow = row;
      s.singleWorkgroupScan = single;
      TriangleMesh rows = gpuMesh(*r.poly, GpuField::single(p), s);
      CHECK(rows.positions == culled.positions);
      CHECK(triangleSet(rows) == triangleSet(culled));
    }
  s.dispatchRow = 0;
  s.singleWorkgroupScan = true;
  for (auto pool : {GpuPolygonizeSettings::PoolBuffer::Uniform, GpuPolygonizeSettings::PoolBuffer::Storage}) {
    s.poolBuffer = pool;
    GpuPolygonizeStats st;
    TriangleMesh other = gpuMesh(*r.poly, GpuField::single(p), s, &st);
    CHECK(st.uniformPool == (pool == GpuPolygonizeSettings::PoolBuffer::Uniform));
    CHECK(triangleSet(other) == triangleSet(culled));
  }

  // Normals: the field gradient, as the CPU's.
  auto [matched, close] = normalAgreement(culled, cpu, cell);
  CHECK(matched > culled.positions.size() / 2);
  CHECK(close >= matched * 99 / 100);
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("GPU polygoniser covers every op, primitive, skeleton and map of the CPU program", "[gpu][gpupoly]") {
  Rig r = makeRig();
  Coverage coverage;
  for (unsigned seed : {1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u, 9u, 10u, 11u, 12u, 13u, 14u, 15u, 16u}) {
    std::mt19937 rng(seed);
    int id = 1;
    BlobTree tree = treeOf(randomNode(rng, 3, id), 0.5f);
    FieldProgram p = compileFieldProgram(tree, 0.5);
    INFO("seed " << seed);
    REQUIRE(GpuPolygonizer::unsupported(GpuField::single(p)).empty());
    coverage.add(p);
    GpuPolygonizeSettings s;
    s.resolution = 40;
    s.bounds = cube(1.2f);  // some random trees are unbounded
    GpuPolygonizeStats st;
    TriangleMesh gpu = gpuMesh(*r.poly, GpuField::single(p), s, &st);
    TriangleMesh cpu = cpuMesh(p, 40, s.bounds);
    requireAgrees(gpu, cpu, st.cellSize);
    // Normals: analytic gradients through every op (the stencil for HyperBlend and curved maps).
    auto [matched, close] = normalAgreement(gpu, cpu, st.cellSize);
    CHECK(matched >= gpu.positions.size() / 2);
    CHECK(close >= matched * 95 / 100);
  }
  // Ops the compiler makes rarely: an R-union node, and a constant (a hand-built program).
  {
    BlobTree tree = treeOf(operatorNode(NodeType::RUnion, 1,
                                        {pointNode(2, glm::vec3(-0.2f, 0, 0), 0.5f), segmentNode(3, glm::vec3(0.1f, -0.3f, 0), glm::vec3(0.2f, 0.3f, 0.1f), 0.3f)}),
                           0.5f);
    FieldProgram withConst;
    withConst.threshold = 0.5f;
    withConst.addConstant(0.2f);
    withConst.addCapsule({glm::vec3(-0.3f, 0, 0), glm::vec3(0.3f, 0.1f, 0), 0.15f}, false, false);
    withConst.addOperator(OpCode::Sum, 2);
    withConst.finish();
    // A bounded, scaled operand and a plainly scaled one (the morph's Remap ops).
    FieldProgram remapped;
    remapped.threshold = 0.5f;
    remapped.addCapsule({glm::vec3(-0.3f, 0, 0), glm::vec3(0.3f, 0.1f, 0), 0.2f}, false, false);
    const float bounded[2] = {0.7f, 3.0f}, scaled[2] = {0.6f, 0.0f};
    remapped.addOperator(OpCode::Remap, 1, bounded, 2);
    remapped.addConvolution(glm::vec3(0.0f, -0.3f, 0.0f), glm::vec3(0.1f, 0.3f, 0.1f), 0.15f, 12.0f, 1e-3f, false);
    remapped.addOperator(OpCode::Remap, 1, scaled, 2);
    remapped.addOperator(OpCode::Sum, 2);
    remapped.finish();
    for (const FieldProgram& p : {compileFieldProgram(tree, 0.0), withConst, remapped}) {
      coverage.add(p);
      GpuPolygonizeSettings s;
      s.resolution = 40;
      s.bounds = cube(0.8f);
      GpuPolygonizeStats st;
      TriangleMesh gpu = gpuMesh(*r.poly, GpuField::single(p), s, &st);
      TriangleMesh cpu = cpuMesh(p, 40, s.bounds);
      REQUIRE(cpu.triangleCount() > 500);
      requireAgrees(gpu, cpu, st.cellSize);
      auto [matched, close] = normalAgreement(gpu, cpu, st.cellSize);
      CHECK(close >= matched * 95 / 100);
    }
  }
  for (OpCode op : {OpCode::Prims, OpCode::Const, OpCode::Sum, OpCode::Max, OpCode::Min, OpCode::HyperBlend,
                    OpCode::Difference, OpCode::RUnion, OpCode::RIntersection, OpCode::BoundedBlend,
                    OpCode::BeginMap, OpCode::EndMap, OpCode::Remap}) {
    INFO("op " << int(op));
    CHECK(coverage.ops.count(int(op)) == 1);
  }
  CHECK(coverage.classes.size() == 3);
  CHECK(coverage.skeletons.size() == 9);
  CHECK(coverage.maps.size() == 4);
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("GPU polygoniser skips the map subtrees no primitive of a block reaches", "[gpu][gpupoly]") {
  // The demo BlobTree creature: frames (affine maps) nest its limbs. A block away from a limb
  // pushes the limb subtree's constant value instead of running it (as the CPU's specialise);
  // without culling every block runs every subtree. Same surface either way, and as the CPU's.
  Rig r = makeRig();
  FieldProgram p = compileFieldProgram(makeBlobCreature(), 0.5);
  GpuPolygonizeSettings s;
  s.resolution = 64;
  GpuPolygonizeStats culledStats;
  TriangleMesh culled = gpuMesh(*r.poly, GpuField::single(p), s, &culledStats);
  s.culling = false;
  TriangleMesh dense = gpuMesh(*r.poly, GpuField::single(p), s);
  TriangleMesh cpu = cpuMesh(p, 64, std::nullopt);
  REQUIRE(cpu.triangleCount() > 3000);
  CHECK(culledStats.blocksActive < culledStats.blocksTotal);
  requireAgrees(culled, cpu, culledStats.cellSize);
  requireAgrees(dense, cpu, culledStats.cellSize);
  requireClosedManifold(culled);
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("GPU polygoniser compiles a kind of field's pipelines in the background (prewarm)", "[gpu][gpupoly]") {
  Rig r = makeRig();
  BlobTree ta = chainTree(8, 11, 1.3f), tb = chainTree(8, 11, 1.8f, glm::vec3(0.06f, 0.0f, 0.0f));
  FieldProgram a = compileFieldProgram(ta, 0.0), b = compileFieldProgram(tb, 0.0);
  GpuPolygonizeSettings s;
  s.resolution = 40;
  s.bounds = cube(0.6f);
  CHECK(r.poly->variantCount() == 0);
  r.poly->prewarm(GpuField::interpolation(a, b, 0.3f), s);
  r.poly->prewarm(GpuField::interpolation(a, b, 0.7f), s);  // the same kind of field: already under way
  CHECK(r.poly->variantCount() == 1);
  // The polygonisation takes the prewarmed pipelines over instead of compiling its own, and
  // makes the mesh a polygoniser that compiled them itself makes.
  TriangleMesh warm = gpuMesh(*r.poly, GpuField::interpolation(a, b, 0.5f), s);
  CHECK(r.poly->variantCount() == 1);
  auto cold = GpuPolygonizer::create(*r.ctx);
  REQUIRE(cold.ok());
  TriangleMesh reference = gpuMesh(**cold, GpuField::interpolation(a, b, 0.5f), s);
  REQUIRE(reference.triangleCount() > 100);
  CHECK(triangleSet(warm) == triangleSet(reference));
  // Another kind (space-time blending, a single program): its own variant.
  r.poly->prewarm(GpuField::spaceTime(a, b, 0.5f), s);
  r.poly->prewarm(GpuField::single(a), s);
  CHECK(r.poly->variantCount() == 3);
  // A polygoniser destroyed while it compiles waits for the compiler and frees what it made.
  {
    auto brief = GpuPolygonizer::create(*r.ctx);
    REQUIRE(brief.ok());
    (*brief)->prewarm(GpuField::single(b), s);
  }
  r.poly.reset();
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("GPU polygoniser grows its buffers from tiny capacities and redoes the frame", "[gpu][gpupoly]") {
  Rig r = makeRig();
  FieldProgram p = compileFieldProgram(chainTree(12, 3), 0.0);
  GpuPolygonizeSettings s;
  s.resolution = 48;
  GpuPolygonizeStats normal, tiny;
  TriangleMesh reference = gpuMesh(*r.poly, GpuField::single(p), s, &normal);
  CHECK(normal.regrows == 0);
  s.initialBlockCapacity = 1;
  s.initialVertexCapacity = 3;
  s.initialTriangleCapacity = 1;
  TriangleMesh grown = gpuMesh(*r.poly, GpuField::single(p), s, &tiny);
  CHECK(tiny.regrows >= 1);
  REQUIRE(reference.triangleCount() > 1000);
  CHECK(triangleSet(grown) == triangleSet(reference));
  requireClosedManifold(grown);
  s.singleWorkgroupScan = false;  // the multi-group scan's overflow path
  GpuPolygonizeStats tinyGrouped;
  TriangleMesh grownGrouped = gpuMesh(*r.poly, GpuField::single(p), s, &tinyGrouped);
  CHECK(tinyGrouped.regrows >= 1);
  CHECK(triangleSet(grownGrouped) == triangleSet(reference));
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("GPU polygoniser displaces its mesh by solid noise as the CPU does", "[gpu][gpupoly]") {
  // The morph's noise track (docs/design.md §5): every vertex moves along its normal by
  // amplitude * solidNoise(frequency * p). On the GPU a pass after the normals; on the CPU
  // displaceBySolidNoise on the polygonised mesh. Same mesh, and a real displacement.
  Rig r = makeRig();
  FieldProgram p = compileFieldProgram(chainTree(12, 3), 0.0);
  GpuPolygonizeSettings s;
  s.resolution = 64;
  GpuPolygonizeStats st;
  TriangleMesh plain = gpuMesh(*r.poly, GpuField::single(p), s, &st);
  s.noiseAmplitude = 2.0f * st.cellSize;
  s.noiseFrequency = 7.0f;
  TriangleMesh noisy = gpuMesh(*r.poly, GpuField::single(p), s);
  TriangleMesh cpu = cpuMesh(p, 64, std::nullopt);
  REQUIRE(cpu.triangleCount() > 1000);
  displaceBySolidNoise(cpu, s.noiseAmplitude, s.noiseFrequency);
  requireAgrees(noisy, cpu, st.cellSize);
  requireClosedManifold(noisy);
  // The same vertices moved: by up to the amplitude, most of them by a visible fraction of it.
  REQUIRE(noisy.positions.size() == plain.positions.size());
  size_t moved = 0;
  float largest = 0.0f;
  for (size_t i = 0; i < plain.positions.size(); ++i) {
    float d = glm::length(noisy.positions[i] - plain.positions[i]);
    largest = std::max(largest, d);
    moved += d > 0.1f * s.noiseAmplitude;
  }
  CHECK(largest <= 1.01f * s.noiseAmplitude);
  CHECK(moved > plain.positions.size() / 2);
  CHECK(noisy.normals == plain.normals);  // normals of the undisplaced surface, as on the CPU
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("GPU polygoniser morphs two programs by interpolation and by space-time blending", "[gpu][gpupoly]") {
  Rig r = makeRig();
  // Two overlapping stand-ins: the same walk, thicker and shifted in the target.
  BlobTree ta = chainTree(8, 11, 1.3f), tb = chainTree(8, 11, 1.8f, glm::vec3(0.06f, 0.0f, 0.0f));
  FieldProgram a = compileFieldProgram(ta, 0.0), b = compileFieldProgram(tb, 0.0);
  const Bounds box = cube(0.6f);
  const int res = 48;
  GpuPolygonizeSettings s;
  s.resolution = res;
  s.bounds = box;
  FieldEvaluator ea, eb;

  SECTION("interpolation equals the CPU polygoniser on the weight-scaled merged program") {
    const float w = 0.4f;
    // (1 - w) (pA - T) + w (pB - T) = (1 - w) pA + w pB - T: one program with scaled weights.
    BlobNode both = makeBlobNode(NodeType::Blend, 1000);
    both.children = {ta.root, tb.root};
    FieldProgram merged = compileFieldProgram(treeOf(both, 1.0f), 0.0);
    REQUIRE(merged.convolution.size() == 16);
    for (size_t i = 0; i < 16; ++i) merged.convolution.weight[i] *= i < 8 ? 1.0f - w : w;
    GpuPolygonizeStats st;
    TriangleMesh gpu = gpuMesh(*r.poly, GpuField::interpolation(a, b, w), s, &st);
    TriangleMesh cpu = cpuMesh(merged, res, box);
    REQUIRE(cpu.triangleCount() > 1000);
    requireAgrees(gpu, cpu, st.cellSize);
    TriangleMesh ref = referenceMesh(
        [&](const glm::vec3& x) {
          return morphfield::amMorphInterpolate(ea.evaluatePoint(a, x), eb.evaluatePoint(b, x), w);
        },
        box, res, -1e-6f);
    requireAgrees(gpu, ref, st.cellSize);
    // The ends of the interpolation are the programs themselves.
    TriangleMesh atZero = gpuMesh(*r.poly, GpuField::interpolation(a, b, 0.0f), s);
    requireAgrees(atZero, cpuMesh(a, res, box), st.cellSize);
  }
  SECTION("space-time blending equals the reference of the shared formula") {
    for (float t : {-0.3f, 0.5f}) {
      GpuField f = GpuField::spaceTime(a, b, t, 1.0f, 2.0f, 1.0f, 1.0f, 0.2f);
      GpuPolygonizeStats st;
      TriangleMesh gpu = gpuMesh(*r.poly, f, s, &st);
      TriangleMesh ref = referenceMesh(
          [&](const glm::vec3& x) {
            return morphfield::amMorphSpaceTime(ea.evaluatePoint(a, x), eb.evaluatePoint(b, x), f.morphTime,
                                                f.timeScale, f.a0, f.a1, f.a2, f.a3);
          },
          box, res, -1e-6f);
      INFO("t = " << t);
      REQUIRE(ref.triangleCount() > 500);
      requireAgrees(gpu, ref, st.cellSize);
      // Culling (intervals of the morph) changes nothing.
      s.culling = false;
      TriangleMesh dense = gpuMesh(*r.poly, f, s);
      s.culling = true;
      CHECK(triangleSet(dense) == triangleSet(gpu));
    }
  }
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("GPU polygoniser draws its mesh with an indirect draw, no read-back", "[gpu][gpupoly]") {
  Rig r = makeRig();
  BlobTree tree = treeOf(pointNode(2, glm::vec3(0.0f), 0.8f), 0.5f);
  FieldProgram p = compileFieldProgram(tree, 0.0);
  auto target = OffscreenTarget::create(*r.ctx, 96, 96);
  REQUIRE(target.ok());
  auto renderer = SceneRenderer::create(*r.ctx, (*target)->renderPass());
  INFO(renderer.error());
  REQUIRE(renderer.ok());
  GpuPolygonizeSettings s;
  s.resolution = 32;
  Status recorded;
  Status submitted = r.ctx->submitImmediate([&](VkCommandBuffer cmd) {
    recorded = r.poly->record(cmd, 0, GpuField::single(p), s);
  });
  INFO(recorded.error() + submitted.error());
  REQUIRE(recorded.ok());
  REQUIRE(submitted.ok());
  OrbitCamera cam;
  cam.target = glm::vec3(0.0f);
  cam.yawRad = 0.0f;
  cam.pitchRad = 0.0f;
  cam.distanceM = 3.0f;
  Scene scene;
  scene.options.grid = false;
  scene.options.axisIndicator = false;
  scene.options.background = {0.1f, 0.2f, 0.3f, 1.0f};
  scene.generatedMeshes.push_back(r.poly->generatedMesh({0.9f, 0.3f, 0.2f, 1.0f}));
  Status drawn;
  Status rendered = (*target)->render([&](VkCommandBuffer cmd) {
    drawn = (*renderer)->record(cmd, (*target)->serial(), {0, 0, 96, 96}, cam, scene);
  });
  REQUIRE(drawn.ok());
  REQUIRE(rendered.ok());
  const RgbaImage& img = (*target)->image();
  // A sphere of radius ~0.46 m (g = 0.5 at d = R sqrt(1 - 0.5^(1/3))) seen from 3 m fills the middle.
  CHECK(differs(img.at(48, 48), scene.options.background));
  CHECK(!differs(img.at(3, 3), scene.options.background));
  size_t covered = countDiffering(img, scene.options.background);
  CHECK(covered > 96 * 96 / 20);
  CHECK(covered < 96 * 96 / 2);

  // The wireframe overlay covers generated meshes too (polygon-mode lines of the indirect draw):
  // dark edges over the sphere, nothing outside it.
  const RgbaImage shaded = img;
  scene.options.wireframe = true;
  scene.options.wireColor = {0.0f, 0.0f, 0.0f, 1.0f};
  Status wired = (*target)->render([&](VkCommandBuffer cmd) {
    drawn = (*renderer)->record(cmd, (*target)->serial(), {0, 0, 96, 96}, cam, scene);
  });
  REQUIRE(drawn.ok());
  REQUIRE(wired.ok());
  const RgbaImage& wire = (*target)->image();
  size_t dark = 0, outside = 0;
  for (uint32_t y = 0; y < 96; ++y)
    for (uint32_t x = 0; x < 96; ++x) {
      if (wire.at(x, y) == shaded.at(x, y)) continue;
      dark += wire.at(x, y).r < 40;
      bool nearSurface = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const uint32_t nx = uint32_t(std::clamp(int(x) + dx, 0, 95)), ny = uint32_t(std::clamp(int(y) + dy, 0, 95));
          nearSurface |= differs(shaded.at(nx, ny), scene.options.background);
        }
      outside += !nearSurface;
    }
  if (r.ctx->supportsWireframeFill()) CHECK(dark > covered / 4);  // 32^3 triangles of a few pixels each
  CHECK(outside == 0);
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("GPU polygoniser takes wide operators and deep maps (a tail of 24 beads, a limb of 12 frames)", "[gpu][gpupoly]") {
  // The demo creature's tail is a spline of nodes: one frame per copy, all summed. With 24
  // copies the blend had 24 operands, and the GPU's operand stack (16) sent the preview to the
  // CPU; the compiler's folded operators keep the stack shallow.
  BlobTree tree = makeBlobCreature();
  int tails = 0;
  std::function<void(BlobNode&)> lengthen = [&](BlobNode& n) {
    if (n.type == NodeType::SplineOfNodes) {
      n.floatParam("count") = FloatTrack(24.0f);
      ++tails;
    }
    for (BlobNode& c : n.children) lengthen(c);
  };
  lengthen(tree.root);
  REQUIRE(tails == 1);
  FieldProgram p = compileFieldProgram(tree, 0.5);
  REQUIRE(GpuPolygonizer::unsupported(GpuField::single(p)).empty());
  Rig r = makeRig();
  GpuPolygonizeSettings s;
  s.resolution = 64;
  GpuPolygonizeStats st;
  TriangleMesh gpu = gpuMesh(*r.poly, GpuField::single(p), s, &st);
  TriangleMesh cpu = cpuMesh(p, 64, std::nullopt);
  REQUIRE(cpu.triangleCount() > 3000);
  requireAgrees(gpu, cpu, st.cellSize);
  requireClosedManifold(gpu);

  // A limb of 12 frames each inside the last (a rig's chain: hips, spine, ..., finger tip), each
  // with its own bead: maps nest 12 deep (the GPU took 6 before).
  int id = 1;
  BlobNode chain = makeBlobNode(NodeType::Frame, id++);
  chain.children.push_back(pointNode(id++, glm::vec3(0.0f), 0.16f));
  for (int i = 0; i < 11; ++i) {
    BlobNode parent = makeBlobNode(NodeType::Frame, id++);
    parent.vec3Param("translation") = Vec3Track(glm::vec3(0.0f, -0.07f, 0.0f));
    parent.quatParam("rotation") = QuatTrack(glm::angleAxis(0.15f, glm::vec3(0.0f, 0.0f, 1.0f)));
    parent.children.push_back(pointNode(id++, glm::vec3(0.0f), 0.16f));
    parent.children.push_back(chain);
    chain = parent;
  }
  FieldProgram limb = compileFieldProgram(treeOf(chain, 0.5f), 0.0);
  REQUIRE(limb.maxMapDepth() == 12);
  REQUIRE(GpuPolygonizer::unsupported(GpuField::single(limb)).empty());
  s.bounds = cube(0.9f);
  TriangleMesh gpuLimb = gpuMesh(*r.poly, GpuField::single(limb), s, &st);
  TriangleMesh cpuLimb = cpuMesh(limb, 64, s.bounds);
  REQUIRE(cpuLimb.triangleCount() > 1000);
  requireAgrees(gpuLimb, cpuLimb, st.cellSize);
  requireClosedManifold(gpuLimb);
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("GPU polygoniser reports what it cannot do and bad settings", "[gpu][gpupoly]") {
  // 20 nested blends, each taking a constant first and the next blend second, keep 20 values on
  // the stack (wide operators fold into a shallow one: next test).
  FieldProgram deep;
  deep.threshold = 1.0f;
  for (int i = 0; i < 20; ++i) deep.addConstant(0.0f);
  for (int i = 0; i < 19; ++i) deep.addOperator(OpCode::Sum, 2);
  deep.finish();
  std::string why = GpuPolygonizer::unsupported(GpuField::single(deep));
  CHECK(why.find("stack") != std::string::npos);
  Rig r = makeRig();
  GpuPolygonizeSettings s;
  s.bounds = cube(1.0f);
  auto refused = r.poly->polygonize(GpuField::single(deep), s);
  REQUIRE(!refused.ok());
  CHECK(refused.error().find("stack depth 20") != std::string::npos);
  FieldProgram ok = compileFieldProgram(chainTree(3, 1), 0.0);
  s.resolution = 1000;
  auto tooFine = r.poly->polygonize(GpuField::single(ok), s);
  REQUIRE(!tooFine.ok());
  CHECK(tooFine.error().find("resolution") != std::string::npos);
  CHECK(!r.poly->readBack().ok());  // nothing polygonised yet

  // Devices at Vulkan's minimum limits (16 KiB of shared memory, 128 invocations a workgroup) are
  // reported, not handed pipelines they cannot run; lavapipe has enough.
  const VkPhysicalDeviceLimits lvp = r.ctx->properties().limits;
  CHECK(GpuPolygonizer::deviceShortfall(lvp).empty());
  VkPhysicalDeviceLimits small = lvp;
  small.maxComputeSharedMemorySize = 16384;
  CHECK_THAT(GpuPolygonizer::deviceShortfall(small), Catch::Contains("16384 bytes of compute shared memory") &&
                                                         Catch::Contains(std::to_string(AM_POLY_EMIT_SHARED_BYTES)));
  small = lvp;
  small.maxComputeWorkGroupInvocations = 128;
  CHECK_THAT(GpuPolygonizer::deviceShortfall(small), Catch::Contains("at most 128 invocations"));
  small.maxComputeSharedMemorySize = AM_POLY_EMIT_SHARED_BYTES;  // exactly enough
  CHECK(GpuPolygonizer::deviceShortfall(small).find("shared memory") == std::string::npos);
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("GPU polygoniser never draws a wrong mesh of a BlobTree of thousands of primitives (the demo dragon)",
          "[gpu][gpupoly]") {
  // The animorphosis demo's dragon: ~21 700 point primitives, each under its own frame. lavapipe
  // stops every loop of a shader invocation after 65 535 iterations, all loops together, and the
  // passes' interpreters walked every op and looped over every primitive reaching a block: the GPU
  // mesh had a quarter of the CPU's triangles and a few dozen vertices, and stale edge prefixes
  // sent the emit pass's shared-memory writes out of bounds (heap corruption, crashes). Now the
  // passes walk per-region programs; the whole program's walk, forced (regionPrograms Off), is
  // refused with its reason, and run anyway the shaders find their loops cut and fail the frame.
  FieldProgram dragon = compileFieldProgram(makeDragon(), 0.5);
  REQUIRE(dragon.primitiveCount() > 10000);
  Rig r = makeRig();
  const GpuField field = GpuField::single(dragon);
  CHECK(GpuPolygonizer::unsupported(field).empty());  // its size is no reason any more
  GpuPolygonizeSettings s;
  s.resolution = 32;
  s.regionPrograms = GpuPolygonizeSettings::RegionPrograms::Off;
  const uint64_t limit = GpuPolygonizer::loopLimit(r.ctx->properties());
  if (limit == 0) {
    ANIMORPH_SKIP("the device has no loop limiter (not llvmpipe): nothing to cut");
    return;
  }
  CHECK(gpuLoopIterationEstimate(dragon) > limit);
  auto refused = r.poly->polygonize(field, s);
  REQUIRE(!refused.ok());
  CHECK_THAT(refused.error(), Catch::Contains("llvmpipe") && Catch::Contains(std::to_string(dragon.primitiveCount())));
  // Run anyway, the passes find their loops cut and the frame fails: no mesh, no crash.
  s.loopBudgetCheck = false;
  auto cut = r.poly->polygonize(field, s);
  REQUIRE(!cut.ok());
  CHECK_THAT(cut.error(), Catch::Contains("cut the shaders' loops short"));
  // The editor's path: the record draws nothing; recordFitted() and the next record() say why, so
  // the preview goes to the CPU instead of redoing a frame that cannot fit.
  Status recorded, again;
  Status submitted = r.ctx->submitImmediate([&](VkCommandBuffer cmd) { recorded = r.poly->record(cmd, 0, field, s); });
  REQUIRE(recorded.ok());
  REQUIRE(submitted.ok());
  auto fitted = r.poly->recordFitted(0);
  REQUIRE(!fitted.ok());
  CHECK_THAT(fitted.error(), Catch::Contains("cut the shaders' loops short"));
  CHECK(r.ctx->submitImmediate([&](VkCommandBuffer cmd) { again = r.poly->record(cmd, 1, field, s); }).ok());
  REQUIRE(!again.ok());
  CHECK_THAT(again.error(), Catch::Contains("cut the shaders' loops short"));
  // The polygoniser goes on: the small demo creature still agrees with the CPU afterwards.
  FieldProgram small = compileFieldProgram(makeBlobCreature(), 0.5);
  CHECK(gpuLoopIterationEstimate(small) < limit / 8);
  s.loopBudgetCheck = true;
  GpuPolygonizeStats st;
  TriangleMesh gpuSmall = gpuMesh(*r.poly, GpuField::single(small), s, &st);
  requireAgrees(gpuSmall, cpuMesh(small, 32, std::nullopt), st.cellSize);
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("GPU polygoniser walks per-region programs: the same mesh as the whole programs", "[gpu][gpupoly]") {
  // Small programs through both paths (region lists forced on and off), single and morphed: the
  // values in a region are the whole program's (a left-out primitive contributes exactly 0), so
  // the meshes are the same triangles; and both agree with the CPU.
  Rig r = makeRig();
  FieldProgram creature = compileFieldProgram(makeBlobCreature(), 0.5);
  BlobTree ta = chainTree(8, 11, 1.3f), tb = chainTree(8, 11, 1.8f, glm::vec3(0.06f, 0.0f, 0.0f));
  FieldProgram a = compileFieldProgram(ta, 0.0), b = compileFieldProgram(tb, 0.0);
  const std::vector<GpuField> fields = {GpuField::single(creature), GpuField::interpolation(a, b, 0.4f),
                                        GpuField::spaceTime(a, b, 0.5f, 1.0f, 2.0f, 1.0f, 1.0f, 0.2f)};
  for (size_t k = 0; k < fields.size(); ++k) {
    INFO("field " << k);
    GpuPolygonizeSettings s;
    s.resolution = 72;  // 9 blocks a side: 3 superblocks, the last one partial
    if (k > 0) s.bounds = cube(0.6f);
    s.regionPrograms = GpuPolygonizeSettings::RegionPrograms::Off;
    GpuPolygonizeStats whole, regions;
    TriangleMesh m0 = gpuMesh(*r.poly, fields[k], s, &whole);
    CHECK(!whole.regionLists);
    s.regionPrograms = GpuPolygonizeSettings::RegionPrograms::On;
    TriangleMesh m1 = gpuMesh(*r.poly, fields[k], s, &regions);
    CHECK(regions.regionLists);
    REQUIRE(m0.triangleCount() > 100);
    CHECK(m1.triangleCount() == m0.triangleCount());
    CHECK(maxNearestDistance(m1.positions, m0.positions, whole.cellSize) <= 1e-4f * whole.cellSize);
    CHECK(maxNearestDistance(m0.positions, m1.positions, whole.cellSize) <= 1e-4f * whole.cellSize);
    requireClosedManifold(m1);
    // The normals too (the normals pass selects each vertex's region).
    auto [matched, close] = normalAgreement(m1, m0, whole.cellSize);
    CHECK(matched == m1.positions.size());
    CHECK(close == matched);
  }
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("GPU polygoniser: normals over region lists one vertex per dispatch equal the whole programs' (stencil and analytic)",
          "[gpu][gpupoly]") {
  // Near lavapipe's loop limit the normals pass runs once per vertex of its invocations' four
  // (GpuPolygonizeSettings::normalsPerVertex, forced here). Seeded random trees (not made for this
  // test), with analytic normals and with the stencil (HyperBlend, curved maps), through region
  // lists so and through the whole programs: the same triangles and normals.
  Rig r = makeRig();
  int counted[2] = {0, 0};  // analytic, stencil
  for (unsigned seed = 1; seed <= 60 && (counted[0] < 3 || counted[1] < 3); ++seed) {
    std::mt19937 rng(seed);
    int id = 1;
    BlobTree tree = treeOf(randomNode(rng, 3, id), 0.5f);
    FieldProgram p = compileFieldProgram(tree, 0.5);
    bool stencil = false;
    for (const FieldOp& op : p.ops) stencil |= op.code == OpCode::HyperBlend;
    for (const SpaceMap& m : p.maps) stencil |= m.kind != SpaceMapKind::Affine;
    if (counted[stencil ? 1 : 0] >= 3) continue;
    INFO("seed " << seed << (stencil ? " (stencil)" : " (analytic)"));
    GpuPolygonizeSettings s;
    s.resolution = 72;
    s.bounds = cube(1.2f);
    s.regionPrograms = GpuPolygonizeSettings::RegionPrograms::Off;
    GpuPolygonizeStats whole, regions;
    TriangleMesh m0 = gpuMesh(*r.poly, GpuField::single(p), s, &whole);
    if (m0.triangleCount() < 100) continue;
    ++counted[stencil ? 1 : 0];
    s.regionPrograms = GpuPolygonizeSettings::RegionPrograms::On;
    s.normalsPerVertex = true;
    TriangleMesh m1 = gpuMesh(*r.poly, GpuField::single(p), s, &regions);
    CHECK(whole.normalsDispatches == 1);
    CHECK(regions.regionLists);
    CHECK(regions.normalsDispatches == 4);
    CHECK(m1.triangleCount() == m0.triangleCount());
    CHECK(maxNearestDistance(m1.positions, m0.positions, whole.cellSize) <= 1e-4f * whole.cellSize);
    auto [matched, close] = normalAgreement(m1, m0, whole.cellSize);
    CHECK(matched == m1.positions.size());
    CHECK(close == matched);
  }
  CHECK(counted[0] == 3);
  CHECK(counted[1] == 3);
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("GPU polygoniser: the animorphosis demo's creatures at three times agree with the CPU (lavapipe's loop limit included)",
          "[gpu][gpupoly]") {
  // 22 000 primitives and 41 000 ops each: refused on lavapipe (loop limit) before per-region
  // programs. Three times of each: the dinosaur walking, the dragon flying, C(t) inside the morph.
  // Every frame must polygonise and agree with the CPU, on lavapipe too (docs/gpu-polygonizer.md,
  // "Loop budget, second round"); a failure is printed with its reason (the pass whose loops were cut).
  auto project = makeAnimorphosisDemoProject();
  REQUIRE(project.ok());
  auto c = projectGenericTree(*project);
  REQUIRE(c.ok());
  Rig r = makeRig();
  const bool limited = GpuPolygonizer::loopLimit(r.ctx->properties()) != 0;
  const AnimorphosisTiming timing = animorphosisTiming(*project);
  const int kRes = 128;  // blocks of 8 cells: the fewer primitives reach one, the more fits the limiter
  struct Case {
    std::string name;
    std::function<FieldProgram(double)> at;
    double times[3];
  };
  const std::vector<Case> cases = {
      {"dinosaur", [&](double t) { return compileFieldProgram(project->actors[0].blobTree, t); }, {0.2, 0.9, 1.6}},
      {"dragon", [&](double t) { return compileFieldProgram(project->actors[1].blobTree, t); }, {0.3, 1.1, 2.4}},
      {"C(t)", [&](double t) { return compileGeneric(*c, timing, t); }, {2.6, 4.0, 5.4}}};
  int agreed = 0, failed = 0;
  for (const Case& cs : cases) {
    int caseAgreed = 0;
    for (double t : cs.times) {
      INFO(cs.name << " at " << t << " s");
      const FieldProgram p = cs.at(t);
      REQUIRE(p.primitiveCount() > 10000);
      const GpuField field = GpuField::single(p);
      CHECK(GpuPolygonizer::unsupported(field).empty());  // their size is no reason any more
      GpuPolygonizeSettings s;
      s.resolution = kRes;
      auto st = r.poly->polygonize(field, s);
      if (!st.ok()) {
        WARN(cs.name << " at " << t << " s: " << st.error() << (limited ? "" : " (no loop limiter)"));
        ++failed;
        continue;
      }
      CHECK(st->regionLists);
      CHECK(st->regionLongestOps < p.ops.size() / 2);
      auto gpu = r.poly->readBack();
      REQUIRE(gpu.ok());
      const TriangleMesh cpu = cpuMesh(p, kRes, std::nullopt);
      REQUIRE(cpu.triangleCount() > 1000);
      requireAgrees(*gpu, cpu, st->cellSize);
      ++agreed;
      ++caseAgreed;
    }
    if (cs.name == "dinosaur") CHECK(caseAgreed == 3);
  }
  WARN(agreed << " of 9 frames polygonised on the GPU and agreed with the CPU; " << failed
              << " failed naming the loop limit");
  CHECK(agreed == 9);
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("GPU polygoniser: a skeleton-correspondence pair is refused with its reason, the core's methods combine",
          "[gpu][gpupoly]") {
  // No device needed: unsupported() looks at the field (and at the loop limit of the devices polygonisers
  // were made on, which these small programs are far below).
  BlobTree ta = chainTree(4, 11, 1.3f), tb = chainTree(4, 11, 1.8f);
  FieldProgram a = compileFieldProgram(ta, 0.0), b = compileFieldProgram(tb, 0.0);
  CHECK(GpuPolygonizer::unsupported(GpuField::interpolation(a, b, 0.5f)).empty());
  CHECK(GpuPolygonizer::unsupported(GpuField::spaceTime(a, b, 0.5f)).empty());
  CHECK(GpuField::spaceTime(a, b, 0.5f).method == animorph::MorphMethod::SpaceTime);
  GpuField f = GpuField::interpolation(a, b, 0.5f);
  f.method = animorph::MorphMethod::SkeletonCorrespondence;
  CHECK_THAT(GpuPolygonizer::unsupported(f), Catch::Contains("morphImplicitField"));
  CHECK(GpuPolygonizer::unsupported(GpuField::single(a)).empty());
}

TEST_CASE("GPU polygoniser uploads programs beyond 64 KiB through a staging buffer: the CPU's mesh, frame after frame",
          "[gpu][gpupoly]") {
  Rig r = makeRig();
  // 500 animated points blended: a pool and bounds of ~80 KiB, past one vkCmdUpdateBuffer; three
  // times of the same tree (new values into the same buffers), then a small program (the
  // vkCmdUpdateBuffer path) and the large one again.
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(-0.45f, 0.45f);
  BlobNode root = makeBlobNode(NodeType::Blend, 1);
  for (int i = 0; i < 500; ++i) {
    BlobNode p = pointNode(2 + i, glm::vec3(u(rng), u(rng), u(rng)), 0.12f);
    std::get<Vec3Track>(p.params[size_t(paramIndex(NodeType::Point, "center"))])
        .setKey(1.0, glm::vec3(u(rng), u(rng), u(rng)));
    root.children.push_back(std::move(p));
  }
  const BlobTree tree = treeOf(root, 0.5f);
  const FieldProgram small = compileFieldProgram(chainTree(12, 5, 2.0f), 0.0);
  GpuPolygonizeSettings s;
  s.resolution = 32;
  s.bounds = cube(0.7f);
  for (double t : {0.0, 0.4, -1.0, 0.9}) {
    INFO("t = " << t);
    const FieldProgram p = t < 0.0 ? small : compileFieldProgram(tree, t);
    Result<PackedFieldPrograms> packed = packFieldPrograms(p);
    REQUIRE(packed.ok());
    CHECK(((packed->pool.size() + packed->bounds.size()) * 16 > 65536) == (t >= 0.0));
    GpuPolygonizeStats st;
    TriangleMesh gpu = gpuMesh(*r.poly, GpuField::single(p), s, &st);
    TriangleMesh cpu = cpuMesh(p, 32, s.bounds);
    REQUIRE(cpu.triangleCount() > 200);
    requireAgrees(gpu, cpu, st.cellSize);
  }
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("GPU field programs: fieldProgramsShape gives packFieldPrograms' variant without packing", "[gpu][gpupoly]") {
  std::vector<FieldProgram> programs;
  for (unsigned seed = 1; seed <= 8; ++seed) {
    std::mt19937 rng(seed);
    int id = 1;
    programs.push_back(compileFieldProgram(treeOf(randomNode(rng, 3, id), 0.5f), 0.5));
  }
  programs.push_back(compileFieldProgram(makeBlobCreature(), 0.3));
  programs.push_back(compileFieldProgram(chainTree(40, 3), 0.0));
  for (size_t i = 0; i < programs.size(); ++i)
    for (const FieldProgram* b : {static_cast<const FieldProgram*>(nullptr),
                                   static_cast<const FieldProgram*>(&programs[(i + 1) % programs.size()])}) {
      INFO("program " << i << (b ? " with the next" : " alone"));
      Result<PackedFieldPrograms> pk = packFieldPrograms(programs[i], b);
      REQUIRE(pk.ok());
      const FieldProgramsShape shape = fieldProgramsShape(programs[i], b);
      CHECK(shape.features == pk->features);
      CHECK(shape.kinds == pk->kinds);
      CHECK(shape.poolWords == pk->pool.size());
    }
}
