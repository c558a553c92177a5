"""Distances between two triangle meshes for the CLI tests, in plain Python (no numpy on a fresh
machine): reading a binary PLY that bake wrote, and the largest distance from the vertices of one
mesh to the surface of the other (a one-sided Hausdorff distance over the vertices), found through
a uniform grid so that a few thousand vertices take well under a second."""
import math
import struct


def read_ply_mesh(path):
    """(positions, triangles) of a binary little-endian PLY: the first three floats of each vertex
    and the vertex triples of its faces (a uchar count of 3, then three 32-bit indices). Raises
    ValueError naming the path when the file is not that."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.find(b"end_header\n")
    if not data.startswith(b"ply\nformat binary_little_endian 1.0\n") or end < 0:
        raise ValueError(f"{path}: not a binary little-endian PLY")
    sizes = {"char": 1, "uchar": 1, "short": 2, "ushort": 2, "int": 4, "uint": 4, "float": 4, "double": 8}
    verts = faces = None
    stride = floats_first = 0  # bytes per vertex; how many float properties lead it
    leading = True
    index_type = None
    for line in data[:end].decode("ascii").split("\n"):
        words = line.split()
        if line.startswith("element vertex "):
            verts = int(words[2])
        elif line.startswith("element face "):
            faces = int(words[2])
        elif line.startswith("property list ") and faces is not None:
            index_type = words[3]
        elif line.startswith("property ") and faces is None:
            stride += sizes.get(words[1], 0)
            leading = leading and words[1] == "float"
            floats_first += leading
    if verts is None or faces is None or floats_first < 3 or index_type not in ("int", "uint", "int32", "uint32"):
        raise ValueError(f"{path}: header has {verts} vertices ({floats_first} leading floats), {faces} faces of {index_type}")
    body = end + len("end_header\n")
    positions = [struct.unpack_from("<3f", data, body + i * stride) for i in range(verts)]
    code = "<B3I" if index_type.startswith("u") else "<B3i"
    triangles = []
    for n, a, b, c in struct.iter_unpack(code, data[body + verts * stride:body + verts * stride + faces * 13]):
        if n != 3 or max(a, b, c) >= verts or min(a, b, c) < 0:
            raise ValueError(f"{path}: face {len(triangles)} is not a triangle of valid indices")
        triangles.append((a, b, c))
    return positions, triangles


def median_edge_length(positions, triangles):
    """The median length of the triangles' edges: the mesh's own scale (about a grid cell for a
    marching-cubes mesh)."""
    lengths = sorted(math.dist(positions[t[k]], positions[t[(k + 1) % 3]]) for t in triangles for k in range(3))
    return lengths[len(lengths) // 2] if lengths else 0.0


def _sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def point_triangle_distance(p, a, b, c):
    """Distance from point p to the triangle abc (its closest point by the Voronoi regions of the
    vertices, edges and face; Ericson, Real-Time Collision Detection, 5.1.5)."""
    ab, ac, ap = _sub(b, a), _sub(c, a), _sub(p, a)
    d1, d2 = _dot(ab, ap), _dot(ac, ap)
    if d1 <= 0 and d2 <= 0:
        return math.dist(p, a)
    bp = _sub(p, b)
    d3, d4 = _dot(ab, bp), _dot(ac, bp)
    if d3 >= 0 and d4 <= d3:
        return math.dist(p, b)
    vc = d1 * d4 - d3 * d2
    if vc <= 0 and d1 >= 0 and d3 <= 0:
        v = d1 / (d1 - d3)
        return math.dist(p, (a[0] + v * ab[0], a[1] + v * ab[1], a[2] + v * ab[2]))
    cp = _sub(p, c)
    d5, d6 = _dot(ab, cp), _dot(ac, cp)
    if d6 >= 0 and d5 <= d6:
        return math.dist(p, c)
    vb = d5 * d2 - d1 * d6
    if vb <= 0 and d2 >= 0 and d6 <= 0:
        w = d2 / (d2 - d6)
        return math.dist(p, (a[0] + w * ac[0], a[1] + w * ac[1], a[2] + w * ac[2]))
    va = d3 * d6 - d5 * d4
    if va <= 0 and (d4 - d3) >= 0 and (d5 - d6) >= 0:
        w = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        return math.dist(p, (b[0] + w * (c[0] - b[0]), b[1] + w * (c[1] - b[1]), b[2] + w * (c[2] - b[2])))
    denom = va + vb + vc
    if denom == 0:  # a degenerate triangle: its closest vertex is near enough
        return min(math.dist(p, a), math.dist(p, b), math.dist(p, c))
    v, w = vb / denom, vc / denom
    q = (a[0] + ab[0] * v + ac[0] * w, a[1] + ab[1] * v + ac[1] * w, a[2] + ab[2] * v + ac[2] * w)
    return math.dist(p, q)


class SurfaceGrid:
    """The triangles of a mesh binned in cubes of side `cell`: distance queries from a point up to
    `cell` look at the 27 cubes around it."""

    def __init__(self, positions, triangles, cell):
        self.positions, self.triangles, self.cell = positions, triangles, cell
        self.bins = {}
        for t, tri in enumerate(triangles):
            pts = [positions[i] for i in tri]
            lo = [math.floor(min(p[k] for p in pts) / cell) for k in range(3)]
            hi = [math.floor(max(p[k] for p in pts) / cell) for k in range(3)]
            for x in range(lo[0], hi[0] + 1):
                for y in range(lo[1], hi[1] + 1):
                    for z in range(lo[2], hi[2] + 1):
                        self.bins.setdefault((x, y, z), []).append(t)

    def _nearest(self, p, keys, seen, best):
        for key in keys:
            for t in self.bins.get(key, ()):
                if t not in seen:
                    seen.add(t)
                    a, b, c = (self.positions[i] for i in self.triangles[t])
                    best = min(best, point_triangle_distance(p, a, b, c))
        return best

    def distance(self, p, enough=0.0):
        """Distance from p to the surface, exact up to `cell` (math.inf when farther). A distance
        found within `enough` among the triangles of p's own cube is returned at once: an upper
        bound of the exact one, which is all a check against a bound of `enough` needs."""
        key = tuple(math.floor(p[k] / self.cell) for k in range(3))
        seen = set()
        best = self._nearest(p, (key,), seen, math.inf)
        if best <= enough:
            return best
        around = [(key[0] + dx, key[1] + dy, key[2] + dz) for dx in (-1, 0, 1) for dy in (-1, 0, 1) for dz in (-1, 0, 1)]
        best = self._nearest(p, around, seen, best)
        return best if best <= self.cell else math.inf


def farthest_vertex(from_positions, to_grid, bound):
    """(largest distance, that vertex) from the vertices `from_positions` to the surface in
    `to_grid`, exact where it exceeds `bound` (below it, an upper bound); math.inf when some vertex
    is farther than the grid's cell."""
    worst, where = 0.0, None
    for p in from_positions:
        d = to_grid.distance(p, bound)
        if d > worst:
            worst, where = d, p
    return worst, where
