// The correspondence editor's tab for a morph by skeleton correspondence: its chain matching
// (correspondence_editor_intern.h).
#include <imgui.h>

#include "ui/animorphosis/correspondence_editor_intern.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {

bool showsMorphChainTab(bool chains, bool graph) {
  bool chainTab = chains && !graph;
  if (chains && graph) {  // both: a tab each
    if (ImGui::BeginTabBar("##corr_tabs")) {
      if (ImGui::BeginTabItem("Animorphosis")) ImGui::EndTabItem();
      noteWidget("corr/tab/animorphosis");
      if (ImGui::BeginTabItem("Morph chains")) {
        chainTab = true;
        ImGui::EndTabItem();
      }
      noteWidget("corr/tab/chains");
      ImGui::EndTabBar();
    }
  }
  return chainTab;
}

void drawMorphChainTab(Document& doc, MorphPanelState& morph) {
  const MorphSetup& setup = doc.project().morph;
  ImGui::TextDisabled("Morph %s -> %s: skeleton correspondence by chains", setup.sourceActorId.c_str(),
                      setup.targetActorId.c_str());
  drawChainMatching(doc, morph, "corr/chains");
}

}  // namespace animorph
