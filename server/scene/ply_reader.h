#pragma once
// PLY (Greg Turk's polygon file format, as Blender, MeshLab and the Stanford scans write it):
// ASCII, binary little-endian and binary big-endian. ShadeLab reads it itself rather than through
// assimp, whose 5.2.5 binary PLY reader crashes on crafted headers (docs/reliability.md); the
// format is a header and fixed-layout records, small enough to read with every bound checked.
//
// Read: the `vertex` element's x, y, z (and nx, ny, nz when all three are present) and the
// `face` element's `vertex_indices` (or `vertex_index`) list. Every other element and property
// (colours, texture coordinates, edges, materials) is parsed and skipped.
#include <string>
#include <string_view>

#include "core/expected.h"
#include "scene/indexed_mesh.h"

namespace shadelab::scene {

// Errors: mesh_parse_failed, with the header line or the element and record where reading
// stopped, and why.
Expected<IndexedMesh> read_ply(std::string_view bytes, const std::string& name);

}  // namespace shadelab::scene
