#pragma once
// Command builders for the project-wide settings the panels edit: timeline
// fields (fps, range, playback speed, loop), the morph set-up's fields and view options.
#include <memory>
#include <string>

#include "core/doc/command.h"

namespace animorph {

// Sets one field of the project's Timeline.
template <class T>
std::unique_ptr<Command> setTimelineField(const Project& p, T Timeline::*field, T value, std::string label,
                                          std::string mergeKey = {}) {
  return std::make_unique<SetValueCommand<T>>(
      std::move(label), [field](Project& proj) -> T* { return &(proj.timeline.*field); }, p.timeline.*field,
      std::move(value), std::move(mergeKey));
}

// Sets one field of the project's morph set-up (markers, method, ...).
template <class T>
std::unique_ptr<Command> setMorphField(const Project& p, T MorphSetup::*field, T value, std::string label,
                                       std::string mergeKey = {}) {
  return std::make_unique<SetValueCommand<T>>(
      std::move(label), [field](Project& proj) -> T* { return &(proj.morph.*field); }, p.morph.*field,
      std::move(value), std::move(mergeKey));
}

// Sets one of the project's ViewOptions switches.
inline std::unique_ptr<Command> setViewOption(const Project& p, bool ViewOptions::*field, bool value,
                                              std::string label) {
  return std::make_unique<SetValueCommand<bool>>(
      std::move(label), [field](Project& proj) -> bool* { return &(proj.view.*field); }, p.view.*field, value);
}

}  // namespace animorph
