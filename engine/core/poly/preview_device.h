#pragma once
// Where the implicit previews (BlobTree actors, the morph's B->C stage) are
// polygonised, and the limits of their resolutions. A user preference
// (ui/common/prefs.h) read by the preview (engine/gpu/polygonizer/implicit_preview.h).
#include <cstddef>

namespace animorph {

// Auto: the GPU on discrete/integrated/virtual GPUs, the CPU worker on a CPU
// Vulkan device (lavapipe), where the worker is faster.
enum class PreviewDevice { Auto, Gpu, Cpu };

// "auto", "gpu", "cpu".
inline const char* previewDeviceName(PreviewDevice d) {
  switch (d) {
    case PreviewDevice::Gpu: return "gpu";
    case PreviewDevice::Cpu: return "cpu";
    case PreviewDevice::Auto: break;
  }
  return "auto";
}

// Limits of the preview resolutions (cells along the longest side).
inline constexpr int kMinPreviewResolution = 32;
inline constexpr int kMaxPreviewResolution = 256;

}  // namespace animorph
