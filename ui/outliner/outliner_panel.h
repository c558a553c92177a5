#pragma once
// Outliner (left panel): the project's actors; expanding one shows its
// character's node hierarchy (meshes, joints) from the AssetCache. Click
// selects, double-click renames, the eye box toggles visibility, the context
// menu deletes; an asset that failed to load shows its error in red.
#include <string>
#include <vector>

#include "ui/outliner/blob_outliner.h"
#include "core/project/asset_cache.h"
#include "core/doc/document.h"
#include "ui/common/layout.h"
#include "ui/common/shortcuts.h"
#include "ui/common/status_bar.h"

namespace animorph {

struct OutlinerState {
  std::string renamingActorId;  // actor whose name is being edited, or empty
  std::string renameBuffer;
  bool focusRename = false;
  BlobOutlinerState blob;  // BlobTree actors' node hierarchies
};

// Starts renaming actorId in place (double-click does this too).
void beginRename(OutlinerState& st, const Document& doc, const std::string& actorId);

// Draws the panel as a fixed window over rect. Edits go through the
// Document's commands; actions the panel cannot do itself (import) are
// appended to actions. BlobTree actors show their node tree (blob_outliner.h);
// refused node edits report to status.
void drawOutlinerPanel(const LayoutRect& rect, Document& doc, AssetCache& assets, OutlinerState& st,
                       std::vector<Action>& actions, StatusMessage& status);

}  // namespace animorph
