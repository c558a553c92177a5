// The GPU frame's host half prepared ahead (GpuPolygonizer::prepare, GpuPreparedFrame): on another
// thread, with no device; a record or polygonize() given it computes no bounds, packing or region
// lists (counted) and draws exactly the mesh of the unprepared path; a prepared frame that does not
// suit the call is prepared again on the spot. The editor's preview prepares on its compile thread.
#include <catch2/catch.hpp>

#include <random>
#include <thread>

#include "core/blobtree/compile.h"
#include "core/scene/morph_preview_source.h"
#include "demo/blob_creature.h"
#include "gpu_fixture.h"
#include "polygonizer_rig.h"
#include "gpu/polygonizer/gpu_polygonizer.h"
#include "gpu/polygonizer/implicit_preview.h"
#include "util/blob_builders.h"
#include "util/morph_fixtures.h"

using namespace animorph;
using namespace animorph::gpu;
using namespace animorph::test;

namespace {

// The shared rig; mesh() is its polygonisation read back.
struct PolyRig : PolygonizerRig {
  TriangleMesh mesh(const GpuField& f, const GpuPolygonizeSettings& s, const GpuPreparedFrame* prepared,
                    GpuPolygonizeStats& stats) {
    return polygonizeAndRead(f, s, prepared, stats);
  }
};

// A seeded random tree of every node type (tests/util/blob_builders.h).
BlobTree randomTree(unsigned seed) {
  std::mt19937 rng(seed);
  int nextId = 1;
  return treeOf(randomNode(rng, 3, nextId), 0.5f);
}

void requireIdentical(const TriangleMesh& a, const TriangleMesh& b) {
  REQUIRE(a.positions.size() == b.positions.size());
  REQUIRE(a.indices.size() == b.indices.size());
  CHECK(a.positions == b.positions);
  CHECK(a.normals == b.normals);
  CHECK(a.indices == b.indices);
}

}  // namespace

TEST_CASE("GPU polygoniser: a frame prepared on another thread is polygonised with no host preparation, the same mesh",
          "[gpu][gpupoly]") {
  PolyRig r;
  const uint64_t limit = GpuPolygonizer::loopLimit(r.ctx->properties());
  const FieldProgram creature = compileFieldProgram(makeBlobCreature(), 0.5);
  std::vector<FieldProgram> randoms;
  for (unsigned seed : {3u, 8u, 21u}) randoms.push_back(compileFieldProgram(randomTree(seed), 0.0));
  struct Case {
    const char* name;
    GpuField field;
    GpuPolygonizeSettings::RegionPrograms lists;
  };
  std::vector<Case> cases = {{"creature, whole programs", GpuField::single(creature), GpuPolygonizeSettings::RegionPrograms::Off},
                             {"creature, region lists", GpuField::single(creature), GpuPolygonizeSettings::RegionPrograms::On},
                             {"random morph", GpuField::interpolation(randoms[0], randoms[1], 0.3f),
                              GpuPolygonizeSettings::RegionPrograms::On},
                             {"random space-time", GpuField::spaceTime(randoms[1], randoms[2], 0.6f),
                              GpuPolygonizeSettings::RegionPrograms::Auto}};
  int nonEmpty = 0;
  for (const Case& c : cases) {
    INFO(c.name);
    GpuPolygonizeSettings s;
    s.resolution = 40;
    s.regionPrograms = c.lists;
    // Prepared off this thread, as the preview's compile thread does.
    Result<std::shared_ptr<const GpuPreparedFrame>> prepared = Error{"not run"};
    std::thread([&] { prepared = GpuPolygonizer::prepare(c.field, s, limit); }).join();
    INFO(prepared.error());
    REQUIRE(prepared.ok());
    CHECK((*prepared)->milliseconds() >= 0.0);
    GpuPolygonizeStats plain, fromPrepared;
    const uint64_t before = r.poly->preparesInRecord();
    const TriangleMesh m0 = r.mesh(c.field, s, nullptr, plain);
    CHECK(plain.preparedInRecord);
    CHECK(r.poly->preparesInRecord() == before + 1);
    const TriangleMesh m1 = r.mesh(c.field, s, prepared->get(), fromPrepared);
    CHECK_FALSE(fromPrepared.preparedInRecord);
    CHECK(fromPrepared.prepareMs == 0.0);
    CHECK(r.poly->preparesInRecord() == before + 1);  // nothing computed for the prepared frame
    CHECK(fromPrepared.regionLists == plain.regionLists);
    CHECK(fromPrepared.gridX == plain.gridX);
    requireIdentical(m1, m0);
    if (m0.triangleCount() > 50) ++nonEmpty;
    // The editor's path: a record given the prepared frame prepares nothing either.
    Status recorded;
    REQUIRE(r.ctx->submitImmediate([&](VkCommandBuffer cmd) {
      recorded = r.poly->record(cmd, 0, c.field, s, prepared->get());
    }).ok());
    INFO(recorded.error());
    REQUIRE(recorded.ok());
    CHECK_FALSE(r.poly->lastStats().preparedInRecord);
    REQUIRE(r.poly->recordFitted(0).ok());
    CHECK(r.poly->lastStats().triangles == m0.triangleCount());
    CHECK(r.poly->preparesInRecord() == before + 1);
    // A frame prepared for other settings (another resolution) is not used: prepared on the spot.
    GpuPolygonizeSettings other = s;
    other.resolution = 48;
    GpuPolygonizeStats again;
    r.mesh(c.field, other, prepared->get(), again);
    CHECK(again.preparedInRecord);
    CHECK(again.gridX != plain.gridX);
    CHECK(r.poly->preparesInRecord() == before + 2);
  }
  CHECK(nonEmpty >= 3);
  // Preparing what cannot be polygonised fails with the record's reason.
  GpuPolygonizeSettings bad;
  bad.resolution = 1;
  auto refused = GpuPolygonizer::prepare(GpuField::single(creature), bad, limit);
  REQUIRE_FALSE(refused.ok());
  CHECK_THAT(refused.error(), Catch::Contains("resolution 1"));
  CHECK(r.ctx->validationErrorCount() == 0);
}

TEST_CASE("implicit preview: the compile thread prepares the GPU frame, the record step prepares nothing",
          "[gpu][preview]") {
  std::unique_ptr<Context> ctx = makeTestContext();
  std::shared_ptr<const MorphRuntime> rt = demoMorph().runtime;
  ImplicitPreviewSettings ps;
  ps.interactiveResolution = 24;
  ps.refinedResolution = 32;
  ps.gpu = true;
  ps.paceGpu = false;
  const MorphMarkers& mk = rt->setup.markers;
  ImplicitPreview preview(*ctx);
  uint64_t compiledOnThread = 0;
  for (double u : {0.2, 0.5, 0.8}) {
    const double t = rt->timeline.frameToSec(int(mk.b + u * (mk.c - mk.b)));
    auto source = morphPreviewSource(rt, t);
    for (int i = 0; i < 60 && (i == 0 || preview.busy()); ++i) {
      preview.update(source, t, ps);
      preview.endFrame();
      preview.waitIdle(60.0);
    }
    REQUIRE_FALSE(preview.busy());
    REQUIRE(preview.gpuFailure().empty());
    CHECK(preview.status().gpu);
    CHECK(preview.status().triangles > 100);
    compiledOnThread = preview.fieldCounters().onCompileThread + preview.fieldCounters().onCallerThread;
  }
  CHECK(preview.gpuRecordCount() >= 3);
  CHECK(compiledOnThread >= 3);
  // Every record and screenshot polygonisation used the frame prepared with its field.
  CHECK(preview.gpuPreparesInRecord() == 0);
  CHECK(preview.fieldCounters().prepareMs > 0.0);  // prepared with the fields instead
  CHECK(ctx->validationErrorCount() == 0);
}
