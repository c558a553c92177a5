#pragma once
// The fields File > Export... and File > Export > Playblast... share, each noted in the widget map
// as PREFIX/NAME: the frame range (PREFIX/use_timeline, /first, /last), a plain integer field and
// the output path with its Browse... button (PREFIX/output, /browse).
#include <string>

#include "core/project/project.h"

namespace animorph {

// LABEL then a field without step buttons (the widget map's rectangle is the field itself).
void plainIntField(const char* label, const char* id, int& v);

// "Timeline range" (first and last follow the timeline while it is ticked) and the two frames.
void frameRangeFields(const Project& p, const std::string& prefix, bool& useTimeline, int& first, int& last);

// What is wrong with a frame range and a project to bake ("" when nothing): a negative first frame,
// the last before the first, no morph or animorphosis (what names the operation: "export").
std::string frameRangeProblem(const Project& p, int first, int last, const char* what);

// The output path as text and Browse... beside it; true when Browse... was clicked.
bool outputPathField(const std::string& prefix, const char* label, std::string& output);

}  // namespace animorph
