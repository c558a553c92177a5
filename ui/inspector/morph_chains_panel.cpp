// The morph panel's chain matching (morph_sections.h): the skeleton correspondence of the
// prepared morph, the two rigs' chains side by side with their pairing.
#include <imgui.h>

#include "inspector/morph_sections.h"
#include "morph/chain_matching.h"
#include "widgets/widget_rects.h"

namespace animorph {

void drawMorphChains(const MorphPanelState& st) {
  const bool open = ImGui::CollapsingHeader("Chain matching");
  noteWidget("morph/chains");
  if (!open) return;
  const SkeletonCorrespondence* c = st.runtime ? st.runtime->correspondence.get() : nullptr;
  if (!c) {
    ImGui::TextDisabled(st.runtime ? "No skeleton correspondence (see the projection report's notes)."
                                   : "Preparing the morph...");
    return;
  }
  ImGui::TextDisabled("Automatic pairing of the rigs' chains");
  // One table per side; each partner cell is noted as morph/chains/ROLE/INDEX.
  const auto side = [](const std::string& id, const SkeletonChains& own, const SkeletonChains& other,
                       const std::vector<int>& match, const char* verb, const char* tableId, const char* role) {
    if (!ImGui::BeginTable(tableId, 2, ImGuiTableFlags_BordersInnerH | ImGuiTableFlags_SizingStretchProp)) return;
    ImGui::TableSetupColumn(id.c_str());
    ImGui::TableSetupColumn("partner");
    ImGui::TableHeadersRow();
    for (size_t i = 0; i < own.chains.size(); ++i) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::Text("%s%s", own.chains[i].name.c_str(), int(i) == own.mainRoot ? " (root)" : "");
      ImGui::TableNextColumn();
      const std::string text = chainPartnerText(own, other, match, int(i), verb);
      if (match[i] >= 0) ImGui::TextUnformatted(text.c_str());
      else ImGui::TextDisabled("%s", text.c_str());
      noteWidget(std::string("morph/chains/") + role + "/" + std::to_string(i));
    }
    ImGui::EndTable();
  };
  side(st.runtime->setup.sourceActorId, c->source, c->target, c->sourceMatch, "shrinks into", "##sourceChains", "source");
  side(st.runtime->setup.targetActorId, c->target, c->source, c->targetMatch, "grows from", "##targetChains", "target");
}

}  // namespace animorph
