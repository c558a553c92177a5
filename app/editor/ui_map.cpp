#include "app/editor/ui_map.h"

#include "core/util/atomic_file.h"

namespace animorph {

void writeUiMap(const std::string& path, const WidgetRects& rects, const EditorOutput& out, const Document& doc,
                int frameCount, const nlohmann::json& extra) {
  nlohmann::json j = extra;
  j["frame_count"] = frameCount;
  j["project"] = doc.path();
  j["selected"] = doc.selection.actorId;
  j["current_frame"] = doc.project().timeline.currentFrame;
  j["frame_start"] = doc.project().timeline.frameStart;
  j["frame_end"] = doc.project().timeline.frameEnd;
  j["fps"] = doc.project().timeline.fps;
  j["dirty"] = doc.dirty();
  j["viewport"] = {out.viewport.min.x, out.viewport.min.y, out.viewport.size.x, out.viewport.size.y};
  nlohmann::json w = nlohmann::json::object();
  for (const auto& [key, r] : rects.all()) w[key] = {r.min.x, r.min.y, r.max.x, r.max.y};
  j["widgets"] = std::move(w);
  (void)writeFileAtomic(path, j.dump(1));
}

void writeEditorUiMap(const std::string& path, const EditorUI& ui, EditorContext& ectx, int frameCount,
                      const FrameMapInfo& info) {
  const Document& doc = *ectx.document;
  writeUiMap(path, ui.widgets(), ui.output(), doc, frameCount,
             {{"preview_busy", info.previewBusy},
              {"idle", info.idle},
              {"status", ui.state().status.text},
              // A test knows input it sent before polled_at has been processed once the editor is
              // idle (gui_driver.fresh_map).
              {"polled_at", info.polledAt},
              {"preview", ectx.stats.previewInfo},
              {"viewport_note", ectx.viewportNote},  // "morph: morph 50%", a morph's error
              {"preview_gpu", info.previewGpu},
              {"present", info.presentPath},
              {"particle_view", info.particlesShown},
              {"paced", info.paced},
              {"scene_passes", info.scenePasses},
              {"kept_viewport_frames", info.keptFrames},
              {"standin_segment", selectedStandinSegment(doc)},
              {"job", ui.runningJob() ? ui.runningJob()->label() : std::string()},
              {"job_fraction", ui.runningJob() ? ui.runningJob()->progress().fraction() : 0.0}});
}

}  // namespace animorph
