#pragma once
// The particle view's drawing (core/scene/particle_draw.h; the editor's editor/particle_view.h says
// when; docs/particles.md): a ParticleDraw (centres and visible radii in its tree's space) as a
// ParticleSpheresDraw in the world, drawn by the scene renderer as instanced, ray-cast spheres with
// true depth, shaded like the surface they stand for.
#include "gpu/render/scene_renderer.h"
#include "core/scene/particle_draw.h"

namespace animorph::gpu {

// The spheres of draw in the world (centres through draw.model, radii by its scale, at least
// 1 mm), each in its own colour (draw.colors, sRGB) or, where draw has none, in color; selected
// adds the selection's rim as on meshes.
ParticleSpheresDraw particleSpheres(const ParticleDraw& draw, const glm::vec4& color, bool selected);

}  // namespace animorph::gpu
