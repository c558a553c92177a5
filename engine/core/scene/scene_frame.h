#pragma once
// The scene at one time: what to draw, in world space. Evaluating a frame is
// a pure function of the project, the loaded assets and the time; the
// renderer, the picker and the CLI all consume a SceneFrame.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/project/actor_time.h"
#include "core/project/asset_cache.h"
#include "core/project/project.h"
#include "core/math/bounds.h"
#include "core/rig/character.h"
#include "core/scene/blob_guides.h"

namespace animorph {

struct MorphRuntime;
struct TransitionFrame;
class PreviewSource;

// One mesh of one actor, posed.
struct MeshDraw {
  std::string actorId;
  std::shared_ptr<const Character> character;
  int meshNode = -1;   // node that draws the mesh
  int meshIndex = -1;  // index into character->meshes
  glm::mat4 model{1.0f};             // actor transform * global(meshNode)
  std::vector<glm::mat4> joints;     // skinning matrices (rig/pose.h jointMatrices)
  std::vector<float> morphWeights;   // blend-shape weights (rig/pose.h morphWeightsAt); empty: none
  float opacity = 1.0f;              // < 1: cross-fade, drawn dithered (gpu::MeshDraw::opacity)
  bool complementDither = false;     // the complementary dither pattern
  // Base colour (sRGB); none: the renderer's default for imported meshes. A BlobTree surface
  // polygonised into a mesh (animorph-cli render) takes the implicit surfaces' clay tone.
  std::optional<glm::vec3> color;
};

// A mesh of a morph actor in its collapse or expansion, deformed on the GPU
// (scene/morph_scene.h): the posed mesh, the prepared morph whose stand-in
// binding the vertices use (uploaded once per runtime), and the frame's
// transition parameters.
struct TransitionDraw {
  MeshDraw mesh;
  std::shared_ptr<const MorphRuntime> runtime;
  bool targetActor = false;   // the runtime's target (expansion), else its source
  size_t firstVertex = 0;     // of this mesh in the binding (concatenated over meshNodes())
  std::shared_ptr<const TransitionFrame> frame;
};

// A bone of the skeleton overlay: from a joint's parent to the joint.
struct BoneDraw {
  std::string actorId;
  int node = -1;
  glm::vec3 head{0.0f};  // parent joint, world space
  glm::vec3 tail{0.0f};  // this joint, world space
};

// A BlobTree actor. Its surface is polygonised off the frame loop (poly/
// preview_polygonizer.h) at treeTimeSec and drawn with model.
struct BlobDraw {
  std::string actorId;
  glm::mat4 model{1.0f};    // the actor's transform
  double treeTimeSec = 0.0; // blobActorTimeSec of the scene time
  // Drawn instead of the actor's tree when set: the animorphosis' C(t)
  // (scene/animorphosis_scene.h) as a preview source compiled straight from C (a
  // new pointer when it changes), which the preview polygonises...
  std::shared_ptr<const PreviewSource> source;
  // ... and as a tree of constant tracks, built only when asked (ownTree(): the
  // particle view, the CLI's render); valid while the AnimorphosisCache and the
  // project of the frame are.
  std::function<std::shared_ptr<const BlobTree>()> snapshot;
  // A tree of the draw's own (the snapshot when one is set), or null: the actor's.
  std::shared_ptr<const BlobTree> ownTree() const { return snapshot ? snapshot() : nullptr; }
  // A ghost (scene/animorphosis_scene.h): its own preview, keyed "actorId#ghost"
  // (empty: the actor's), drawn dithered at opacity < 1 and not pickable.
  std::string previewKey;
  float opacity = 1.0f;
  // The surface's colour (a ghost's tint: scene/animorphosis_scene.h); none: the implicit surfaces' clay tone.
  std::optional<glm::vec3> tint;
  const std::string& key() const { return previewKey.empty() ? actorId : previewKey; }
};

// The skeleton drawings (scene/blob_guides.h) of a frame's BlobTree actors,
// built when first asked for. Building one walks every node of the tree (about
// 140 ms for each creature of the animorphosis demo), which a frame that
// neither shows nor picks the skeleton -- or whose animorphosis replaces the
// actors -- never pays. The drawings are built from the project's trees, so
// get() must be called before the project the frame came from changes.
class LazyBlobGuides {
 public:
  // The drawing of tree at timeSec under the actor transform model, for actorId.
  void add(const std::string& actorId, const BlobTree& tree, double timeSec, const glm::mat4& model);
  // Forgets the drawings of the actors for which drop(actorId) is true.
  template <class Pred>
  void dropIf(Pred drop) {
    std::erase_if(sources_, [&](const Source& s) { return drop(s.actorId); });
    if (built_) std::erase_if(*built_, [&](const BlobGuides& g) { return drop(g.actorId); });
  }
  // Every drawing, in the order added (built on the first call).
  const std::vector<BlobGuides>& get() const;
  bool empty() const { return sources_.empty(); }

 private:
  struct Source {
    std::string actorId;
    const BlobTree* tree = nullptr;
    double timeSec = 0.0;
    glm::mat4 model{1.0f};
  };
  std::vector<Source> sources_;
  mutable std::optional<std::vector<BlobGuides>> built_;
};

struct SceneFrame {
  double timeSec = 0.0;
  std::vector<MeshDraw> meshes;
  std::vector<TransitionDraw> transitions;
  std::vector<BlobDraw> blobs;
  LazyBlobGuides blobGuides;              // skeleton drawing of each BlobTree actor
  std::vector<BoneDraw> bones;
  std::vector<glm::vec3> jointPositions;  // every skin joint, world space
  std::vector<std::string> errors;        // "actor 'x': <asset load error>"
};

// Evaluates every visible actor of project at timeSec. baseDir resolves the
// actors' relative asset paths. Actors whose asset failed to load are
// reported in errors and skipped.
SceneFrame evaluateScene(const Project& project, const std::string& baseDir, AssetCache& assets, double timeSec);

// World-space bounds of the posed meshes of one actor, or of all actors when
// actorId is empty (Frame Selection / Frame All). Skins on the CPU: call on
// demand, not every frame.
Bounds posedBounds(const SceneFrame& frame, const std::string& actorId = {});

}  // namespace animorph
