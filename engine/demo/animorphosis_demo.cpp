#include "demo/animorphosis_demo.h"

#include "demo/dino_dragon.h"
#include "core/project/animorphosis_project.h"
#include "core/doc/blobtree_commands.h"

namespace animorph {

Result<Project> makeAnimorphosisDemoProject() {
  Project p;
  p.name = "Dinosaur to dragon";
  p.timeline.fps = 24.0;
  p.timeline.frameStart = 0;
  p.timeline.frameEnd = int(p.timeline.secToFrame(kDemoMorphEndSec + kDemoMorphStartSec));
  p.view.showSkeleton = false;
  Actor dinosaur = makeBlobTreeActor(p, "Dinosaur");
  dinosaur.blobTree = makeDinosaur();
  dinosaur.loop = true;
  p.actors.push_back(dinosaur);
  Actor dragon = makeBlobTreeActor(p, "Dragon");
  dragon.blobTree = makeDragon();
  dragon.loop = true;
  p.actors.push_back(dragon);
  p.animorphosis.sourceActorId = dinosaur.id;
  p.animorphosis.targetActorId = dragon.id;
  p.animorphosis.startSec = kDemoMorphStartSec;
  p.animorphosis.endSec = kDemoMorphEndSec;
  p.animorphosis.globalS = defaultSCurve();
  p.animorphosis.graph = dinosaurToDragonGraph(dinosaur.blobTree, dragon.blobTree);
  if (auto s = checkAnimorphosis(p); !s) return Error{"demo animorphosis: " + s.error()};
  return p;
}

}  // namespace animorph
