#pragma once
// Clicking what the morph shows: the collapsing or expanding mesh (drawn by a
// vertex shader, so it is not in the scene's CPU meshes) and the implicit
// stage's surface select the actor they come from.
#include <optional>

#include "core/scene/morph_runtime.h"
#include "core/poly/mesh.h"
#include "editor/pick.h"
#include "core/camera/camera.h"

namespace animorph {

// The nearest hit of ray on the morph's own surface at timeSec, or nothing
// before A and after D (the actors are drawn as themselves then). The
// transitions are evaluated on the CPU for the click; the implicit stage uses
// implicitMesh (the preview's world-space mesh) when given and non-empty, else
// it is polygonised at fallbackResolution.
std::optional<ScenePick> pickMorphSurface(const MorphRuntime& rt, double timeSec, const Ray& ray,
                                          const TriangleMesh* implicitMesh, int fallbackResolution = 48);

}  // namespace animorph
