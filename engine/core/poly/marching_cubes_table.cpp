#include "core/poly/marching_cubes_table.h"

#include <glm/glm.hpp>
#include <vector>

namespace animorph {

namespace {

glm::vec3 cornerPos(int c) { return glm::vec3(float(c & 1), float((c >> 1) & 1), float((c >> 2) & 1)); }

MarchingCubesTable build() {
  MarchingCubesTable t{};
  int edgeOf[8][8];
  for (auto& row : edgeOf)
    for (int& e : row) e = -1;
  // Edges: axis a, the other two coordinates from the low two bits of e % 4.
  for (int a = 0; a < 3; ++a)
    for (int k = 0; k < 4; ++k) {
      int e = a * 4 + k;
      int o1 = (a + 1) % 3, o2 = (a + 2) % 3;
      int c0 = ((k & 1) << o1) | (((k >> 1) & 1) << o2);
      int c1 = c0 | (1 << a);
      t.edgeCorners[size_t(e)] = {uint8_t(c0), uint8_t(c1)};
      t.edgeAxis[size_t(e)] = uint8_t(a);
      edgeOf[c0][c1] = edgeOf[c1][c0] = e;
    }
  // Faces holding each edge, as bits 2 * axis + side.
  int edgeFaces[12];
  for (int e = 0; e < 12; ++e) {
    int c0 = t.edgeCorners[size_t(e)][0], c1 = t.edgeCorners[size_t(e)][1];
    edgeFaces[e] = 0;
    for (int a = 0; a < 3; ++a)
      if (((c0 >> a) & 1) == ((c1 >> a) & 1)) edgeFaces[e] |= 1 << (2 * a + ((c0 >> a) & 1));
  }
  // Faces: corners in counter-clockwise order seen from outside the cube.
  int faces[6][4];
  for (int a = 0, f = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side, ++f) {
      int u = (a + 1) % 3, w = (a + 2) % 3;
      int base = side << a;
      int ring[4] = {base, base | (1 << u), base | (1 << u) | (1 << w), base | (1 << w)};
      glm::vec3 n(0.0f);
      n[a] = side ? 1.0f : -1.0f;
      glm::vec3 cr = glm::cross(cornerPos(ring[1]) - cornerPos(ring[0]), cornerPos(ring[2]) - cornerPos(ring[1]));
      bool ccw = glm::dot(cr, n) > 0.0f;
      for (int i = 0; i < 4; ++i) faces[f][i] = ccw ? ring[i] : ring[3 - i];
    }
  bool flip = false;
  for (int pass = 0; pass < 2; ++pass) {
    for (int mask = 0; mask < 256; ++mask) {
      auto in = [&](int c) { return (mask >> c) & 1; };
      int next[12];
      for (int& n : next) n = -1;
      for (auto& face : faces)
        for (int i = 0; i < 4; ++i) {
          int v0 = face[i], v1 = face[(i + 1) % 4];
          if (in(v0) || !in(v1)) continue;  // run of inside corners starts at v1
          for (int s = 1; s <= 4; ++s) {
            int j = (i + s) % 4;
            int a = face[j], b = face[(j + 1) % 4];
            if (in(a) && !in(b)) {
              next[edgeOf[v0][v1]] = edgeOf[a][b];
              break;
            }
          }
        }
      bool used[12] = {};
      int nt = 0;
      auto& tri = t.triangles[size_t(mask)];
      for (int e = 0; e < 12; ++e) {
        if (next[e] < 0 || used[e]) continue;
        std::vector<int> loop;
        for (int x = e; !used[x]; x = next[x]) {
          used[x] = true;
          loop.push_back(x);
        }
        // Fan from the first apex whose diagonals all join edges on no common
        // face. A diagonal between two edges of one face (possible when the
        // loop crosses an ambiguous face twice) would also be drawable by the
        // neighbour across that face: both cells could emit it, even the same
        // triangle lying flat in the face with opposite windings, and the edge
        // would get four triangles. Such an apex exists for every case (the
        // table test checks it); it also keeps every triangle out of a face
        // plane, so none is degenerate.
        const size_t n = loop.size();
        size_t apex = 0;
        for (size_t r = 0; r < n; ++r) {
          bool ok = true;
          for (size_t k = 2; k + 1 < n && ok; ++k) ok = (edgeFaces[loop[r]] & edgeFaces[loop[(r + k) % n]]) == 0;
          if (ok) {
            apex = r;
            break;
          }
        }
        for (size_t k = 1; k + 1 < n; ++k) {
          int a = loop[apex], b = loop[(apex + k) % n], c = loop[(apex + k + 1) % n];
          if (flip) std::swap(b, c);
          tri[size_t(3 * nt)] = uint8_t(a);
          tri[size_t(3 * nt + 1)] = uint8_t(b);
          tri[size_t(3 * nt + 2)] = uint8_t(c);
          ++nt;
        }
      }
      tri[size_t(3 * nt)] = 255;
      t.triangleCount[size_t(mask)] = uint8_t(nt);
    }
    if (pass == 1) break;
    // Calibrate the winding on the single-corner case: the normal must point
    // away from the inside corner 0, towards (1, 1, 1).
    const auto& tr = t.triangles[1];
    auto mid = [&](int e) { return 0.5f * (cornerPos(t.edgeCorners[size_t(e)][0]) + cornerPos(t.edgeCorners[size_t(e)][1])); };
    glm::vec3 n = glm::cross(mid(tr[1]) - mid(tr[0]), mid(tr[2]) - mid(tr[0]));
    if (glm::dot(n, glm::vec3(1.0f)) > 0.0f) break;
    flip = true;
  }
  return t;
}

}  // namespace

const MarchingCubesTable& marchingCubesTable() {
  static const MarchingCubesTable table = build();
  return table;
}

}  // namespace animorph
