#include "ui/timeline/actor_timing.h"

#include <imgui.h>

#include "ui/widgets/widget_rects.h"

namespace animorph {

void drawActorTiming(Document& doc, const Actor& actor, DragMerge& drag, const std::string& widgetPrefix) {
  const std::string id = actor.id;
  ImGui::PushID(widgetPrefix.c_str());
  double offset = actor.timeOffsetSec;
  bool changed = ImGui::DragScalar("Offset (s)", ImGuiDataType_Double, &offset, 0.01f, nullptr, nullptr, "%.3f");
  noteWidget(widgetPrefix + "/offset");
  drag.begin(doc);
  if (changed)
    doc.execute(setActorField(doc.project(), id, &Actor::timeOffsetSec, offset, "Set time offset of " + actor.name,
                              id + "/offset"));
  drag.end(doc);

  double speed = actor.speed;
  changed = ImGui::DragScalar("Speed", ImGuiDataType_Double, &speed, 0.01f, nullptr, nullptr, "%.3fx");
  noteWidget(widgetPrefix + "/speed");
  drag.begin(doc);
  if (changed)
    doc.execute(setActorField(doc.project(), id, &Actor::speed, speed, "Set speed of " + actor.name, id + "/speed"));
  drag.end(doc);

  bool loop = actor.loop;
  if (ImGui::Checkbox("Loop", &loop))
    doc.execute(setActorField(doc.project(), id, &Actor::loop, loop, "Set loop of " + actor.name));
  noteWidget(widgetPrefix + "/loop");
  ImGui::PopID();
}

}  // namespace animorph
