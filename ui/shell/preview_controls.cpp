#include "ui/shell/preview_controls.h"

#include <imgui.h>

#include <cstdio>
#include <string>

#include "ui/widgets/widget_rects.h"

namespace animorph {

bool drawPreviewSettings(Preferences& prefs) {
  bool changed = false;
  const PreviewDevice devices[] = {PreviewDevice::Auto, PreviewDevice::Gpu, PreviewDevice::Cpu};
  const char* labels[] = {"Auto", "GPU", "CPU"};
  const char* tips[] = {
      "The GPU. On a CPU Vulkan device (lavapipe) the CPU worker, which is faster there, except for morphs of "
      "convolution stand-ins (the status bar says which and why)",
      "Vulkan compute polygonisation; falls back to the CPU worker with a message if the GPU cannot take a shape",
      "The CPU worker thread, refining when the shape stops changing"};
  ImGui::TextUnformatted("Device");
  for (int i = 0; i < 3; ++i) {
    ImGui::SameLine();
    if (ImGui::RadioButton(labels[i], prefs.previewDevice == devices[i])) {
      prefs.previewDevice = devices[i];
      changed = true;
    }
    noteWidget(std::string("preview/device_") + previewDeviceName(devices[i]));
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tips[i]);
  }
  const ImGuiSliderFlags clamp = ImGuiSliderFlags_AlwaysClamp;
  ImGui::SetNextItemWidth(260.0f);
  ImGui::SliderInt("While scrubbing", &prefs.previewCoarseResolution, kMinPreviewResolution, kMaxPreviewResolution,
                   "%d^3", clamp);
  changed |= ImGui::IsItemDeactivatedAfterEdit();
  noteWidget("preview/interactive");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Cells along the longest side while the time or the shape changes");
  ImGui::SetNextItemWidth(260.0f);
  ImGui::SliderInt("Refined", &prefs.previewResolution, kMinPreviewResolution, kMaxPreviewResolution, "%d^3", clamp);
  changed |= ImGui::IsItemDeactivatedAfterEdit();
  noteWidget("preview/refined");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Cells along the longest side once scrubbing stops");
  changed |= ImGui::Checkbox("Particles as spheres while scrubbing", &prefs.particleView);
  noteWidget("preview/particle_view");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("BlobTrees made of particles show each particle while the time changes; the surface once it stops");
  return changed;
}

bool drawPreviewQuickControl(Preferences& prefs, bool& hovered) {
  char label[64];
  std::snprintf(label, sizeof label, "preview %d/%d %s###preview_button", prefs.previewCoarseResolution,
                prefs.previewResolution, previewDeviceName(prefs.previewDevice));
  if (ImGui::SmallButton(label)) ImGui::OpenPopup("##preview_popup");
  noteWidget("viewport/preview_button");
  hovered = ImGui::IsItemHovered() || ImGui::IsItemActive();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Implicit preview: device and resolutions");
  bool changed = false;
  if (ImGui::BeginPopup("##preview_popup")) {
    ImGui::TextUnformatted("Implicit preview (BlobTrees, morph B-C)");
    changed = drawPreviewSettings(prefs);
    hovered = true;
    ImGui::EndPopup();
  }
  return changed;
}

}  // namespace animorph
