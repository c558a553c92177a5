#pragma once
// Makes one ImGui drag (or one typed edit of a drag field) one undo step:
// opens the Document's merge group when the last item becomes active and
// closes it when it is released. Commands pushed in between need a merge key.
#include <imgui.h>

#include "core/doc/document.h"

namespace animorph {

class DragMerge {
 public:
  // Call right after the widget, before executing its edit.
  void begin(Document& doc) {
    if (ImGui::IsItemActivated() && !open_) {
      doc.beginDrag();
      open_ = true;
    }
  }
  // Call after executing the widget's edit.
  void end(Document& doc) {
    if (ImGui::IsItemDeactivated() && open_) {
      doc.endDrag();
      open_ = false;
    }
  }
  // Once per frame: closes a group whose widget vanished mid-drag.
  void endFrame(Document& doc) {
    if (open_ && !ImGui::IsAnyItemActive()) {
      doc.endDrag();
      open_ = false;
    }
  }
  bool open() const { return open_; }

 private:
  bool open_ = false;
};

}  // namespace animorph
