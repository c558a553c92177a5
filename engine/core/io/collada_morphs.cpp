#include "core/io/collada_morphs.h"

#include <algorithm>
#include <charconv>
#include <map>

#include "core/io/collada_morph_weights.h"
#include "core/io/collada_text.h"

namespace animorph {
namespace {

// assimp reads the tag as a float: indices above 2^24 would not be exact.
constexpr size_t kMaxTaggedPositions = size_t(1) << 24;

using namespace collada;

struct Ctx {
  const std::string& file;
  View b;
  std::map<std::string, Element> geometries;  // by id
  Error fail(const std::string& element, const std::string& reason) const {
    return Error{file + ": " + element + ": " + reason};
  }
};

// The mesh, its <vertices> and the positions of geometry `id`.
struct GeometryPositions {
  Element mesh, vertices;
  std::vector<glm::vec3> positions;
};

Result<GeometryPositions> geometryPositions(const Ctx& c, const std::string& id) {
  const std::string where = "geometry '" + id + "'";
  auto g = c.geometries.find(id);
  if (g == c.geometries.end()) return c.fail(where, "missing");
  GeometryPositions out;
  out.mesh = findElement(c.b, "mesh", g->second.begin, g->second.close);
  out.vertices = out.mesh.at == npos ? Element{} : findElement(c.b, "vertices", out.mesh.begin, out.mesh.close);
  if (out.vertices.at == npos || out.vertices.close == out.vertices.end) return c.fail(where, "no <mesh> with <vertices>");
  std::string source;
  for (Element in = findElement(c.b, "input", out.vertices.begin, out.vertices.close); in.at != npos;
       in = findElement(c.b, "input", in.end, out.vertices.close))
    if (attribute(c.b, in, "semantic") == "POSITION") source = attribute(c.b, in, "source");
  if (source.size() < 2 || source[0] != '#') return c.fail(where, "<vertices> has no POSITION input");
  const Element src = findById(c.b, "source", source.substr(1), out.mesh.begin, out.mesh.close);
  const Element arr = src.at == npos ? Element{} : findElement(c.b, "float_array", src.begin, src.close);
  if (arr.at == npos) return c.fail(where, "position source '" + source + "' has no <float_array>");
  const Element accessor = findElement(c.b, "accessor", src.begin, src.close);
  if (accessor.at != npos && !attribute(c.b, accessor, "stride").empty() && attribute(c.b, accessor, "stride") != "3")
    return c.fail(where, "positions of stride " + attribute(c.b, accessor, "stride") + " are not read (3 expected)");
  auto values = floats(where + " positions", c.b, arr);
  if (!values) return Error{c.file + ": " + values.error()};
  if (values->size() % 3 != 0) return c.fail(where, std::to_string(values->size()) + " position numbers, not a multiple of 3");
  out.positions.resize(values->size() / 3);
  for (size_t i = 0; i < out.positions.size(); ++i)
    out.positions[i] = {(*values)[3 * i], (*values)[3 * i + 1], (*values)[3 * i + 2]};
  return out;
}

// The <source id=ID> of the morph (its arrays' text).
Element morphSource(const Ctx& c, const Element& morph, const std::string& ref) {
  if (ref.size() < 2 || ref[0] != '#') return {};
  return findById(c.b, "source", ref.substr(1), morph.begin, morph.close);
}

// One <morph> controller: its base geometry, target deltas and weights.
Result<ColladaMorph> readMorph(const Ctx& c, const Element& controller, const Element& morph, size_t maxShapeVertices,
                               size_t& shapeVertices) {
  ColladaMorph m;
  m.controllerId = attribute(c.b, controller, "id");
  const std::string where = "controller '" + m.controllerId + "'";
  const std::string base = attribute(c.b, morph, "source");
  if (base.size() < 2 || base[0] != '#') return c.fail(where, "<morph source=\"" + base + "\"> is not a reference #ID");
  m.baseGeometryId = base.substr(1);
  if (!c.geometries.count(m.baseGeometryId))
    return c.fail(where, "morph source '" + base + "' names no geometry (a morph of a controller is not read)");
  auto basePositions = geometryPositions(c, m.baseGeometryId);
  if (!basePositions) return Error{basePositions.error()};
  m.basePositions = std::move(basePositions->positions);
  const bool relative = attribute(c.b, morph, "method") == "RELATIVE";  // targets are deltas already

  std::string targetRef, weightRef;
  const Element targets = findElement(c.b, "targets", morph.begin, morph.close);
  if (targets.at == npos) return c.fail(where, "<morph> has no <targets>");
  for (Element in = findElement(c.b, "input", targets.begin, targets.close); in.at != npos;
       in = findElement(c.b, "input", in.end, targets.close)) {
    const std::string semantic = attribute(c.b, in, "semantic");
    if (semantic == "MORPH_TARGET") targetRef = attribute(c.b, in, "source");
    if (semantic == "MORPH_WEIGHT") weightRef = attribute(c.b, in, "source");
  }
  const Element targetSource = morphSource(c, morph, targetRef);
  Element ids = targetSource.at == npos ? Element{} : findElement(c.b, "IDREF_array", targetSource.begin, targetSource.close);
  if (ids.at == npos && targetSource.at != npos) ids = findElement(c.b, "Name_array", targetSource.begin, targetSource.close);
  if (ids.at == npos) return c.fail(where, "MORPH_TARGET input '" + targetRef + "' names no source with an IDREF_array");
  for (const std::string& id : tokens(c.b, ids)) {
    auto target = geometryPositions(c, id);
    if (!target) return Error{target.error() + " (a target of " + where + ")"};
    if (target->positions.size() != m.basePositions.size())
      return c.fail(where, "target '" + id + "' has " + std::to_string(target->positions.size()) +
                               " positions, the base geometry '" + m.baseGeometryId + "' " +
                               std::to_string(m.basePositions.size()));
    shapeVertices += m.basePositions.size();
    if (shapeVertices > maxShapeVertices)
      return c.fail(where, "blend shapes of more than " + std::to_string(maxShapeVertices) + " vertices in all");
    ColladaMorphTarget t;
    t.name = attribute(c.b, c.geometries.at(id), "name");
    if (t.name.empty()) t.name = id;
    t.deltas = std::move(target->positions);
    if (!relative)
      for (size_t i = 0; i < t.deltas.size(); ++i) t.deltas[i] -= m.basePositions[i];
    m.targets.push_back(std::move(t));
  }
  const Element weightSource = morphSource(c, morph, weightRef);
  const Element weightArray =
      weightSource.at == npos ? Element{} : findElement(c.b, "float_array", weightSource.begin, weightSource.close);
  if (weightSource.at != npos) m.weightSourceId = attribute(c.b, weightSource, "id");
  if (weightArray.at != npos) m.weightArrayId = attribute(c.b, weightArray, "id");
  if (weightArray.at != npos) {
    auto w = floats(where + " weights", c.b, weightArray);
    if (!w) return Error{c.file + ": " + w.error()};
    if (w->size() != m.targets.size())
      return c.fail(where, std::to_string(w->size()) + " weights for " + std::to_string(m.targets.size()) + " targets");
    m.defaultWeights = std::move(*w);
  } else {
    m.defaultWeights.assign(m.targets.size(), 0.0f);
  }
  return m;
}

struct Edit {
  size_t at, erase;
  std::string insert;
};

// The edits that tag geometry `id`'s vertices with their position index (see the header).
Result<std::vector<Edit>> tagEdits(const Ctx& c, const std::string& id, size_t serial) {
  auto g = geometryPositions(c, id);
  if (!g) return Error{g.error()};
  const Element& geometry = c.geometries.at(id);
  const size_t n = g->positions.size();
  if (n > kMaxTaggedPositions)
    return c.fail("geometry '" + id + "'", std::to_string(n) + " positions: blend shapes are read on meshes of at most " +
                                               std::to_string(kMaxTaggedPositions));
  if (findIn(c.b, "set=\"" + std::to_string(kColladaIndexSet) + "\"", geometry.begin, geometry.close) != npos)
    return c.fail("geometry '" + id + "'", "uses texture coordinate set " + std::to_string(kColladaIndexSet) +
                                               ", which the importer needs to map its blend shapes");
  const std::string sid = "animorph_position_index_" + std::to_string(serial);
  char tag[32];
  const auto r = std::to_chars(tag, tag + sizeof tag, kColladaIndexTag);
  const std::string tagText(tag, r.ptr);
  std::string source = "<source id=\"" + sid + "\"><float_array id=\"" + sid + "-array\" count=\"" +
                       std::to_string(2 * n) + "\">";
  source.reserve(source.size() + n * (tagText.size() + 10) + 300);
  for (size_t i = 0; i < n; ++i) source += std::to_string(i) + " " + tagText + " ";
  source += "</float_array><technique_common><accessor source=\"#" + sid + "-array\" count=\"" + std::to_string(n) +
            "\" stride=\"2\"><param name=\"S\" type=\"float\"/><param name=\"T\" type=\"float\"/></accessor>"
            "</technique_common></source>";
  // After the POSITION input: assimp pads a set to the positions read so far.
  const std::string input = "<input semantic=\"TEXCOORD\" source=\"#" + sid + "\" set=\"" +
                            std::to_string(kColladaIndexSet) + "\"/>";
  return std::vector<Edit>{{g->mesh.begin, 0, std::move(source)}, {g->vertices.close, 0, input}};
}

// The document with the edits applied, and every "#CONTROLLER" reference to a removed morph
// controller turned into "#BASE" (one pass).
std::string applyEdits(View b, std::vector<Edit> edits, const std::map<std::string, std::string>& baseOfMorph) {
  std::sort(edits.begin(), edits.end(), [](const Edit& x, const Edit& y) { return x.at < y.at; });
  std::string edited;
  edited.reserve(b.size());
  size_t p = 0;
  for (const Edit& e : edits) {
    edited.append(b.substr(p, e.at - p));
    edited += e.insert;
    p = e.at + e.erase;
  }
  edited.append(b.substr(p));
  std::string out;
  out.reserve(edited.size());
  size_t q = 0;
  for (size_t h = edited.find("\"#"); h != npos; h = edited.find("\"#", h + 2)) {
    const size_t end = edited.find('"', h + 2);
    if (end == npos) break;
    auto it = baseOfMorph.find(edited.substr(h + 2, end - h - 2));
    if (it == baseOfMorph.end()) continue;
    out.append(edited, q, h + 2 - q);
    out += it->second;
    q = end;
  }
  out.append(edited, q, npos);
  return out;
}

}  // namespace

Result<ColladaMorphDocument> prepareColladaMorphs(const std::string& file, const std::string& bytes,
                                                  size_t maxShapeVertices) {
  ColladaMorphDocument out;
  const View b(bytes);
  if (b.find("<morph") == npos) return out;
  const Element controllers = findElement(b, "library_controllers", 0, b.size());
  const Element geometries = findElement(b, "library_geometries", 0, b.size());
  if (controllers.at == npos) return out;  // no controller library: assimp reads no <morph> either
  if (geometries.at == npos) return Error{file + ": library_geometries: missing (the <morph> controllers need it)"};
  Ctx c{file, b, {}};
  for (Element g = findElement(b, "geometry", geometries.begin, geometries.close); g.at != npos;
       g = findElement(b, "geometry", g.end, geometries.close))
    c.geometries.emplace(attribute(b, g, "id"), g);
  std::vector<Edit> edits;
  std::map<std::string, std::string> baseOfMorph;
  size_t shapeVertices = 0;
  for (Element ctl = findElement(b, "controller", controllers.begin, controllers.close); ctl.at != npos;
       ctl = findElement(b, "controller", ctl.end, controllers.close)) {
    const Element morph = findElement(b, "morph", ctl.begin, ctl.close);
    if (morph.at == npos) continue;
    auto m = readMorph(c, ctl, morph, maxShapeVertices, shapeVertices);
    if (!m) return Error{m.error()};
    edits.push_back({ctl.at, ctl.end - ctl.at, ""});
    const bool tagged = std::any_of(out.morphs.begin(), out.morphs.end(),
                                    [&](const ColladaMorph& o) { return o.baseGeometryId == m->baseGeometryId; });
    if (!tagged) {
      auto tag = tagEdits(c, m->baseGeometryId, out.morphs.size());
      if (!tag) return Error{tag.error()};
      edits.insert(edits.end(), tag->begin(), tag->end());
    }
    baseOfMorph[m->controllerId] = m->baseGeometryId;
    out.morphs.push_back(std::move(*m));
  }
  if (out.morphs.empty()) return out;
  auto channels = readColladaMorphWeights(file, b, out.morphs, out.notes);
  if (!channels) return Error{channels.error()};
  for (const auto& [at, end] : *channels) edits.push_back({at, end - at, ""});
  out.document = applyEdits(b, std::move(edits), baseOfMorph);
  return out;
}

}  // namespace animorph
