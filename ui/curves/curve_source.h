#pragma once
// What the curve editor shows and edits: a set of tracks of the project (a
// BlobTree node's parameters, the morph's easing / blend / noise / segment
// tracks, the animorphosis' s curves) behind one interface, so the panel
// draws and edits any of them the same way. A source is a light view built each frame from the document and
// the selection; the tracks stay in the Project and change only through the
// commands edit() returns.
#include <any>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/anim/key_edit.h"
#include "core/doc/document.h"

namespace animorph {

struct CurveChannel {
  ParamAddress addr;
  int channel = 0;   // 0 for floats; x, y, z of vectors; Euler X, Y, Z degrees of rotations
  std::string name;  // unique within the source
  bool rotation = false;
  int colorIndex = -1;  // 0..2: x, y, z colours; -1: the single-channel colour
};

struct CurvePlayhead {
  double x = 0.0;
  std::string label;  // drawn beside the line
  bool secondary = false;  // drawn in the second colour (e.g. a transition's progress)
};

// The horizontal axis: x = track time * xPerTime.
struct CurveAxis {
  double xPerTime = 24.0;     // frames per second; 1 for a normalised progress
  std::string label;          // "frame", "u: progress"
  double snapStep = 1.0;      // x units that key drags snap to
  std::string snapLabel;      // "Snap to frames"
  double rangeStart = 0.0;    // shaded in a lighter tone (the playback range, [0, 1])
  double rangeEnd = 0.0;
  std::vector<CurvePlayhead> playheads;
};

// An axis over a normalised progress u in [0, 1] (shaded), keys snapped to 0.01.
CurveAxis progressAxis(std::string label);

using KeyEditFn = std::function<Status(const TrackSet&)>;

class CurveSource {
 public:
  virtual ~CurveSource() = default;
  // What is shown; the editor resets its selection and framing when this changes.
  virtual std::string id() const = 0;
  virtual std::string title() const = 0;
  // Shown in the channel list when there are no channels.
  virtual std::string emptyHint() const = 0;
  virtual std::vector<CurveChannel> channels() const = 0;
  virtual CurveAxis axis() const = 0;
  // The track at a in the project now, or in a snapshot.
  virtual ConstTrackPtr track(const ParamAddress& a) const = 0;
  virtual ConstTrackPtr track(const std::any& snapshot, const ParamAddress& a) const = 0;
  // The tracks' container now (kept while a drag runs, so each drag step rebuilds from it).
  virtual std::any snapshot() const = 0;
  // Runs fn on a copy of the tracks (of from, a snapshot, when non-null) and
  // returns the command that puts the result in; fn's error otherwise.
  virtual Result<std::unique_ptr<Command>> edit(std::string label, const KeyEditFn& fn, std::string mergeKey = {},
                                                const std::any* from = nullptr) const = 0;
};

// The curve source for the document's selection: the selected BlobTree node's
// tracks; the morph's tracks when nothing (or the morph's source or target
// actor) is selected in a project with a morph; null otherwise.
std::unique_ptr<CurveSource> curveSourceForSelection(const Document& doc);

// The two kinds (blob_curve_source.cpp, morph_curve_source.cpp); null when
// there is nothing to show.
std::unique_ptr<CurveSource> makeBlobCurveSource(const Document& doc, const std::string& actorId, int node);
std::unique_ptr<CurveSource> makeMorphCurveSource(const Document& doc);
// The animorphosis' global s(u), and the s(u) of the link nodeA -> nodeB when
// it has its own (animorphosis_curve_source.cpp); null without an animorphosis.
std::unique_ptr<CurveSource> makeAnimorphosisCurveSource(const Document& doc, int nodeA = -1, int nodeB = -1);

}  // namespace animorph
