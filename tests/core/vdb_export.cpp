// OpenVDB level sets of the implicit frames (poly/level_set_sampler.h, io/vdb_export.h,
// export/frame_volume.h), read back with OpenVDB itself.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>

#include "core/animorphosis/evaluate_generic.h"
#include "core/export/export_project.h"
#include "core/export/frame_volume.h"
#include "core/project/animorphosis_project.h"
#include "core/project/project_io.h"
#include "core/field/surface_color.h"
#include "core/io/vdb_export.h"
#include "util/animorph_fixtures.h"
#include "util/morph_fixtures.h"
#include "util/temp_dir.h"

using namespace animorph;
using namespace animorph::test;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

openvdb::GridPtrVecPtr readGrids(const std::string& path) {
  openvdb::initialize();
  openvdb::io::File file(path);
  file.open();
  openvdb::GridPtrVecPtr grids = file.getGrids();
  file.close();
  return grids;
}

// The file's level set: its first grid, a float grid (a colour grid "Cd" may follow it).
openvdb::FloatGrid::Ptr readLevelSet(const std::string& path) {
  openvdb::GridPtrVecPtr grids = readGrids(path);
  REQUIRE(!grids->empty());
  REQUIRE(grids->size() <= 2);
  auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>((*grids)[0]);
  REQUIRE(grid);
  return grid;
}

// Two balls (point primitives of radius 0.5 at x = -+0.45), red on the left, blue on the right.
FieldProgram twoColouredBalls() {
  FieldProgram p;
  p.threshold = 0.5f;
  for (float x : {-0.45f, 0.45f}) {
    SkeletalPrimitive prim;
    prim.skeleton.kind = SkeletonKind::Point;
    prim.skeleton.p0 = glm::vec3(x, 0.0f, 0.0f);
    prim.radius = 0.5f;
    prim.intensity = 1.0f;
    prim.stiffness = 3.0f;
    p.nextColor = x < 0.0f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 0.0f, 1.0f);
    p.addSkeletal(prim, x > 0.0f, false);  // the second joins the first's sum (a blend)
  }
  p.finish();
  return p;
}

// A ball: one point primitive I (1 - (d/R)^2)^k with threshold T, whose surface is the sphere of
// radius R sqrt(1 - (T/I)^(1/k)) about the origin.
FieldProgram ballProgram(float& surfaceRadius) {
  FieldProgram p;
  p.threshold = 0.5f;
  SkeletalPrimitive prim;
  prim.skeleton.kind = SkeletonKind::Point;
  prim.radius = 1.0f;
  prim.intensity = 1.0f;
  prim.stiffness = 3.0f;
  p.addSkeletal(prim, false, false);
  p.finish();
  surfaceRadius = std::sqrt(1.0f - std::pow(0.5f, 1.0f / 3.0f));
  return p;
}

}  // namespace

TEST_CASE("vdb export: a ball's band is its signed distance, the file a level set with the grid's transform", "[vdb]") {
  float r0 = 0.0f;
  const FieldProgram ball = ballProgram(r0);
  LevelSetSettings ls;
  ls.grid.resolution = 32;
  auto band = sampleLevelSet(ball, ls);
  INFO(band.error());
  REQUIRE(band.ok());
  auto grid = polygonizeGrid(ball, ls.grid);
  REQUIRE(grid.ok());
  const float h = band->voxelSize;
  CHECK(h == grid->cellSize);
  CHECK(band->background == Approx(3.0f * h));
  REQUIRE(band->index.size() > 1000);
  // First order -f/|grad f| against the exact distance |p| - r0: within a tenth of a voxel next to
  // the surface, and within half a voxel across the band of 3 voxels.
  float nearErr = 0.0f, bandErr = 0.0f;
  int inside = 0;
  for (size_t v = 0; v < band->index.size(); ++v) {
    const glm::vec3 p = band->origin + h * glm::vec3(band->index[v]);
    const float exact = glm::length(p) - r0;
    const float err = std::abs(band->distance[v] - exact);
    bandErr = std::max(bandErr, err);
    if (std::abs(exact) < h) nearErr = std::max(nearErr, err);
    inside += band->distance[v] < 0.0f;
    CHECK(std::abs(band->distance[v]) < band->background);
  }
  CAPTURE(h, nearErr / h, bandErr / h);
  CHECK(nearErr < 0.1f * h);
  CHECK(bandErr < 0.5f * h);
  CHECK(inside > 100);

  TempDir tmp;
  const std::string path = tmp.file("ball.vdb");
  Status st = writeVdbLevelSet(*band, path);
  INFO(st.error());
  REQUIRE(st.ok());
  auto g = readLevelSet(path);
  CHECK(g->getName() == "surface");
  CHECK(g->getGridClass() == openvdb::GRID_LEVEL_SET);
  CHECK(g->voxelSize()[0] == Approx(h));
  CHECK(g->transform().isLinear());
  CHECK(g->background() == Approx(band->background));
  // Voxel (i, j, k) is the polygoniser's corner origin + h (i, j, k).
  const openvdb::Vec3d w = g->indexToWorld(openvdb::Coord(3, 4, 5));
  CHECK(w.x() == Approx(band->origin.x + 3.0f * h));
  CHECK(w.z() == Approx(band->origin.z + 5.0f * h));
  openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sample(*g);
  CHECK(sample.wsSample(openvdb::Vec3d(0.0)) == Approx(-band->background));  // deep inside: flood-filled
  CHECK(sample.wsSample(openvdb::Vec3d(3.0, 0.0, 0.0)) == Approx(band->background));
  CHECK(std::abs(sample.wsSample(openvdb::Vec3d(r0, 0.0, 0.0))) < 0.05 * h);
  // The written band (swept out from the voxels next to the surface) against the exact distance.
  float fileNearErr = 0.0f, fileBandErr = 0.0f;
  size_t active = 0;
  for (auto it = g->cbeginValueOn(); it; ++it, ++active) {
    const openvdb::Vec3d p = g->indexToWorld(it.getCoord());
    const float exact = float(p.length()) - r0;
    const float err = std::abs(*it - exact);
    fileBandErr = std::max(fileBandErr, err);
    if (std::abs(exact) < h) fileNearErr = std::max(fileNearErr, err);
    CHECK(std::abs(*it) <= g->background());
  }
  CAPTURE(fileNearErr / h, fileBandErr / h);
  CHECK(active > band->index.size() / 2);
  CHECK(fileNearErr < 0.1f * h);
  CHECK(fileBandErr < 0.5f * h);
}

TEST_CASE("vdb export: a coloured field's file carries a colour grid Cd beside the level set, with each side's colour",
          "[vdb][color]") {
  const FieldProgram balls = twoColouredBalls();
  LevelSetSettings ls;
  ls.grid.resolution = 32;
  ls.colors = true;
  auto band = sampleLevelSet(balls, ls);
  INFO(band.error());
  REQUIRE(band.ok());
  const float h = band->voxelSize;
  REQUIRE(band->colorVoxel.size() == band->color.size());
  REQUIRE(band->colorVoxel.size() > 500);
  // Exactly the voxels within kColorBandVoxels of the surface have a colour.
  size_t near = 0;
  for (float d : band->distance) near += std::abs(d) < kColorBandVoxels * h;
  CHECK(band->colorVoxel.size() == near);
  CHECK(band->colorVoxel.size() < band->index.size());

  TempDir tmp;
  const std::string path = tmp.file("balls.vdb");
  REQUIRE(writeVdbLevelSet(*band, path).ok());
  openvdb::GridPtrVecPtr grids = readGrids(path);
  REQUIRE(grids->size() == 2);
  CHECK((*grids)[0]->getName() == "surface");
  auto cd = openvdb::gridPtrCast<openvdb::Vec3SGrid>((*grids)[1]);
  REQUIRE(cd);
  CHECK(cd->getName() == "Cd");
  CHECK(cd->voxelSize()[0] == Approx(h));
  CHECK(cd->activeVoxelCount() == openvdb::Index64(band->colorVoxel.size()));
  // The far ends of the two balls (apart: each beyond the other's reach there) are their own colour.
  openvdb::tools::GridSampler<openvdb::Vec3SGrid, openvdb::tools::BoxSampler> sample(*cd);
  const float r = 0.45f + 0.5f * std::sqrt(1.0f - std::pow(0.5f, 1.0f / 3.0f));
  const openvdb::Vec3s left = sample.wsSample(openvdb::Vec3d(-r, 0.0, 0.0));
  const openvdb::Vec3s right = sample.wsSample(openvdb::Vec3d(r, 0.0, 0.0));
  CAPTURE(left.x(), left.z(), right.x(), right.z());
  CHECK(left.x() > 0.95f);
  CHECK(left.z() < 0.05f);
  CHECK(right.z() > 0.95f);
  CHECK(right.x() < 0.05f);
  // Every stored colour is the evaluator's at its voxel, and each voxel's value is in the file.
  SurfaceColorEvaluator colors;
  auto acc = cd->getConstAccessor();
  for (size_t c = 0; c < band->colorVoxel.size(); c += 37) {
    const glm::ivec3 v = band->index[band->colorVoxel[c]];
    const glm::vec3 expect = colors.evaluatePoint(balls, band->origin + h * glm::vec3(v));
    const openvdb::Vec3s got = acc.getValue(openvdb::Coord(v.x, v.y, v.z));
    CHECK(std::abs(got.x() - expect.x) < 1e-5f);
    CHECK(std::abs(got.z() - expect.z) < 1e-5f);
  }

  // Without colours: the level set alone.
  ls.colors = false;
  auto plain = sampleLevelSet(balls, ls);
  REQUIRE(plain.ok());
  CHECK(plain->colorVoxel.empty());
  const std::string plainPath = tmp.file("plain.vdb");
  REQUIRE(writeVdbLevelSet(*plain, plainPath).ok());
  CHECK(readGrids(plainPath)->size() == 1);
}

TEST_CASE("vdb export: a B->C frame of the demo morph crosses zero within half a voxel of its polygonised mesh",
          "[vdb]") {
  const DemoMorph& dm = demoMorph();
  const MorphRuntime& rt = *dm.runtime;
  const int frame = (rt.setup.markers.b + rt.setup.markers.c) / 2;
  const double t = rt.timeline.frameToSec(frame);
  const int res = 40;
  MorphFrameSettings fs;
  fs.resolution = res;
  auto mesh = evaluateMorphFrame(rt, t, fs);
  REQUIRE(mesh.ok());
  REQUIRE(mesh->stage == MorphStage::Morph);
  REQUIRE(mesh->mesh.positions.size() > 500);
  auto band = morphFrameLevelSet(rt, t, res, 0, nullptr);
  INFO(band.error());
  REQUIRE(band.ok());
  REQUIRE(band->has_value());
  CHECK((*band)->voxelSize == mesh->polygonize.cellSize);

  TempDir tmp;
  const std::string path = tmp.file("morph_" + std::to_string(frame) + ".vdb");
  REQUIRE(writeVdbLevelSet(**band, path).ok());
  auto g = readLevelSet(path);
  CHECK(g->getGridClass() == openvdb::GRID_LEVEL_SET);
  const double h = g->voxelSize()[0];
  CHECK(h == Approx(mesh->polygonize.cellSize));
  openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sample(*g);
  // Trilinear samples at the mesh's vertices: the zero crossing is within half a voxel of each;
  // a voxel in along the normal is inside (negative), a voxel out is outside.
  double worst = 0.0;
  size_t wrongSide = 0;
  const auto& m = mesh->mesh;
  for (size_t v = 0; v < m.positions.size(); ++v) {
    const glm::vec3 p = m.positions[v], n = m.normals[v];
    worst = std::max(worst, std::abs(double(sample.wsSample(openvdb::Vec3d(p.x, p.y, p.z)))));
    const glm::vec3 in = p - float(h) * n, out = p + float(h) * n;
    wrongSide += sample.wsSample(openvdb::Vec3d(in.x, in.y, in.z)) >= 0.0f;
    wrongSide += sample.wsSample(openvdb::Vec3d(out.x, out.y, out.z)) <= 0.0f;
  }
  CAPTURE(h, worst / h, wrongSide, m.positions.size());
  CHECK(worst < 0.5 * h);
  // Thin parts (about a voxel thick) and close neighbours can put a side's sample past another
  // surface: at 40^3 about 2 % of the samples.
  CHECK(wrongSide < m.positions.size() / 20);

  // Skinned-mesh frames (before A: the creature plays) have no field.
  auto none = morphFrameLevelSet(rt, rt.timeline.frameToSec(0), res, 0, nullptr);
  REQUIRE(none.ok());
  CHECK_FALSE(none->has_value());
}

TEST_CASE("vdb export: an export writes a level set per implicit frame, bad paths and skinned-only ranges are named",
          "[vdb][export]") {
  TempDir tmp;
  Project p = walkerToFlyerProject("morph me");
  ExportSettings s;
  s.format = ExportFormat::VdbSequence;
  s.useTimeline = false;
  s.first = 40;
  s.last = 41;
  s.resolution = 20;
  s.output = "volumes";
  JobProgress progress;
  auto r = exportProject(p, tmp.path().string(), s, progress);
  INFO(r.error());
  REQUIRE(r.ok());
  const std::string dir = (tmp.path() / "volumes").string();
  CHECK(r->files == std::vector<std::string>{dir + "/morph_me_0040.vdb", dir + "/morph_me_0041.vdb"});
  CHECK(readLevelSet(r->files[0])->getGridClass() == openvdb::GRID_LEVEL_SET);
  // The format is saved in the project as "vdb".
  Project saved = p;
  saved.exportSettings = s;
  auto back = projectFromJson(projectToJson(saved), "p.animorph");
  REQUIRE(back.ok());
  CHECK(back->exportSettings.format == ExportFormat::VdbSequence);
  CHECK(projectToJson(saved).find("\"vdb\"") != std::string::npos);

  // Unwritable: the folder of the frames is an existing file.
  const std::string blocker = tmp.file("a_file");
  { std::ofstream(blocker) << "x"; }
  s.output = blocker + "/volumes";
  auto refused = exportProject(p, tmp.path().string(), s, progress);
  REQUIRE_FALSE(refused.ok());
  CHECK_THAT(refused.error(), Contains(blocker));
  // The writer itself names the path and the reason.
  auto band = fieldLevelSet(compileGeneric(projectGenericTree(p).value(), animorphosisTiming(p), 1.5), 16, 0, nullptr);
  REQUIRE(band.ok());
  const std::string missing = tmp.file("no/such/folder/f.vdb");
  Status st = writeVdbLevelSet(**band, missing);
  REQUIRE_FALSE(st.ok());
  CHECK_THAT(st.error(), Contains(missing) && Contains("cannot write"));

  // The demo morph's first frames are the creature's skinned mesh: nothing to write, said so.
  const DemoMorph& dm = demoMorph();
  s.output = tmp.file("skinned");
  s.first = 0;
  s.last = 1;
  auto skinned = exportProject(dm.project, dm.dir, s, progress);
  REQUIRE_FALSE(skinned.ok());
  CHECK_THAT(skinned.error(), Contains("skinned meshes") && Contains("0..1"));
}
