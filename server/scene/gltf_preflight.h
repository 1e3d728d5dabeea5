#pragma once
// A glTF 2.0 upload (.gltf, or the binary .glb container) checked before assimp reads it: every
// size the file declares must fit in the bytes it holds. assimp allocates what a file declares:
// a 672-byte GLB had it ask for 2.9 GB (tests/fuzz/regressions/mesh_loader/oom-fda11aa1…). After
// this check, what assimp allocates is bounded by the upload's size.
//
// Checked: the GLB header and chunk lengths; the JSON (strict); asset.version 2.x; each buffer
// held by the file (the GLB's BIN chunk or a base64 `data:` URI; any other URI names another
// file, which an upload is not allowed to read) and no longer than what holds it; each buffer
// view inside its buffer; each accessor's elements inside its view, and no more of them than
// three per triangle of the limit; sparse accessors likewise.
#include <string>
#include <string_view>

#include "core/expected.h"
#include "scene/mesh.h"

namespace shadelab::scene {

// `binary`: the bytes are a GLB container, else glTF JSON. Errors: mesh_parse_failed naming the
// field (`bufferViews[2].byteLength: ...`) or mesh_too_large (an accessor over the limit).
Status check_gltf(std::string_view bytes, bool binary, const std::string& name, const MeshLimits& limits);

}  // namespace shadelab::scene
