#pragma once
// Weight-map painting (docs/design.md §4: the map m_i shifts each vertex's start
// within a transition). A brush is a circle on the screen, its radius in
// pixels; a dab changes the weights of the vertices of a PaintMesh that
// project inside it and that the camera sees (front-facing, not behind
// another part of the mesh). A stroke is a sequence of dabs spaced along the
// cursor's path. Pure math on the CPU, no GPU and no UI.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/paint/paint_mesh.h"
#include "core/camera/camera.h"

namespace animorph {

enum class BrushFalloff { Smooth, Linear, Constant };
enum class BrushMode { Add, Subtract, Smooth, Fill };

const char* brushFalloffName(BrushFalloff f);  // "smooth", "linear", "constant"
const char* brushModeName(BrushMode m);        // "add", "subtract", "smooth", "fill"

struct BrushSettings {
  float radiusPx = 40.0f;   // on screen; vertices farther from the cursor are untouched
  float strength = 0.5f;    // per dab, 0..1 (Fill: the value the whole map is set to)
  BrushFalloff falloff = BrushFalloff::Smooth;
  BrushMode mode = BrushMode::Add;
  bool mirrorX = false;     // also paint the vertex mirrored across the actor's local X = 0
  float spacing = 0.25f;    // distance between dabs as a fraction of the radius (> 0)
};

// The camera a brush sees through: the viewport's camera and size in pixels.
struct BrushView {
  OrbitCamera camera;
  glm::vec2 viewportPx{1.0f};
};

// Falloff at distance t (0 centre .. 1 rim) from the cursor; 0 outside.
float brushFalloff(BrushFalloff f, float t);

struct BrushHit {
  uint32_t vertex = 0;
  float influence = 0.0f;  // falloff, 0..1
};

// Vertices of mesh inside a brush of radiusPx at cursorPx (viewport pixels),
// facing the camera and not hidden by the mesh itself (a depth buffer of the
// mesh's front faces, counter-clockwise as in glTF, rasterised over the
// brush's square). Sorted by vertex.
std::vector<BrushHit> verticesUnderBrush(const PaintMesh& mesh, const BrushView& view, glm::vec2 cursorPx,
                                         float radiusPx, BrushFalloff falloff);

// Applies one dab of hits to weights (one entry per mesh vertex; clamped to
// [0, 1]). Add / Subtract move by strength * influence; Smooth moves each hit
// vertex towards the mean of its neighbours by strength * influence; Fill sets
// every weight to strength. mirror (from mirrorVertexMap, may be empty) also
// applies each hit to its mirrored vertex.
void applyDab(std::vector<float>& weights, const std::vector<BrushHit>& hits, const BrushSettings& s,
              const std::vector<std::vector<uint32_t>>& neighbours, const std::vector<int32_t>& mirror);

// A stroke from mouse down to mouse up on one mesh: turns cursor positions
// into dabs spaced by settings.spacing * radius and paints them on a working
// copy of the weight map (created as zeros when the actor has none).
class WeightStroke {
 public:
  WeightStroke(PaintMesh mesh, std::vector<float> startWeights, BrushSettings settings, BrushView view);
  // Moves the brush to cursorPx; the first call dabs there, later calls dab
  // along the segment from the last dab. Returns the number of dabs made.
  int moveTo(glm::vec2 cursorPx);
  const std::vector<float>& weights() const { return weights_; }
  const PaintMesh& mesh() const { return mesh_; }
  int dabCount() const { return dabs_; }
  size_t verticesTouched() const;  // vertices whose weight changed since the start

 private:
  void dab(glm::vec2 p);
  PaintMesh mesh_;
  std::vector<float> start_, weights_;
  BrushSettings settings_;
  BrushView view_;
  std::vector<std::vector<uint32_t>> neighbours_;
  std::vector<int32_t> mirror_;
  bool started_ = false;
  glm::vec2 last_{0.0f};
  int dabs_ = 0;
};

}  // namespace animorph
