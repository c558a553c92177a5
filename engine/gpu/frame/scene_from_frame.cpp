#include "gpu/frame/scene_from_frame.h"

#include <algorithm>

namespace animorph::gpu {

void buildScene(const SceneFrame& frame, const ViewOptions& view, const std::string& selectedActorId,
                MeshCache& meshes, Scene& out, const BlobPreviewSet* blobs, int selectedBlobNode,
                StandinBindingCache* bindings) {
  out.meshes.clear();
  out.transitionMeshes.clear();
  out.weightOverlays.clear();
  out.particles.clear();
  out.lines.clear();
  out.overlay.clear();
  out.options.grid = view.showGrid;
  out.options.wireframe = view.wireframe;
  out.options.axisIndicator = view.showAxes;
  Bounds b;
  for (const auto& d : frame.meshes) {
    const GpuMesh* gm = meshes.get(d.character, d.meshIndex);
    if (!gm) continue;
    gpu::MeshDraw md;
    md.mesh = gm;
    md.model = d.model;
    md.jointMatrices = d.joints;
    md.morphWeights = d.morphWeights;
    md.selected = !selectedActorId.empty() && d.actorId == selectedActorId;
    md.opacity = d.opacity;
    md.complementDither = d.complementDither;
    if (d.color) md.color = glm::vec4(*d.color, 1.0f), md.materials = false;
    out.meshes.push_back(md);
    Bounds mb = gm->bounds();
    if (!mb.empty()) {
      b.add(glm::vec3(d.model * glm::vec4(mb.min, 1.0f)));
      b.add(glm::vec3(d.model * glm::vec4(mb.max, 1.0f)));
    }
  }
  for (const auto& t : frame.transitions) {
    const GpuMesh* gm = meshes.get(t.mesh.character, t.mesh.meshIndex);
    const GpuStandinBinding* gb = bindings ? bindings->get(t.runtime, t.targetActor) : nullptr;
    if (!gm || !gb || !t.frame) continue;
    gpu::TransitionMeshDraw td;
    td.draw.mesh = gm;
    td.draw.model = t.mesh.model;
    td.draw.jointMatrices = t.mesh.joints;
    td.draw.morphWeights = t.mesh.morphWeights;
    td.draw.selected = !selectedActorId.empty() && t.mesh.actorId == selectedActorId;
    td.draw.opacity = t.mesh.opacity;
    td.draw.complementDither = t.mesh.complementDither;
    td.binding = gb;
    td.firstVertex = static_cast<uint32_t>(t.firstVertex);
    td.frame = t.frame.get();
    out.transitionMeshes.push_back(td);
    Bounds mb = gm->bounds();  // bind pose, like the meshes': sizes the skeleton markers
    if (!mb.empty()) {
      b.add(glm::vec3(t.mesh.model * glm::vec4(mb.min, 1.0f)));
      b.add(glm::vec3(t.mesh.model * glm::vec4(mb.max, 1.0f)));
    }
  }
  out.generatedMeshes.clear();
  for (const auto& d : frame.blobs) {
    if (!blobs) continue;
    // A ghost is dithered at its opacity, in its tint (the GPU preview draws a generated mesh, the CPU one a mesh).
    const size_t firstMesh = out.meshes.size(), firstGenerated = out.generatedMeshes.size();
    const bool ghost = d.opacity < 1.0f;
    blobs->draw(d.key(), out, d.model, d.tint ? glm::vec4(*d.tint, 1.0f) : kBlobSurfaceColor,
                !ghost && !selectedActorId.empty() && d.actorId == selectedActorId);
    for (size_t i = firstMesh; ghost && i < out.meshes.size(); ++i) out.meshes[i].opacity = d.opacity;
    // The surface in its vertex colours (the primitives' colours; ImplicitPreview::draw), a tinted one in its tint.
    for (size_t i = firstMesh; d.tint && i < out.meshes.size(); ++i) out.meshes[i].materials = false;
    for (size_t i = firstGenerated; ghost && i < out.generatedMeshes.size(); ++i) out.generatedMeshes[i].opacity = d.opacity;
  }
  // The skeleton's drawings are built only when it is shown (scene_frame.h, LazyBlobGuides).
  if (view.showSkeleton)
    for (const auto& g : frame.blobGuides.get())
      for (const auto& m : g.markers) b.add(m.position);
  if (view.showSkeleton && !frame.blobGuides.empty()) {
    float radius = std::max(0.006f, 0.006f * b.diagonal());
    const uint32_t guide = packRgba({0.45f, 0.95f, 0.55f, 1.0f});
    const uint32_t guideActor = packRgba({0.7f, 1.0f, 0.75f, 1.0f});
    const uint32_t guideSel = packRgba({1.0f, 0.7f, 0.25f, 1.0f});
    const uint32_t axisColor[3] = {packRgba({0.95f, 0.3f, 0.3f, 1.0f}), packRgba({0.4f, 0.9f, 0.3f, 1.0f}),
                                   packRgba({0.35f, 0.55f, 1.0f, 1.0f})};
    for (const auto& g : frame.blobGuides.get()) {
      bool actorSel = g.actorId == selectedActorId;
      auto color = [&](int node) {
        return actorSel && node == selectedBlobNode ? guideSel : actorSel ? guideActor : guide;
      };
      for (const auto& l : g.lines) out.overlay.line(l.a, l.b, color(l.node));
      for (const auto& m : g.markers) out.overlay.octahedron(m.position, radius, color(m.node));
      for (const auto& a : g.axes) {
        bool sel = actorSel && a.node == selectedBlobNode;
        for (int k = 0; k < 3; ++k) out.overlay.line(a.origin, a.tips[k], sel ? guideSel : axisColor[k]);
      }
    }
  }
  if (view.showSkeleton && !frame.bones.empty()) {
    // Joint markers sized to the scene, bones in a light blue, the selected actor's in orange.
    float radius = std::max(0.004f, 0.006f * b.diagonal());
    const uint32_t bone = packRgba({0.55f, 0.8f, 1.0f, 1.0f});
    const uint32_t boneSel = packRgba({1.0f, 0.7f, 0.25f, 1.0f});
    for (const auto& bd : frame.bones) {
      uint32_t c = bd.actorId == selectedActorId ? boneSel : bone;
      out.overlay.line(bd.head, bd.tail, c);
      out.overlay.octahedron(bd.head, radius, c);
      out.overlay.octahedron(bd.tail, radius, c);
    }
  }
}

void setCrossFade(Scene& scene, size_t firstMesh, size_t firstGenerated, float opacity) {
  if (!(opacity < 1.0f)) return;
  for (size_t i = firstMesh; i < scene.meshes.size(); ++i) {
    scene.meshes[i].opacity = opacity;
    scene.meshes[i].complementDither = true;
  }
  for (size_t i = firstGenerated; i < scene.generatedMeshes.size(); ++i) {
    scene.generatedMeshes[i].opacity = opacity;
    scene.generatedMeshes[i].complementDither = true;
  }
}

void addBlobHighlight(const BlobGuides& guides, Scene& out) {
  Bounds b;
  for (const auto& m : guides.markers) b.add(m.position);
  for (const auto& l : guides.lines) b.add(l.a), b.add(l.b);
  const float radius = std::max(0.01f, 0.03f * (b.empty() ? 0.0f : b.diagonal()));
  const size_t n = guides.markers.size() + guides.lines.size() + guides.axes.size();
  // A few guides (a primitive, a chain) solid; a big sub-tree's guides, drawn over each other,
  // would paint it flat: a sample of them, faint, under the sub-tree's outline box.
  const size_t stride = highlightGuideStride(n);
  const float alpha = highlightGuideAlpha(n);
  const uint32_t color = packRgba({kHighlightColor.r, kHighlightColor.g, kHighlightColor.b, alpha});
  if (alpha < 1.0f) out.overlay.box(b, packRgba(kHighlightColor));
  for (size_t i = 0; i < guides.lines.size(); i += stride) out.overlay.line(guides.lines[i].a, guides.lines[i].b, color);
  for (size_t i = 0; i < guides.markers.size(); i += stride)
    out.overlay.octahedron(guides.markers[i].position, radius, color);
  for (size_t i = 0; i < guides.axes.size(); i += stride)
    for (int k = 0; k < 3; ++k) out.overlay.line(guides.axes[i].origin, guides.axes[i].tips[k], color);
}

size_t highlightGuideStride(size_t guides) {
  return std::max<size_t>(1, (guides + kMaxHighlightGuides - 1) / kMaxHighlightGuides);
}

float highlightGuideAlpha(size_t guides) {
  const size_t drawn = (guides + highlightGuideStride(guides) - 1) / highlightGuideStride(guides);
  return std::clamp(kSolidHighlightGuides / float(std::max<size_t>(drawn, 1)), kMinHighlightAlpha, 1.0f);
}

}  // namespace animorph::gpu
