#pragma once
// Collada morph controllers (Blender's shape keys) read beside assimp 5.2, which cannot read them:
// its parser keeps the '#' of <morph source="#GEOMETRY">, never reads the <targets> inputs, and then
// refuses the whole file ("Unable to resolve library reference "#Body-mesh""). This reads each
// <morph> controller's base geometry, target geometries and weights from the document itself, and
// rewrites the document for assimp:
//   * every <morph> controller is removed; a reference to one ("#CONTROLLER": a skin's source,
//     an instance_controller's url) then names its base geometry, so assimp loads the mesh;
//   * each base geometry's <vertices> gain a texture coordinate set (set kColladaIndexSet) holding
//     (position index, kColladaIndexTag), so that after assimp has split vertices per face corner
//     and joined identical ones, each of its vertices still says which position of the file it is.
// Bounded: the scan is linear in the document; arrays are parsed from the document's own text
// (at most one number per two bytes), and the shapes' vertices together are capped.
#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/util/result.h"

namespace animorph {

// The tag set's coordinates are (position index, kColladaIndexTag); set attribute kColladaIndexSet
// (assimp packs sets, so the tag is the last set of each mesh built from a tagged geometry).
inline constexpr float kColladaIndexTag = -7919.0f;
inline constexpr int kColladaIndexSet = 7;

struct ColladaMorphTarget {
  std::string name;                // the target geometry's name attribute (its id if it has none)
  std::vector<glm::vec3> deltas;   // per position of the base geometry, in the geometry's units and axes
};

struct ColladaMorph {
  std::string controllerId;
  std::string baseGeometryId;            // assimp 5.2 names the meshes it builds from it by this id
  std::vector<glm::vec3> basePositions;  // the base geometry's positions, for checking the mapping
  std::vector<ColladaMorphTarget> targets;
  std::vector<float> defaultWeights;     // one per target (0 where the file gives none)
  std::string weightSourceId;            // the MORPH_WEIGHT <source>'s id ("" when none)
  std::string weightArrayId;             // its <float_array>'s id ("" when none)
  // The weight animation: the <channel>s addressing this morph's weights (io/collada_morph_weights),
  // merged so that every key holds every target's weight (a target no channel animates keeps its
  // default weight). Empty times: not animated.
  std::vector<float> weightTimesSec;     // non-decreasing, in seconds
  std::vector<float> weightKeys;         // weightTimesSec.size() x targets.size(), key by key
  bool weightsStep = false;              // every key STEP (held until the next); else linear
};

struct ColladaMorphDocument {
  std::string document;               // the document for assimp; empty when the file has no <morph>
  std::vector<ColladaMorph> morphs;   // one per <morph> controller
  std::vector<std::string> notes;     // lines for the import report (keys taken as linear, ...)
};

// Reads bytes (a Collada document; file is the path as given, for messages). A document without
// <morph> gives an empty result (nothing rewritten). Fails naming file, the controller or geometry
// and the reason: a base or target geometry that is missing, has no positions or a different
// number of them, a <morph> whose base is not a geometry, or targets x positions over
// maxShapeVertices. The morphs' weight animation is read too (io/collada_morph_weights.h: its
// errors), and the <channel>s it read are left out of the document for assimp.
Result<ColladaMorphDocument> prepareColladaMorphs(const std::string& file, const std::string& bytes,
                                                  size_t maxShapeVertices);

}  // namespace animorph
