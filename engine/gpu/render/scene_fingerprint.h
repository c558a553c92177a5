#pragma once
// What a viewport frame would draw, reduced to 64 bits: the kept viewport image
// (present/viewport_image.h) is drawn again only when the fingerprint changes. Covers every field
// SceneRenderer::record reads (meshes by their content serial, poses, weights, colours, lines,
// particles, options), the camera and the rectangle's size.
#include <cstdint>
#include <optional>

#include "core/camera/camera.h"
#include "gpu/render/scene_renderer.h"

namespace animorph::gpu {

// The fingerprint of scene seen through camera in a width x height rectangle; equal fingerprints
// draw the same pixels. nullopt when the scene holds draws whose content can change without any
// field here changing, which must be drawn every frame: GPU-generated meshes (their buffers are
// rewritten in place) and transitions (their frame's stand-in primitives).
std::optional<uint64_t> sceneFingerprint(const Scene& scene, const OrbitCamera& camera, uint32_t width,
                                         uint32_t height);

}  // namespace animorph::gpu
