#pragma once
// Wavefront OBJ, read as the homework page's loader reads it (web/js/obj.js): `v` and `vn`
// numbers parsed as doubles and stored as floats (JavaScript's Number, then a Float32Array), so
// the server draws the vertices the student's browser draws, bit for bit; `f` polygons in file
// order, each corner's position and normal (`v`, `v/vt`, `v//vn`, `v/vt/vn`; negative indices
// count back from the latest vertex). Points (`p`) and lines (`l`) are counted, not drawn. Every
// other statement (`vt`, `o`, `g`, `s`, `usemtl`, `mtllib`, comments) is skipped: a mesh upload
// is one file, and materials do not change how the homework shades it.
//
// ShadeLab reads OBJ itself rather than through assimp: assimp 5.2.5's OBJ reader crashes on
// crafted files (docs/reliability.md), and its fast_atof rounds about one coordinate in twenty
// of the built-in bunny one float step away from what the browser parses.
#include <string>
#include <string_view>

#include "core/expected.h"
#include "scene/indexed_mesh.h"
#include "scene/mesh.h"

namespace shadelab::scene {

// Errors: mesh_parse_failed (a malformed statement, with its line), mesh_invalid (an index of a
// vertex or normal the file does not have, or a non-finite number, with its line),
// mesh_too_large (more triangles than limits.max_triangles, found before they are stored).
// When any corner names a normal, every corner is a vertex of its own in the result (a corner
// without one has a zero normal, computed later); otherwise the positions are shared.
Expected<IndexedMesh> read_obj(std::string_view bytes, const std::string& name, const MeshLimits& limits);

}  // namespace shadelab::scene
