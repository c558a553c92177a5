// The morph panel's chain matching (morph_sections.h): the skeleton correspondence of the
// prepared morph, the two rigs' chains side by side with their pairing; per source chain
// a combo re-pairs it by hand (an artist pair, saved in the morph and undoable).
#include <imgui.h>

#include <algorithm>

#include "core/doc/chain_pair_commands.h"
#include "ui/inspector/morph_sections.h"
#include "core/standin_morph/chain_matching.h"
#include "ui/widgets/widget_rects.h"

namespace animorph {
namespace {

const ImVec4 kArtistColour{1.0f, 0.72f, 0.25f, 1.0f};  // rows the artist paired by hand

void execute(Document& doc, std::unique_ptr<Command> cmd) {
  if (cmd) doc.execute(std::move(cmd));
}

// The partner combo of source chain i: "automatic (X)", "unmatched", then every target chain.
// pair: the document's artist pair for the chain (null: automatic).
void partnerCombo(Document& doc, const SkeletonCorrespondence& c, size_t i, const ChainPair* pair,
                  const std::string& keys) {
  const SkeletonChains& target = c.target;
  const int automatic = c.automatic[i];
  const std::string autoPick = automatic >= 0 ? target.chains[size_t(automatic)].name : std::string("unmatched");
  const std::string autoText = "automatic (" + autoPick + ")";
  // The closed combo says "auto (X)": the inspector is narrow.
  const std::string preview = !pair ? "auto (" + autoPick + ")" : pair->target ? *pair->target : std::string("unmatched");
  const std::string& name = c.source.chains[i].name;
  ImGui::SetNextItemWidth(-1.0f);
  if (pair) ImGui::PushStyleColor(ImGuiCol_Text, kArtistColour);
  const bool open = ImGui::BeginCombo(("##partner" + std::to_string(i)).c_str(), preview.c_str());
  if (pair) ImGui::PopStyleColor();
  noteWidget(keys + "/source/" + std::to_string(i));
  if (ImGui::IsItemHovered() && !open)
    ImGui::SetTooltip("%s %s", name.c_str(), chainPartnerText(c.source, target, c.sourceMatch, int(i), "shrinks into").c_str());
  if (!open) return;
  if (ImGui::Selectable(autoText.c_str(), !pair)) execute(doc, resetChainPairCommand(doc.project(), name));
  noteWidget(keys + "/option/0");
  if (ImGui::Selectable("unmatched", pair && !pair->target))
    execute(doc, setChainPairCommand(doc.project(), {name, std::nullopt}));
  noteWidget(keys + "/option/1");
  for (size_t k = 0; k < target.chains.size(); ++k) {
    const std::string& tn = target.chains[k].name;
    const std::string label = tn + (int(k) == target.mainRoot ? " (root)" : "") + "##t" + std::to_string(k);
    if (ImGui::Selectable(label.c_str(), pair && pair->target == tn))
      execute(doc, setChainPairCommand(doc.project(), {name, tn}));
    noteWidget(keys + "/option/" + std::to_string(k + 2));
  }
  ImGui::EndCombo();
}

// The pointer is over the table row drawn from rowTop to the last item (the window hovered,
// no popup open over it).
bool rowHovered(float rowTop) {
  if (!ImGui::IsWindowHovered(ImGuiHoveredFlags_AllowWhenBlockedByActiveItem)) return false;
  const float y = ImGui::GetIO().MousePos.y;
  return y >= rowTop && y < ImGui::GetItemRectMax().y + ImGui::GetStyle().CellPadding.y;
}

}  // namespace

void drawMorphChains(Document& doc, MorphPanelState& st) {
  const bool open = ImGui::CollapsingHeader("Chain matching");
  noteWidget("morph/chains");
  if (open) drawChainMatching(doc, st, "morph/chains");
}

void drawChainMatching(Document& doc, MorphPanelState& st, const std::string& keys) {
  const SkeletonCorrespondence* c = st.runtime ? st.runtime->correspondence.get() : nullptr;
  if (!c) {
    ImGui::TextDisabled(st.runtime ? "No skeleton correspondence (see the projection report's notes)."
                                   : "Preparing the morph...");
    return;
  }
  const std::vector<ChainPair>& pairs = doc.project().morph.chainPairs;
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("Pair a source chain by hand; the automatic matching fills in the rest");
  ImGui::PopStyleColor();
  ImGui::BeginDisabled(pairs.empty());
  if (ImGui::Button("Reset all to automatic")) execute(doc, resetAllChainPairsCommand(doc.project()));
  ImGui::EndDisabled();
  noteWidget(keys + "/reset-all");
  for (const std::string& w : c->warnings) ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.35f, 1.0f), "%s", w.c_str());

  // The source's chains: name, partner combo, reset for an artist pair.
  const SkeletonChains& source = c->source;
  const std::string& sourceId = st.runtime->setup.sourceActorId;
  if (ImGui::BeginTable("##sourceChains", 3, ImGuiTableFlags_BordersInnerH | ImGuiTableFlags_SizingStretchProp)) {
    ImGui::TableSetupColumn(sourceId.c_str(), ImGuiTableColumnFlags_WidthStretch, 1.0f);
    ImGui::TableSetupColumn("partner", ImGuiTableColumnFlags_WidthStretch, 1.7f);
    ImGui::TableSetupColumn("", ImGuiTableColumnFlags_WidthFixed);
    ImGui::TableHeadersRow();
    for (size_t i = 0; i < source.chains.size(); ++i) {
      const std::string& name = source.chains[i].name;
      const auto it = std::find_if(pairs.begin(), pairs.end(), [&](const ChainPair& p) { return p.source == name; });
      const ChainPair* pair = it != pairs.end() ? &*it : nullptr;
      ImGui::PushID(int(i));
      ImGui::TableNextRow();
      const float rowTop = ImGui::GetCursorScreenPos().y;
      ImGui::TableNextColumn();
      const char* root = int(i) == source.mainRoot ? " (root)" : "";
      if (pair) ImGui::TextColored(kArtistColour, "%s%s *", name.c_str(), root);
      else ImGui::Text("%s%s", name.c_str(), root);
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip(pair ? "* paired by hand: the automatic matching leaves it as it is"
                               : "paired by the automatic matching");
      ImGui::TableNextColumn();
      partnerCombo(doc, *c, i, pair, keys);
      ImGui::TableNextColumn();
      if (pair) {
        if (ImGui::SmallButton("x")) execute(doc, resetChainPairCommand(doc.project(), name));
        noteWidget(keys + "/reset/" + std::to_string(i));
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("Reset: back to the automatic matching");
      }
      if (rowHovered(rowTop)) st.hoveredChain = int(i), st.hoveredChainTarget = false;
      ImGui::PopID();
    }
    ImGui::EndTable();
  }

  // The target's chains, read-only: each one's partner or the chain it grows from.
  const SkeletonChains& target = c->target;
  if (ImGui::BeginTable("##targetChains", 2, ImGuiTableFlags_BordersInnerH | ImGuiTableFlags_SizingStretchProp)) {
    ImGui::TableSetupColumn(st.runtime->setup.targetActorId.c_str());
    ImGui::TableSetupColumn("partner");
    ImGui::TableHeadersRow();
    for (size_t i = 0; i < target.chains.size(); ++i) {
      ImGui::TableNextRow();
      const float rowTop = ImGui::GetCursorScreenPos().y;
      ImGui::TableNextColumn();
      ImGui::Text("%s%s", target.chains[i].name.c_str(), int(i) == target.mainRoot ? " (root)" : "");
      ImGui::TableNextColumn();
      const std::string text = chainPartnerText(target, source, c->targetMatch, int(i), "grows from");
      if (c->targetMatch[i] >= 0) ImGui::TextUnformatted(text.c_str());
      else ImGui::TextDisabled("%s", text.c_str());
      noteWidget(keys + "/target/" + std::to_string(i));
      if (rowHovered(rowTop)) st.hoveredChain = int(i), st.hoveredChainTarget = true;
    }
    ImGui::EndTable();
  }
}

BlobGuides hoveredChainGuides(const MorphPanelState& st, double timeSec) {
  BlobGuides out;
  const SkeletonCorrespondence* c = st.runtime ? st.runtime->correspondence.get() : nullptr;
  if (!c || st.hoveredChain < 0) return out;
  const SkeletonChains& chains = st.hoveredChainTarget ? c->target : c->source;
  const MorphActorRuntime& actor = st.hoveredChainTarget ? st.runtime->target : st.runtime->source;
  if (size_t(st.hoveredChain) >= chains.chains.size() || actor.isTree()) return out;
  const std::vector<PosedSegment> posed = posedOperand(actor, timeSec, -1.0).segments;
  out.actorId = actor.actor.id;
  for (int seg : chains.chains[size_t(st.hoveredChain)].segments) {
    if (seg < 0 || size_t(seg) >= posed.size()) continue;
    const PosedSegment& s = posed[size_t(seg)];
    out.lines.push_back({s.a, s.b, -1});
    out.markers.push_back({s.a, -1});
    out.markers.push_back({s.b, -1});
  }
  return out;
}

}  // namespace animorph
