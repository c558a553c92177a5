#include "core/animorphosis/correspondence_json.h"

#include "core/anim/track_json.h"

#include <cmath>

namespace animorph {

using nlohmann::json;

json correspondenceToJson(const CorrespondenceGraph& g) {
  json links = json::array();
  for (const auto& l : g.links) {
    json o{{"a", l.nodeA}, {"b", l.nodeB}, {"confidence", l.confidence}, {"artist", l.artist}};
    if (l.sOverride) o["s"] = trackToJson(*l.sOverride);
    links.push_back(std::move(o));
  }
  json out{{"links", std::move(links)}};
  if (!g.suggestions.empty()) {
    json sug = json::array();
    for (const auto& l : g.suggestions) sug.push_back(json{{"a", l.nodeA}, {"b", l.nodeB}, {"confidence", l.confidence}});
    out["suggestions"] = std::move(sug);
  }
  return out;
}

namespace {

Result<int> idField(const json& o, const char* key, const std::string& where) {
  auto it = o.find(key);
  if (it == o.end()) return Error{where + ": missing \"" + key + "\" (a node id)"};
  if (!it->is_number_integer()) return Error{where + ": \"" + key + "\" must be an integer node id"};
  int64_t v = it->get<int64_t>();
  if (v < INT32_MIN || v > INT32_MAX) return Error{where + ": \"" + key + "\" is out of range"};
  return int(v);
}

// The optional "suggestions": links with ids and a confidence only.
Status suggestionsFromJson(const json& j, const std::string& source, CorrespondenceGraph& g) {
  auto it = j.find("suggestions");
  if (it == j.end()) return Status::success();
  if (!it->is_array()) return Error{source + ": \"suggestions\" must be an array"};
  if (it->size() > kMaxCorrespondenceLinks)
    return Error{source + ": " + std::to_string(it->size()) + " suggestions, more than the limit of " +
                 std::to_string(kMaxCorrespondenceLinks)};
  for (size_t i = 0; i < it->size(); ++i) {
    const json& o = (*it)[i];
    std::string where = source + ": suggestion " + std::to_string(i);
    if (!o.is_object()) return Error{where + " must be an object"};
    auto a = idField(o, "a", where);
    if (!a) return Error{a.error()};
    auto b = idField(o, "b", where);
    if (!b) return Error{b.error()};
    CorrespondenceLink l;
    l.nodeA = *a;
    l.nodeB = *b;
    l.artist = false;
    l.confidence = 0.0f;
    if (auto c = o.find("confidence"); c != o.end()) {
      double v = c->is_number() ? c->get<double>() : -1.0;
      if (!std::isfinite(v) || v < 0.0 || v > 1.0) return Error{where + ": \"confidence\" must be a number in [0, 1]"};
      l.confidence = float(v);
    }
    g.suggestions.push_back(l);
  }
  return Status::success();
}

}  // namespace

Result<CorrespondenceGraph> correspondenceFromJson(const json& j, const std::string& source) {
  if (!j.is_object()) return Error{source + ": a correspondence graph must be a JSON object"};
  auto it = j.find("links");
  if (it == j.end()) return Error{source + ": missing \"links\""};
  if (!it->is_array()) return Error{source + ": \"links\" must be an array"};
  if (it->size() > kMaxCorrespondenceLinks)
    return Error{source + ": " + std::to_string(it->size()) + " links, more than the limit of " +
                 std::to_string(kMaxCorrespondenceLinks)};
  CorrespondenceGraph g;
  g.links.reserve(it->size());
  for (size_t i = 0; i < it->size(); ++i) {
    const json& o = (*it)[i];
    std::string where = source + ": link " + std::to_string(i);
    if (!o.is_object()) return Error{where + " must be an object"};
    CorrespondenceLink l;
    auto a = idField(o, "a", where);
    if (!a) return Error{a.error()};
    auto b = idField(o, "b", where);
    if (!b) return Error{b.error()};
    l.nodeA = *a;
    l.nodeB = *b;
    where += " (" + std::to_string(l.nodeA) + " -> " + std::to_string(l.nodeB) + ")";
    if (auto c = o.find("confidence"); c != o.end()) {
      if (!c->is_number()) return Error{where + ": \"confidence\" must be a number"};
      double v = c->get<double>();
      if (!std::isfinite(v) || v < 0.0 || v > 1.0) return Error{where + ": \"confidence\" must lie in [0, 1]"};
      l.confidence = float(v);
    }
    if (auto ar = o.find("artist"); ar != o.end()) {
      if (!ar->is_boolean()) return Error{where + ": \"artist\" must be true or false"};
      l.artist = ar->get<bool>();
    }
    if (auto s = o.find("s"); s != o.end()) {
      auto track = floatTrackFromJson(*s, where + ": \"s\"");
      if (!track) return Error{track.error()};
      Status ok = checkSCurve(*track, where + ": \"s\"");
      if (!ok) return Error{ok.error()};
      l.sOverride = std::move(*track);
    }
    g.links.push_back(std::move(l));
  }
  if (Status s = suggestionsFromJson(j, source, g); !s) return Error{s.error()};
  return g;
}

}  // namespace animorph
