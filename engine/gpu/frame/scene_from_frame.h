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
// everything else in the overlay, whether the skeleton is shown or not.
void addBlobHighlight(const BlobGuides& guides, Scene& out);

void buildScene(const SceneFrame& frame, const ViewOptions& view, const std::string& selectedActorId,
                MeshCache& meshes, Scene& out, const BlobPreviewSet* blobs = nullptr, int selectedBlobNode = -1,
                StandinBindingCache* bindings = nullptr);

}  // namespace animorph::gpu
