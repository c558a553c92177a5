#pragma once
// Evaluating a project's morph at any time (docs/design.md §5): before A the source
// plays (skinned mesh); A->B its collapse onto its stand-in; B->C the implicit
// morph, polygonised; C->D the target's expansion; after D the target plays.
// prepareMorph does the costly part once (loading, binding vertices to the
// stand-ins); evaluateMorphFrame is then a pure function of the time, cheap
// enough per frame at a coarse resolution (the editor keeps one MorphRuntime
// per document revision and calls it every frame).
#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/project/asset_cache.h"
#include "core/project/project.h"
#include "core/standin_morph/skeleton_correspondence.h"
#include "core/standin_morph/transition.h"
#include "core/poly/mesh.h"
#include "core/poly/polygonizer.h"
#include "core/util/result.h"

namespace animorph {

enum class MorphStage { Source, Collapse, Morph, Expand, Target };
const char* morphStageName(MorphStage s);  // "source", "collapse", "morph", "expand", "target"

// One side of the morph: a skinned (or rigid) glTF character bound to its
// stand-in, or a BlobTree actor (tree set; no character, binding or
// transitions: its own tree plays the stand-in's role).
struct MorphActorRuntime {
  Actor actor;
  std::shared_ptr<const BlobTree> tree;  // a BlobTree actor's tree (character null)
  bool isTree() const { return tree != nullptr; }
  std::shared_ptr<const Character> character;
  const AnimationClip* clip = nullptr;  // null: no animation (static rest pose)
  ActorMorph morph;                     // stand-in, weight map, segment tracks
  StandinBinding binding;
  bool bindingKept = false;  // binding taken from the previous revision's runtime (prepareMorph)
  size_t vertexCount = 0;
};

struct MorphRuntime {
  // The project's setup, with A moved onto B when the source is a BlobTree and
  // D onto C when the target is one (no collapse / expansion on that side).
  MorphSetup setup;
  Timeline timeline;
  MorphActorRuntime source, target;
  // Method SkeletonCorrespondence with a stand-in on both sides: the chain
  // matching B->C follows (null: the plain method; notes say why).
  std::shared_ptr<const SkeletonCorrespondence> correspondence;
  std::vector<std::string> notes;  // what the user should know ("gear.glb: no skin: rigid one-bone actor")
};

// Loads both actors' characters (through assets), checks the stand-ins against
// the rigs and the weight maps against the vertex counts, and binds every
// vertex to its stand-in. Errors name the project element and the reason.
// previous (an earlier revision's runtime, may be null): an actor whose character,
// clip, loop, stand-in and the projection settings are unchanged keeps its binding
// (the same result as binding again, without the cost).
Result<std::shared_ptr<const MorphRuntime>> prepareMorph(const Project& project, const std::string& baseDir,
                                                         AssetCache& assets, const MorphRuntime* previous = nullptr);

// The skeleton correspondence between two prepared actors' stand-ins, with
// the artist's chain pairs (MorphSetup::chainPairs) applied. Errors: a side is
// a BlobTree actor (no rig), or has no chain. Pairs that name no chain are
// warnings of the result (prepareMorph adds them to the notes).
Result<SkeletonCorrespondence> morphSkeletonCorrespondence(const MorphActorRuntime& source,
                                                           const MorphActorRuntime& target,
                                                           const std::vector<ChainPair>& pairs = {});

struct MorphFrameSettings {
  int resolution = 48;     // B->C: polygonisation cells along the longest side of the morph's bounds
  int threads = 0;         // 0: all hardware threads
  bool reproject = true;   // pull vertices onto the posed stand-in near alpha = 1
  const std::atomic<bool>* cancel = nullptr;  // polygonisation stops early; the frame comes back empty
  // applyMorph (scene/morph_scene.h) only: collapse and expansion become
  // TransitionDraws deformed in the vertex shader instead of CPU meshes.
  bool gpuTransitions = false;
  // Collapse and expansion frames carry the stand-in core (scene/standin_core.h)
  // as a second shell of their mesh. false: the transitioned mesh alone.
  bool standinCore = true;
  // Vertex colours (TriangleMesh::colors) of the implicit stage and the stand-in core where a side
  // has colours (MorphImplicitField::colorProgram); false: none (the transitions' colours come with
  // their mesh either way).
  bool colors = true;
};

struct MorphFrame {
  double timeSec = 0.0;
  MorphStage stage = MorphStage::Source;
  double progress = 0.0;  // u in [0, 1] within the stage (0 outside the transitions and the morph)
  float blend = 0.0f;     // w(u) during the morph
  std::string actorId;    // whose mesh this is (empty during the morph)
  TriangleMesh mesh;      // world space, unit normals, counter-clockwise outside
  // Collapse / expansion: the last coreTriangles triangles of mesh are the
  // stand-in core, a closed shell overlapping the transitioned mesh (its volume
  // is the union's: poly/union_volume.h). 0: none.
  size_t coreTriangles = 0;
  PolygonizeStats polygonize;   // B->C, and the stand-in core
  TransitionStats transition;   // A->B and C->D only
  bool cancelled = false;
};

// The stage and its progress u at timeSec.
MorphStage morphStageAt(const MorphSetup& setup, const Timeline& tl, double timeSec, double& progress);

// The B->C field at timeSec as one program (for any polygoniser: the CPU's,
// the GPU's): the morph of the posed stand-ins at the blend w(u), the grid
// bounds it needs (set for space-time blending, whose field is unbounded; with
// a margin of two cells of resolution), and the solid-noise amplitude the
// polygonised mesh is displaced by afterwards (0: none).
struct MorphImplicitField {
  double progress = 0.0;  // u within the stage
  float blend = 0.0f;     // w(u)
  FieldProgram program;
  std::optional<Bounds> bounds;
  float noiseAmplitude = 0.0f;
  // The program of the surface's colours (PolygonizeSettings::colorProgram: the same field, the
  // stand-ins' segments split into their colour samples); null when neither side has colours
  // (characters without colours of their own: the surface has none either).
  std::shared_ptr<const FieldProgram> colorProgram;
};
// progress >= 0 overrides the stage's u (the cross-fade shows the surface
// just before B at u = 0 and just after C at u = 1).
MorphImplicitField morphImplicitField(const MorphRuntime& rt, double timeSec, int resolution, double progress = -1.0);

// The implicit field the frame at timeSec is polygonised from, as evaluateMorphFrame uses it: the
// B->C stage's, and a BlobTree side's before A / after D (its tree: the morph at u = 0 / 1).
// nullopt for a frame that is a skinned mesh (the source or target playing, the collapse, the
// expansion): no field.
std::optional<MorphImplicitField> morphFrameField(const MorphRuntime& rt, double timeSec, int resolution);

// The output of the morph at timeSec. Errors: polygonisation failed (bad resolution).
Result<MorphFrame> evaluateMorphFrame(const MorphRuntime& rt, double timeSec, const MorphFrameSettings& settings);

// The collapse (expand false: the source, alpha rising) or the expansion
// (expand true: the target, alpha falling) at scene time timeSec and stage
// progress u (clamped), computed on the CPU, whatever stage timeSec is in: the
// transitioned mesh alone (evaluateMorphFrame adds the stand-in core).
MorphFrame evaluateMorphTransition(const MorphRuntime& rt, double timeSec, bool expand, double u,
                                   const MorphFrameSettings& settings);

// The implicit morph (B -> C) polygonised at scene time timeSec and morph
// progress u (clamped to [0, 1]), whatever stage timeSec is in: the
// cross-fade draws the surface just before B (u = 0) and just after C (u = 1).
// Errors: polygonisation failed.
Result<MorphFrame> evaluateMorphImplicit(const MorphRuntime& rt, double timeSec, double u,
                                         const MorphFrameSettings& settings);

// Seam between a transition and the polygonised morph: the transition's
// vertices at alpha = 1 at marker B (atB) or C, against the surface
// polygonised there at resolution. Distances in metres, and the grid cell.
struct SeamGap {
  double maxDistance = 0.0;
  double meanDistance = 0.0;
  float cellSize = 0.0f;
};
Result<SeamGap> measureSeamGap(const MorphRuntime& rt, bool atB, int resolution);

// Whether the morph's implicit surfaces have colours: a side is a BlobTree (its primitives' colours)
// or a character with colours of its own (its stand-in's, StandinBinding::segmentColors).
bool morphHasColors(const MorphRuntime& rt);

// The posed stand-in of a runtime actor at scene time timeSec (world space),
// with its segment tracks applied at morph progress u (negative: none), its
// segments carrying their colours (StandinBinding::segmentColors).
MorphOperand posedOperand(const MorphActorRuntime& a, double timeSec, double u);

}  // namespace animorph
