// The one translation unit that includes OpenVDB (its headers are heavy): built as the library
// animorph_vdb (engine/core/CMakeLists.txt).
#include "core/io/vdb_export.h"

#include "core/util/atomic_file.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <sstream>

#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/FastSweeping.h>
#include <openvdb/tools/Prune.h>
#include <openvdb/tools/SignedFloodFill.h>

namespace animorph {

namespace {

// The band's colours as a vector grid "Cd" (Houdini's name for colour; Blender lists it as a
// float-vector grid of the volume): linear RGB at the voxels next to the surface, inactive
// (0, 0, 0) elsewhere, the level set's transform.
openvdb::Vec3SGrid::Ptr colorGrid(const LevelSetVoxels& band, const openvdb::math::Transform::Ptr& xform) {
  auto grid = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
  grid->setTransform(xform);
  grid->setName("Cd");
  grid->setGridClass(openvdb::GRID_UNKNOWN);
  grid->setVectorType(openvdb::VEC_INVARIANT);  // a colour: not moved by a transform
  auto acc = grid->getAccessor();
  for (size_t c = 0; c < band.colorVoxel.size() && c < band.color.size(); ++c) {
    const glm::ivec3& v = band.index[band.colorVoxel[c]];
    acc.setValue(openvdb::Coord(v.x, v.y, v.z), openvdb::Vec3s(band.color[c].x, band.color[c].y, band.color[c].z));
  }
  return grid;
}

}  // namespace

Status writeVdbLevelSet(const LevelSetVoxels& band, const std::string& path, const std::string& gridName) {
  if (band.cancelled) return Error{path + ": the level set was cancelled before it was complete; not written"};
  if (!(band.voxelSize > 0.0f) || !std::isfinite(band.voxelSize) || !(band.background > 0.0f))
    return Error{path + ": the level set has no valid voxel size (" + std::to_string(band.voxelSize) + ")"};
  try {
    openvdb::initialize();  // idempotent and thread-safe
    auto grid = openvdb::FloatGrid::create(band.background);
    openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(double(band.voxelSize));
    xform->postTranslate(openvdb::Vec3d(band.origin.x, band.origin.y, band.origin.z));
    grid->setTransform(xform);
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
    grid->setName(gridName);
    // The sampled band: first-order distances (poly/level_set_sampler.h).
    auto acc = grid->getAccessor();
    bool inside = false, outside = false;
    for (size_t v = 0; v < band.index.size(); ++v) {
      acc.setValue(openvdb::Coord(band.index[v].x, band.index[v].y, band.index[v].z), band.distance[v]);
      (band.distance[v] < 0.0f ? inside : outside) = true;
    }
    openvdb::tools::signedFloodFill(grid->tree());
    if (inside && outside) {
      // Redistanced by fast sweeping (the Eikonal equation from the zero crossing), then widened to
      // the full band (where the field's support ends its first-order values are missing): the
      // voxels within a voxel of the surface keep their first-order values, which lie closer to
      // the field's zero set than the sweep's (measured: docs/export.md).
      const int rings = int(std::ceil(band.background / band.voxelSize));
      openvdb::FloatGrid::Ptr swept = openvdb::tools::sdfToSdf(*grid, 0.0f);
      swept = openvdb::tools::dilateSdf(*swept, rings, openvdb::tools::NN_FACE_EDGE_VERTEX);
      for (auto it = swept->cbeginValueOn(); it; ++it) {
        if (std::abs(*it) < band.background) acc.setValue(it.getCoord(), *it);
        else acc.setValueOff(it.getCoord(), std::copysign(band.background, *it));
      }
      for (size_t v = 0; v < band.index.size(); ++v)
        if (std::abs(band.distance[v]) < band.voxelSize)
          acc.setValue(openvdb::Coord(band.index[v].x, band.index[v].y, band.index[v].z), band.distance[v]);
    }
    // The inside (beyond the band) becomes -background, as OpenVDB's level-set tools expect.
    openvdb::tools::signedFloodFill(grid->tree());
    openvdb::tools::pruneLevelSet(grid->tree());
    // Serialised in memory (the same format as io::File's), then written atomically.
    std::ostringstream bytes(std::ios_base::binary);
    openvdb::GridPtrVec grids{grid};
    if (!band.colorVoxel.empty()) grids.push_back(colorGrid(band, xform));
    openvdb::io::Stream(bytes).write(grids);
    if (Status st = writeFileAtomic(path, bytes.str()); !st)
      return Error{"cannot write the OpenVDB file " + st.error()};
  } catch (const std::exception& e) {  // openvdb::Exception among them
    return Error{path + ": cannot make the OpenVDB grid: " + e.what()};
  }
  return {};
}

}  // namespace animorph
