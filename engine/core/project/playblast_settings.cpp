#include "core/project/playblast_settings.h"

namespace animorph {

std::string playblastSizeProblem(const PlayblastSettings& s) {
  if (s.width < 16 || s.height < 16 || s.width > 8192 || s.height > 8192 || s.width % 2 || s.height % 2)
    return "The picture size must be even numbers of 16..8192 pixels (H.264 needs even sizes).";
  if (s.resolution < 2 || s.resolution > 1024) return "The resolution must be 2..1024 cells.";
  return {};
}

}  // namespace animorph
