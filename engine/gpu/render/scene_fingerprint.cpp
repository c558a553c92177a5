#include "gpu/render/scene_fingerprint.h"

#include <cstring>
#include <span>
#include <type_traits>

#include "gpu/render/gpu_mesh.h"

namespace animorph::gpu {
namespace {

// FNV-1a over bytes, 8 at a time where it can (a few hundred kilobytes a frame at most).
class Hasher {
 public:
  void bytes(const void* data, size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    size_t i = 0;
    for (; i + 8 <= n; i += 8) {
      uint64_t w;
      std::memcpy(&w, p + i, 8);
      h_ = (h_ ^ w) * 0x100000001b3ull;
      h_ ^= h_ >> 29;
    }
    for (; i < n; ++i) h_ = (h_ ^ p[i]) * 0x100000001b3ull;
  }
  template <class T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T> && std::has_unique_object_representations_v<T>);
    bytes(&v, sizeof v);
  }
  void f(float v) { bytes(&v, sizeof v); }
  void vec(const glm::vec3& v) { bytes(&v, sizeof v); }
  void vec(const glm::vec4& v) { bytes(&v, sizeof v); }
  void mat(const glm::mat4& m) { bytes(&m, sizeof m); }
  template <class T>
  void span(std::span<const T> s) {
    value(s.size());
    bytes(s.data(), s.size_bytes());
  }
  uint64_t result() const { return h_; }

 private:
  uint64_t h_ = 0xcbf29ce484222325ull;
};

void meshDraw(Hasher& h, const MeshDraw& d) {
  h.value(d.mesh ? d.mesh->contentSerial() : uint64_t(0));
  h.mat(d.model);
  h.span(d.jointMatrices);
  h.span(d.morphWeights);
  h.vec(d.color);
  h.f(d.opacity);
  const uint32_t flags = uint32_t(d.materials) | uint32_t(d.selected) << 1 | uint32_t(d.doubleSided) << 2 |
                         uint32_t(d.complementDither) << 3;
  h.value(flags);
}

void options(Hasher& h, const SceneOptions& o) {
  h.vec(o.background);
  h.value(uint32_t(o.grid) | uint32_t(o.wireframe) << 1 | uint32_t(o.axisIndicator) << 2);
  h.f(o.gridCellM);
  h.vec(o.wireColor);
  h.vec(o.selectColor);
  h.value(o.axisIndicatorPx);
}

}  // namespace

std::optional<uint64_t> sceneFingerprint(const Scene& scene, const OrbitCamera& camera, uint32_t width,
                                         uint32_t height) {
  if (!scene.generatedMeshes.empty() || !scene.transitionMeshes.empty()) return std::nullopt;
  Hasher h;
  h.value(width);
  h.value(height);
  h.vec(camera.target);
  h.f(camera.yawRad);
  h.f(camera.pitchRad);
  h.f(camera.distanceM);
  h.f(camera.fovYRad);
  options(h, scene.options);
  h.value(scene.meshes.size());
  for (const MeshDraw& d : scene.meshes) meshDraw(h, d);
  h.value(scene.weightOverlays.size());
  for (const WeightOverlayDraw& w : scene.weightOverlays) {
    h.value(w.mesh ? w.mesh->contentSerial() : uint64_t(0));
    h.mat(w.model);
    h.span(w.jointMatrices);
    h.span(w.weights);
    h.span(w.morphWeights);
  }
  h.value(scene.particles.size());
  for (const ParticleSpheresDraw& p : scene.particles) {
    h.span(std::span<const glm::vec4>(p.spheres));
    h.span(std::span<const uint32_t>(p.colors));
    h.vec(p.color);
    h.value(uint32_t(p.selected));
  }
  for (const LineBatch* lines : {&scene.lines, &scene.overlay}) {
    h.value(lines->vertices().size());
    for (const LineVertex& v : lines->vertices()) {
      h.vec(v.position);
      h.value(v.rgba);
    }
  }
  return h.result();
}

}  // namespace animorph::gpu
