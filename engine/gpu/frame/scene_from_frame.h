#pragma once
// Turns an evaluated SceneFrame (engine/core/scene) into the renderer's Scene:
// GPU meshes with their joint matrices, the skeleton overlay, view options.
#include <string>

#include "gpu/polygonizer/blob_preview_set.h"
#include "core/project/project.h"
#include "gpu/render/mesh_cache.h"
#include "core/scene/scene_frame.h"
#include "gpu/render/scene_renderer.h"
#include "gpu/render/standin_binding_cache.h"

namespace animorph::gpu {

// The colour BlobTree surfaces (and their particle view) are drawn in: a cool clay tone (sRGB).
inline const glm::vec4 kBlobSurfaceColor{0.55f, 0.68f, 0.82f, 1.0f};

// Fills out from frame (out keeps pointers into frame: frame must outlive the
// recording). selectedActorId is highlighted. Meshes whose upload failed are
// skipped (meshes.lastError()). BlobTree actors are drawn from blobs' newest
// preview meshes (double-sided) when blobs is given; their skeleton guides
// join the overlay, selectedBlobNode's (a node id of the selected actor) highlighted.
// Transition draws (collapse, expansion) need bindings for their stand-in
// bindings; without it they are skipped.
// Cross-fade of the implicit stage drawn by a preview: the meshes from
// scene.meshes[firstMesh] and scene.generatedMeshes[firstGenerated] on get
// opacity (dithered with the complementary pattern of the transition's mesh)
// when it is below 1.
void setCrossFade(Scene& scene, size_t firstMesh, size_t firstGenerated, float opacity);

// Draws guides (e.g. the sub-tree of a node hovered in the correspondence
// editor, scene/blob_guides.h subtreeGuides, or a skeleton chain hovered in the
// morph's Chain matching) in the highlight colour over
// everything else in the overlay, whether the skeleton is shown or not. Up to
// kSolidHighlightGuides guides are drawn solid; more are drawn translucent
// (highlightGuideAlpha), at most about kMaxHighlightGuides of them (every
// highlightGuideStride-th of each kind), under the solid outline of their
// bounding box, so a big sub-tree is tinted rather than painted over and its
// shape stays readable.
void addBlobHighlight(const BlobGuides& guides, Scene& out);

inline constexpr glm::vec4 kHighlightColor{1.0f, 0.35f, 0.85f, 1.0f};
inline constexpr float kSolidHighlightGuides = 24.0f;
inline constexpr size_t kMaxHighlightGuides = 160;
inline constexpr float kMinHighlightAlpha = 0.15f;
// Every how many guides of `guides` one is drawn: 1 up to kMaxHighlightGuides.
size_t highlightGuideStride(size_t guides);
// The alpha of each drawn guide: 1 up to kSolidHighlightGuides drawn, then
// kSolidHighlightGuides / drawn, never below kMinHighlightAlpha.
float highlightGuideAlpha(size_t guides);

void buildScene(const SceneFrame& frame, const ViewOptions& view, const std::string& selectedActorId,
                MeshCache& meshes, Scene& out, const BlobPreviewSet* blobs = nullptr, int selectedBlobNode = -1,
                StandinBindingCache* bindings = nullptr);

}  // namespace animorph::gpu
