#pragma once
// Turns one actor's meshes of a built Scene into weight-map overlays: the
// actor is drawn in heat colours of its weight map instead of shaded.
#include <string>
#include <vector>

#include "gpu/render/mesh_cache.h"
#include "core/scene/scene_frame.h"
#include "gpu/render/scene_renderer.h"

namespace animorph::gpu {

// Replaces the shaded draws of actorId's meshes in scene (built by buildScene
// from frame) by WeightOverlayDraws over weights, the actor's weight map
// (one entry per vertex over Character::meshNodes()). weights is padded with
// zeros (or cut) to the actor's vertex count, and the draws point into it:
// keep it alive and unchanged until the scene is recorded. Returns the number
// of overlay draws added.
size_t addWeightOverlay(const SceneFrame& frame, const std::string& actorId, std::vector<float>& weights,
                        MeshCache& meshes, Scene& scene);

}  // namespace animorph::gpu
