#pragma once
// Running a command builder's result from a panel or tool: execute the
// command, or put the builder's refusal in the status bar.
#include <memory>

#include "core/doc/document.h"
#include "ui/common/status_bar.h"
#include "core/util/result.h"

namespace animorph {

// Executes cmd when it was built (announce: its label goes to the status bar),
// else shows its error. Returns whether it ran.
inline bool executeOrReport(Document& doc, Result<std::unique_ptr<Command>> cmd, StatusMessage& status,
                            bool announce = false) {
  if (!cmd) {
    status = {cmd.error(), true};
    return false;
  }
  if (announce) status = {(*cmd)->label(), false};
  doc.execute(std::move(*cmd));
  return true;
}

}  // namespace animorph
