#pragma once
// Catch2 checks that a polygonised mesh is a closed 2-manifold: no boundary,
// non-manifold or misoriented edges, no non-manifold vertices, no degenerate
// triangles. Shared by the CPU and GPU polygoniser tests.
#include <string>

#include "core/field/field_program.h"
#include "core/poly/mesh.h"

namespace animorph::test {

// What keeps m from being a closed 2-manifold, as "N boundary edges, N misoriented edges, ..."
// (only the kinds found); empty when m is one. tests/core/mesh_checks.cpp shows it bad meshes.
std::string closedManifoldDefects(const TriangleMesh& m);

// Catch2 CHECK that closedManifoldDefects(m) is empty (the defects are printed when not).
void requireClosedManifold(const TriangleMesh& m);

// The volume of program polygonised over box at resolution (the mesh required watertight).
double polygonisedVolume(const FieldProgram& program, const Bounds& box, int resolution);

}  // namespace animorph::test
