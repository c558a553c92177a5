#pragma once
// Weight Paint mode: painting a morph actor's weight map in the viewport.
// Left drag paints (one undo step per stroke; the map updates live while the
// button is held), the brush circle follows the cursor, [ and ] shrink and
// grow it, F then a mouse move sets its radius (click or F confirms, Esc or
// right click cancels), camera navigation works as everywhere else (Alt or
// the middle button). A tool panel in the viewport's corner holds the brush
// settings, Fill, Clear and the import from vertex colours.
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/project/asset_cache.h"
#include "core/doc/document.h"
#include "ui/common/layout.h"
#include "core/paint/weight_brush.h"
#include "core/paint/weights_from_colors.h"
#include "core/paint/weights_from_texture.h"
#include "ui/common/status_bar.h"
#include "ui/viewport/viewport_input.h"

struct ImDrawList;

namespace animorph {

struct WeightPaintState {
  bool active = false;         // in Weight Paint mode
  bool overlayAlways = false;  // View > Weight Overlay: heat colours outside paint mode too
  BrushSettings brush;
  ColorChannel importChannel = ColorChannel::Red;
  TextureChannel importTextureChannel = TextureChannel::Alpha;
  bool openImportPopup = false;
  // The stroke in progress (mouse down .. up), painting a copy of the map.
  std::shared_ptr<WeightStroke> stroke;
  // F: radius set by the cursor's distance from where F was pressed.
  bool adjustingRadius = false;
  glm::vec2 adjustCentre{0.0f};
  float adjustStartRadius = 0.0f;
  glm::vec2 cursor{0.0f};
  bool cursorInViewport = false;
  // The posed mesh of the painted actor, kept while document, revision, frame and actor stay the same.
  std::shared_ptr<const PaintMesh> mesh;
  const Document* meshDoc = nullptr;
  uint64_t meshRevision = 0;
  int meshFrame = 0;
};

// The actor Weight Paint mode paints: the selection when it is the morph's
// source or target, else "".
std::string weightPaintActor(const Document& doc);

// Enters or leaves Weight Paint mode. Entering selects the morph's source when
// the selection is not a morph actor; without a morph it refuses (status says why).
void toggleWeightPaint(Document& doc, WeightPaintState& st, StatusMessage& status);

// The tool panel (brush settings, Fill, Clear, import) in the viewport's top
// left corner, and the import dialog. Draw only while st.active (the dialog also otherwise).
void drawWeightPaintPanel(const LayoutRect& viewport, Document& doc, AssetCache& assets, WeightPaintState& st,
                          StatusMessage& status);

// One frame of painting input in the viewport: strokes, radius keys, the
// brush circle (on draw). Returns true when it used the left button this
// frame (then the viewport must not turn that click into a pick).
bool updateWeightPaint(Document& doc, AssetCache& assets, const OrbitCamera& camera, const ViewportRect& viewport,
                       const PointerInput& in, WeightPaintState& st, StatusMessage& status, ImDrawList* draw);

// Replaces actorId's weight map with one read from the vertex colours of its
// glTF (channel). One undo step; errors go to status.
bool importWeightsFromColors(Document& doc, AssetCache& assets, const std::string& actorId, ColorChannel channel,
                             StatusMessage& status);

// Replaces actorId's weight map with one channel of its base colour texture sampled at
// each vertex's texture coordinates. One undo step; errors go to status.
bool importWeightsFromTexture(Document& doc, AssetCache& assets, const std::string& actorId, TextureChannel channel,
                              StatusMessage& status);

// What the viewport should show in heat colours: the painted actor's map (the
// stroke's live copy during a stroke) in paint mode or with overlayAlways;
// actorId empty when nothing. weights may be shorter than the mesh (padded with 0).
struct WeightOverlayRequest {
  std::string actorId;
  std::vector<float> weights;
};
WeightOverlayRequest weightOverlayRequest(const Document& doc, const WeightPaintState& st);

// "weight paint: creature, add, r 40 px" for the viewport's note line ("" outside the mode).
std::string weightPaintNote(const Document& doc, const WeightPaintState& st);

}  // namespace animorph
