// EditorUI's long operations, run as background jobs (util/background_job.h): opening a project
// (and loading its characters), opening or importing a glTF, File > Export > Meshes and Volumes...
// and Playblast..., Refit all,
// Animorphosis > Bake to Key-frame Actor, the correspondence editor's Auto-map, and the Particles section's Simulate, Explode and re-form
// and Convert to particles (of a BlobTree actor, or of a character into a new actor). The work runs on the job's thread on copies and fills a result that only the UI thread applies, in
// pollJob(), as one step: a new document, or one undoable command.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include <imgui.h>

#include "core/export/export_project.h"
#include "core/doc/actor_commands.h"
#include "core/doc/animorphosis_bake_actor.h"
#include "core/doc/particle_commands.h"
#include "core/doc/standin_commands.h"
#include "core/doc/animorphosis_commands.h"
#include "core/io/gltf_import.h"
#include "core/project/animorphosis_project.h"
#include "ui/shell/editor_ui.h"
#include "ui/shell/job_progress_panel.h"
#include "core/standin/fit_standin.h"

namespace animorph {
namespace fs = std::filesystem;

namespace {
std::string fileName(const std::string& path) { return fs::path(path).filename().string(); }

// Loads the characters of a project's glTF actors (paths resolved against the project's folder),
// counting each as one step of progress; cancel polled between them.
Status loadActorAssets(const Document& d, JobProgress& pr, std::map<std::string, AssetCache::Entry>& out) {
  std::vector<std::string> paths;
  for (const Actor& a : d.project().actors)
    if (a.kind == ActorKind::Gltf && !a.assetPath.empty()) paths.push_back(d.resolveAsset(a.assetPath));
  // Each character is weighed as a quarter of the project file's steps, spread evenly.
  const double step = paths.empty() ? 0.0 : std::max(1.0, pr.total() * 0.25 / double(paths.size()));
  pr.addTotal(step * double(paths.size()));
  for (const std::string& path : paths) {
    if (pr.cancelled()) return jobCancelled();
    pr.setStage("loading " + fileName(path));
    if (!out.count(path)) out.emplace(path, AssetCache::load(path));
    pr.advance(step);
  }
  return Status::success();
}
// The work of loading one glTF into entry (its failure is kept in the entry, as the cache does).
BackgroundJob::Work loadAssetWork(const std::string& path, std::shared_ptr<AssetCache::Entry> entry) {
  return [path, entry](JobProgress& pr) -> Status {
    pr.setStage("loading");
    *entry = AssetCache::load(path);
    return Status::success();
  };
}
}  // namespace

void EditorUI::startRefitJob(EditorContext& ctx) {
  const std::string actorId = std::move(st_.standinTool.refitAllRequest);
  st_.standinTool.refitAllRequest.clear();
  const Document& d = doc(ctx);
  const Actor* actor = d.project().findActor(actorId);
  const ActorMorph* morphActor = d.project().morph.findActor(actorId);
  if (!actor || !morphActor || actor->assetPath.empty()) return;
  // The character is shared, immutable: the job reads it while the UI goes on drawing it.
  std::shared_ptr<const Character> character = ctx.assets.get(d.resolveAsset(actor->assetPath)).character;
  if (!character) return;
  FitSettings fs;
  fs.kind = morphActor->standin.kind;
  fs.measure = true;  // the report says whether the fit is poor
  auto fitted = std::make_shared<Result<FitResult>>(Error{"not run"});
  auto work = [character, fs, fitted](JobProgress& pr) -> Status {
    pr.setStage("fitting the stand-in");
    *fitted = fitStandin(*character, fs);
    return pr.cancelled() ? jobCancelled() : Status::success();
  };
  startJob("Refit stand-in", std::move(work), [this, actorId, character, fitted](EditorContext& c, const Status&) {
    Document& dd = doc(c);
    const Actor* a = dd.project().findActor(actorId);
    // The actor may have gone, or its file changed, while the job ran: then the fit is not applied.
    if (!a || c.assets.get(dd.resolveAsset(a->assetPath)).character != character) {
      setStatus("Refit stand-in: " + actorId + " changed while fitting; nothing applied", true);
      return;
    }
    if (!*fitted) {
      setStatus("Refit stand-in: " + fitted->error(), true);
      return;
    }
    auto cmd = replaceStandinCommand(dd.project(), actorId, (*fitted)->standin, "Refit stand-in");
    if (!cmd) {
      setStatus("Refit stand-in: " + cmd.error(), true);
      return;
    }
    setStatus((*cmd)->label());
    dd.execute(std::move(*cmd));
    if (dd.selection.actorId == actorId) dd.selection.segment = -1;
    // A poor fit is said loudly: the status bar names the bones.
    if ((*fitted)->report.poor) setStatus("Refit stand-in: POOR FIT: " + (*fitted)->report.problems.front(), true);
    else if (!(*fitted)->report.repairs.empty()) setStatus("Refit stand-in: " + repairSummary((*fitted)->report));
  });
}

void EditorUI::startBakeKeysJob(EditorContext& ctx) {
  const Project& p = doc(ctx).project();
  if (!p.animorphosis.enabled()) {
    setStatus("Bake to key-frame actor: the project has no animorphosis (Create > Animorphosis...)", true);
    return;
  }
  // The bake reads a copy: the UI goes on (and may edit the project) while it runs.
  auto project = std::make_shared<const Project>(p);
  auto baked = std::make_shared<Result<BakedActor>>(Error{"not run"});
  auto work = [project, baked](JobProgress& pr) -> Status {
    pr.setStage("baking the key-frame tree");
    // Progress per node of C; Cancel (or Esc) stops the bake within one channel's work.
    BakeKeysSettings settings;
    settings.cancel = pr.cancelFlag();
    settings.progress = [&pr](size_t done, size_t total) {
      pr.setTotal(double(total));
      pr.setDone(double(done));
    };
    *baked = bakeAnimorphosisActor(*project, settings);
    return pr.cancelled() ? jobCancelled() : Status::success();
  };
  startJob("Bake to key-frame actor", std::move(work), [this, baked](EditorContext& c, const Status&) {
    Document& dd = doc(c);
    if (!*baked) {
      setStatus("Bake to key-frame actor: " + baked->error(), true);
      return;
    }
    // The actor is added to the project as it is now (its id made unique there again).
    setStatus(describeBakedActor(**baked));
    dd.execute(addBakedActorCommand(dd.project(), std::move(**baked)));
    dd.selection = {dd.project().actors.back().id, -1};
  });
}

void EditorUI::startAutoMapJob(EditorContext& ctx) {
  const Project& p = doc(ctx).project();
  if (Status s = checkAnimorphosis(p); !s) {
    setStatus("Auto-map: " + s.error(), true);
    return;
  }
  // The matching reads a copy: the UI goes on (and may edit the project) while it runs.
  auto snapshot = std::make_shared<const Project>(p);
  auto cmd = std::make_shared<std::unique_ptr<Command>>();
  auto report = std::make_shared<AutoCorrespondReport>();
  auto work = [snapshot, cmd, report](JobProgress& pr) -> Status {
    pr.setStage("matching the trees level by level");
    AutoCorrespondSettings settings = autoMapSettings(*snapshot);
    settings.cancel = pr.cancelFlag();
    settings.progress = [&pr](double done, double total) {
      pr.setTotal(total);
      pr.setDone(done);
    };
    auto c = autoMapCommand(*snapshot, settings, report.get());
    if (pr.cancelled()) return jobCancelled();
    if (!c) return Error{c.error()};
    *cmd = std::move(*c);
    return Status::success();
  };
  auto done = [this, snapshot, cmd, report](EditorContext& c, const Status& st) {
    if (!st) {
      setStatus("Auto-map: " + st.error(), true);
      return;
    }
    Document& dd = doc(c);
    // The command swaps the whole setup: applied over an edit made meanwhile it would undo that edit.
    const Project& now = dd.project();
    const AnimorphosisSetup& m = snapshot->animorphosis;
    const Actor* a = now.findActor(m.sourceActorId);
    const Actor* b = now.findActor(m.targetActorId);
    if (!(now.animorphosis == m) || !a || !b || !(a->blobTree == snapshot->findActor(m.sourceActorId)->blobTree) ||
        !(b->blobTree == snapshot->findActor(m.targetActorId)->blobTree)) {
      setStatus("Auto-map: the animorphosis or its trees were edited while it ran; nothing changed. Run it again.",
                true);
      return;
    }
    setStatus((*cmd)->label() + autoMapNote(*report));
    dd.execute(std::move(*cmd));
  };
  startJob("Auto-map", std::move(work), std::move(done), /*lateCancelDiscards=*/true);
}

void EditorUI::startCreateAnimorphosisJob(EditorContext& ctx) {
  const CreateAnimorphosisState& cs = st_.createAnimorphosis;
  auto snapshot = std::make_shared<const Project>(doc(ctx).project());
  const Timeline& tl = snapshot->timeline;
  const std::string source = cs.sourceActorId, target = cs.targetActorId;
  const double startSec = tl.frameToSec(cs.startFrame), endSec = tl.frameToSec(cs.endFrame);
  auto cmd = std::make_shared<std::unique_ptr<Command>>();
  auto work = [snapshot, source, target, startSec, endSec, cmd](JobProgress& pr) -> Status {
    pr.setStage("proposing the correspondence");
    AutoCorrespondSettings settings;
    settings.cancel = pr.cancelFlag();
    settings.progress = [&pr](double done, double total) {
      pr.setTotal(total);
      pr.setDone(done);
    };
    auto c = createAnimorphosisCommand(*snapshot, source, target, startSec, endSec, /*autoMap=*/true, settings);
    if (pr.cancelled()) return jobCancelled();
    if (!c) return Error{c.error()};
    *cmd = std::move(*c);
    return Status::success();
  };
  auto done = [this, snapshot, source, target, cmd](EditorContext& c, const Status& st) {
    if (!st) {
      setStatus("Create animorphosis: " + st.error(), true);
      return;
    }
    Document& dd = doc(c);
    const Project& now = dd.project();
    const Actor* a = now.findActor(source);
    const Actor* b = now.findActor(target);
    if (!(now.animorphosis == snapshot->animorphosis) || !a || !b ||
        !(a->blobTree == snapshot->findActor(source)->blobTree) ||
        !(b->blobTree == snapshot->findActor(target)->blobTree)) {
      setStatus("Create animorphosis: the actors or the animorphosis were edited meanwhile; nothing was created. "
                "Create it again.",
                true);
      return;
    }
    const std::string label = (*cmd)->label();
    dd.execute(std::move(*cmd));
    const size_t links = dd.project().animorphosis.graph.links.size();
    setStatus(label + ": " + std::to_string(links) + " link" + (links == 1 ? "" : "s"));
    st_.correspondence.visible = true;
    st_.correspondence.selected.reset();
  };
  startJob("Create animorphosis", std::move(work), std::move(done), /*lateCancelDiscards=*/true);
}

bool EditorUI::startJob(std::string label, BackgroundJob::Work work, JobDone done, bool lateCancelDiscards) {
  if (job_) {
    setStatus("Wait for " + job_->label() + " to finish, or cancel it (Esc), first", true);
    return false;
  }
  job_ = std::make_unique<BackgroundJob>(std::move(label), std::move(work));
  jobDone_ = std::move(done);
  jobLateCancelDiscards_ = lateCancelDiscards;
  return true;
}

void EditorUI::pollJob(EditorContext& ctx) {
  if (!job_ || !job_->finished()) return;
  std::unique_ptr<BackgroundJob> job = std::move(job_);
  JobDone done = std::move(jobDone_);
  jobDone_ = nullptr;
  if (job->wasCancelled() || (jobLateCancelDiscards_ && job->progress().cancelled())) {
    setStatus(job->label() + " cancelled");
    return;
  }
  done(ctx, job->status());
}

void EditorUI::finishJob(EditorContext& ctx) {
  while (job_) {
    job_->wait();
    pollJob(ctx);  // its done may start another (an opened glTF imports its character)
  }
}

void EditorUI::drawJob(EditorContext& /*ctx*/) {
  if (!job_) return;
  bool cancel = drawJobProgressPanel(st_.layout.viewport, *job_);
  // Esc cancels the job unless a dialog or menu has it.
  if (!ImGui::IsPopupOpen("", ImGuiPopupFlags_AnyPopupId | ImGuiPopupFlags_AnyPopupLevel) &&
      !ImGui::GetIO().WantTextInput && ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false))
    cancel = true;
  if (cancel) cancelJob();
}

void EditorUI::cancelJob() {
  if (!job_ || job_->progress().cancelled()) return;
  job_->cancel();
  setStatus("Cancelling " + job_->label() + "...");
}

void EditorUI::loadProject(const std::string& path, bool recover, EditorContext& ctx) {
  // The document stays editable while the other one loads; edits made meanwhile are not thrown away.
  const Document* before = &doc(ctx);
  const uint64_t revision = before->revision();
  struct Loaded {
    std::unique_ptr<Document> doc;
    std::map<std::string, AssetCache::Entry> assets;
  };
  auto loaded = std::make_shared<Loaded>();
  startJob(
      "Open " + fileName(path),
      [path, recover, loaded](JobProgress& pr) -> Status {
        auto opened = recover ? Document::recoverAutosave(path, &pr) : Document::open(path, &pr);
        if (!opened) return Error{opened.error()};
        loaded->doc = std::move(*opened);
        return loadActorAssets(*loaded->doc, pr, loaded->assets);
      },
      [this, path, recover, loaded, before, revision](EditorContext& ctx, const Status& st) {
        if (!st) {
          showError("Cannot open " + path + ":\n" + st.error());
          return;
        }
        if (ctx.document.get() == before && before->revision() != revision && before->dirty()) {
          showError("Did not open " + path + ": the open project was edited while it loaded.\n"
                    "Save or undo those edits, then open it again.");
          return;
        }
        for (auto& [assetPath, entry] : loaded->assets) ctx.assets.insert(assetPath, std::move(entry));
        std::string abs = loaded->doc->path();
        replaceDocument(std::move(loaded->doc), ctx);
        addRecentFile(st_.prefs, abs);
        savePreferences();
        setStatus(recover ? "Recovered the autosave of " + fileName(abs) + " (not saved yet)" : "Opened " + abs);
      });
}

void EditorUI::openGltfAsNewProject(const std::string& path, EditorContext& /*ctx*/) {
  auto entry = std::make_shared<AssetCache::Entry>();
  startJob(
      "Open " + fileName(path),
      loadAssetWork(path, entry),
      [this, path, entry](EditorContext& ctx, const Status&) {
        if (!entry->character) {  // the current document stays, as when a project fails to open
          showError("Cannot open " + path + ":\n" + entry->error);
          return;
        }
        // The timeline spans the character's first clip, as importing into an empty scene does elsewhere.
        auto fresh = std::make_unique<Document>();
        Project p = fresh->project();
        const Character& c = *entry->character;
        if (!c.clips.empty() && c.clips[0].durationSec > 0.0f && p.timeline.fps > 0.0)
          p.timeline.frameEnd = std::max(1, int(std::ceil(double(c.clips[0].durationSec) * p.timeline.fps)));
        fresh->reset(std::move(p), {});
        ctx.assets.insert(path, std::move(*entry));
        replaceDocument(std::move(fresh), ctx);
        addImportedActor(path, ctx);
        setStatus("New project with " + fileName(path) + " imported (not saved yet)");
      });
}

void EditorUI::importCharacter(const std::string& path, EditorContext& ctx) {
  if (ctx.assets.contains(path)) {  // loaded already (another actor uses it): no job needed
    addImportedActor(path, ctx);
    return;
  }
  auto entry = std::make_shared<AssetCache::Entry>();
  startJob(
      "Import " + fileName(path),
      loadAssetWork(path, entry),
      [this, path, entry](EditorContext& ctx, const Status&) {
        ctx.assets.insert(path, std::move(*entry));
        addImportedActor(path, ctx);
      });
}

void EditorUI::addImportedActor(const std::string& path, EditorContext& ctx) {
  Document& d = doc(ctx);
  std::string projectDir = d.path().empty() ? std::string() : d.baseDir();
  Actor actor = actorForAsset(d.project(), path, projectDir);
  std::string id = actor.id;
  const AssetCache::Entry& e = ctx.assets.get(path);
  d.execute(addActorCommand(std::move(actor)));
  d.selection = {id, -1};
  if (e.character) {
    setStatus("Imported " + fileName(path));
    frameSelection(ctx);
  } else {
    setStatus("Added " + fileName(path) + ", but it did not load: " + e.error, true);
  }
}

void EditorUI::startExport(EditorContext& ctx) {
  Document& d = doc(ctx);
  const ExportSettings s = st_.exportDialog.edit;
  // The settings are the project's (saved with it, undoable) from now on.
  if (!(s == d.project().exportSettings))
    d.execute(std::make_unique<SetValueCommand<ExportSettings>>(
        "Export settings", [](Project& p) -> ExportSettings* { return &p.exportSettings; }, d.project().exportSettings,
        s));
  const std::string baseDir = d.baseDir();
  const std::string out = exportOutputPath(s, baseDir);
  auto report = std::make_shared<ExportReport>();
  startJob(
      "Export",
      [project = d.project(), baseDir, s, report](JobProgress& pr) -> Status {
        auto r = exportProject(project, baseDir, s, pr);
        if (!r) return Error{r.error()};
        *report = std::move(*r);
        return Status::success();
      },
      [this, out, report](EditorContext&, const Status& st) {
        if (!st) {
          showError("Export failed:\n" + st.error());
          return;
        }
        char secs[32];
        std::snprintf(secs, sizeof secs, "%.1f s", report->seconds);
        const std::string skipped = report->framesWithoutField > 0
                                        ? " (" + std::to_string(report->framesWithoutField) +
                                              " skinned-mesh frames have no level set)"
                                        : std::string();
        setStatus("Exported " + std::to_string(report->frames) + " frames to " + out + " in " + secs + skipped);
      });
}

void EditorUI::startPlayblast(EditorContext& ctx) {
  Document& d = doc(ctx);
  const PlayblastSettings s = st_.playblastDialog.edit;
  if (!(s == d.project().playblastSettings))
    d.execute(std::make_unique<SetValueCommand<PlayblastSettings>>(
        "Playblast settings", [](Project& p) -> PlayblastSettings* { return &p.playblastSettings; },
        d.project().playblastSettings, s));
  if (!ctx.playblast) {
    showError("Playblast: this editor was built without the GPU renderer that draws the frames.");
    return;
  }
  // The job draws on a Vulkan device of its own (frame/playblast.h): the editor's device and queue
  // stay the UI thread's. It works on a copy of the project.
  auto report = std::make_shared<PlayblastReport>();
  startJob(
      "Playblast",
      [run = ctx.playblast, project = d.project(), baseDir = d.baseDir(), s, camera = st_.camera,
       report](JobProgress& pr) -> Status {
        auto r = run(project, baseDir, s, camera, pr);
        if (!r) return Error{r.error()};
        *report = std::move(*r);
        return Status::success();
      },
      [this, report](EditorContext&, const Status& st) {
        if (!st) {
          showError("Playblast failed:\n" + st.error());
          return;
        }
        char text[160];
        std::snprintf(text, sizeof text, " (%dx%d) in %.1f s, %.1f frames/s drawn and encoded on ", report->width,
                      report->height, report->seconds,
                      report->pictureSeconds > 0.0 ? report->frames / report->pictureSeconds : 0.0);
        setStatus("Playblast: " + std::to_string(report->frames) + " frames to " + report->file + text + report->device);
      });
}

void EditorUI::startParticleJob(ParticleRequest request, EditorContext& ctx) {
  Document& d = doc(ctx);
  const ParticlesPanelState& ps = st_.inspector.particles;
  const Actor* actor = d.project().findActor(ps.actorId);
  if (actor && actor->kind == ActorKind::Gltf && request == ParticleRequest::Convert)
    return startCharacterParticlesJob(ctx);
  if (!actor || actor->kind != ActorKind::BlobTree) return;
  // The work runs on a snapshot; its command replaces the actor's tree, so it is applied only if
  // that tree is still the snapshot's when the work is done (else it would undo an edit made meanwhile).
  auto snapshot = std::make_shared<const Project>(d.project());
  const std::string actorId = ps.actorId, name = actor->name;
  const bool simulate = request == ParticleRequest::Simulate, reform = request == ParticleRequest::Reform;
  const double timeSec = blobTreeTimeNow(d, *actor);
  auto cmd = std::make_shared<std::unique_ptr<Command>>();
  auto note = std::make_shared<std::string>();
  // The work fills cmd and the status note; the settings' progress and cancel are the job's.
  auto finish = [cmd, note](JobProgress& pr, Result<std::unique_ptr<Command>> c, std::string text) -> Status {
    if (pr.cancelled()) return jobCancelled();
    if (!c) return Error{c.error()};
    *cmd = std::move(*c);
    *note = std::move(text);
    return Status::success();
  };
  auto bind = [](auto& s, JobProgress& pr, const char* stage) {
    pr.setTotal(1.0);
    pr.setStage(stage);
    s.progress = [&pr](float f) { pr.setDone(f); };
    s.cancel = pr.cancelFlag();
  };
  BackgroundJob::Work work;
  if (reform) {
    work = [=, settings = ps.settings, bake = ps.bake, into = ps.reformInto](JobProgress& pr) -> Status {
      ParticleAnimorphosisSettings s = reformSettings(settings, bake);
      bind(s.explosion, pr, "exploding, gathering and baking");
      s.vortex.cancel = s.explosion.cancel;  // the gathering's simulation stops on Cancel too
      ParticleReformReport r;
      char buf[200];
      auto c = particleReformCommand(*snapshot, actorId, s, into, &r);
      std::snprintf(buf, sizeof buf, "%zu particles over %.2f..%.2f s, %zu keys, largest error %.2g mm%s", r.particles,
                    r.startSec, r.endSec, r.keys, double(r.maxError) * 1e3, r.reformed ? ", paths assigned" : "");
      return finish(pr, std::move(c), buf);
    };
  } else if (simulate) {
    work = [=, settings = ps.settings, bake = ps.bake](JobProgress& pr) -> Status {
      ParticleSettings s = settings;
      bind(s, pr, "simulating and baking");
      ParticleBakeReport r;
      char buf[160];
      auto c = simulateParticlesCommand(*snapshot, actorId, s, bake, &r);
      std::snprintf(buf, sizeof buf, "%zu particles, %d steps, %zu keys, largest error %.2g mm", r.particles, r.steps,
                    r.keys, double(r.maxError) * 1e3);
      return finish(pr, std::move(c), buf);
    };
  } else {
    work = [=, count = ps.convertCount](JobProgress& pr) -> Status {
      ConvertToParticlesSettings s;
      s.count = count;
      bind(s, pr, "filling the shape");
      ConvertToParticlesReport r;
      char buf[160];
      auto c = convertToParticlesCommand(*snapshot, actorId, timeSec, s, &r);
      std::snprintf(buf, sizeof buf, "%zu particles, spacing %.3g m, volume %.4g m^3 (shape %.4g m^3)", r.particles,
                    double(r.spacing), r.particleVolume, r.shapeVolume);
      return finish(pr, std::move(c), buf);
    };
  }
  const std::string what = reform     ? "Explode and re-form " + name
                           : simulate ? "Simulate " + name
                                      : "Convert " + name + " to particles";
  startJob(what, std::move(work), [this, snapshot, actorId, what, simulate, reform, cmd, note](EditorContext& ctx, const Status& st) {
    if (!st) {
      showError(what + " failed:\n" + st.error());
      return;
    }
    Document& d = doc(ctx);
    const Actor* now = d.project().findActor(actorId);
    const Actor* then = snapshot->findActor(actorId);
    if (!now || !then || !(now->blobTree == then->blobTree) || (reform && !(d.project().actors == snapshot->actors))) {
      showError(what + ": the actor was edited (or the project replaced) meanwhile; nothing was changed.\n"
                "Run it again.");
      return;
    }
    d.execute(std::move(*cmd));
    if (!simulate) st_.inspector.particles.actorId.clear();  // a new tree: its settings are set up again
    if (reform) d.selection = {actorId, -1};
    setStatus(what + ": " + *note);
  });
}

void EditorUI::startCharacterParticlesJob(EditorContext& ctx) {
  Document& d = doc(ctx);
  const ParticlesPanelState& ps = st_.inspector.particles;
  const Actor* actor = d.project().findActor(ps.actorId);
  if (!actor || actor->kind != ActorKind::Gltf) return;
  // The character is shared, immutable: the job reads it while the UI goes on drawing it.
  const AssetCache::Entry& entry = ctx.assets.get(d.resolveAsset(actor->assetPath));
  const std::string what = "Convert " + actor->name + " to particles";
  if (!entry.character) {
    showError(what + " failed:\n" + actor->assetPath + ": " + entry.error);
    return;
  }
  auto snapshot = std::make_shared<const Project>(d.project());
  const double timeSec = d.project().timeline.currentTimeSec();
  auto made = std::make_shared<Actor>();
  auto note = std::make_shared<std::string>();
  auto work = [=, character = entry.character, id = ps.actorId, from = ps.convertFrom,
               count = ps.convertCount](JobProgress& pr) -> Status {
    ConvertToParticlesSettings s;
    s.count = count;
    pr.setTotal(1.0);
    pr.setStage(from == ParticleSource::Mesh ? "filling the mesh" : "filling the stand-in");
    s.progress = [&pr](float f) { pr.setDone(f); };
    s.cancel = pr.cancelFlag();
    CharacterParticlesReport r;
    auto a = characterParticlesActor(*snapshot, id, *character, timeSec, from, s, &r);
    if (pr.cancelled()) return jobCancelled();
    if (!a) return Error{a.error()};
    *made = std::move(*a);
    char buf[240];
    std::snprintf(buf, sizeof buf, "%zu particles from the %s, spacing %.3g m, volume %.4g m^3 (shape %.4g m^3)",
                  r.convert.particles, from == ParticleSource::Mesh ? "mesh" : "stand-in", double(r.convert.spacing),
                  r.convert.particleVolume, r.convert.shapeVolume);
    *note = buf;
    if (r.standinFitted) *note += "; no stand-in: one was fitted";
    if (r.boundaryEdges > 0)
      *note += "; the mesh is not closed (" + std::to_string(r.boundaryEdges) +
               " boundary edges): filled where 2 of 3 rays are inside";
    return Status::success();
  };
  startJob(what, std::move(work), [this, what, made, note](EditorContext& c, const Status& st) {
    if (!st) {
      showError(what + " failed:\n" + st.error());
      return;
    }
    Document& dd = doc(c);
    // Its id was made unused in the snapshot; another actor may have taken it meanwhile.
    if (dd.project().findActor(made->id)) made->id = dd.project().uniqueActorId(made->id);
    const std::string id = made->id;
    dd.execute(addActorCommand(std::move(*made)));
    dd.selection = {id, -1};
    setStatus(what + ": " + *note);
  });
}

}  // namespace animorph
