#pragma once
// Meshes as a scene places them: in Blender's Z-up object space, with the shading the object asks
// for. Built-ins are Blender's own primitives at their default sizes, so a scene copied from
// Blender (scale 0.8 on the UV sphere, a monkey at size 2) comes out the same size.
//
// | Built-in   | Blender primitive                      | Size                          |
// |------------|----------------------------------------|-------------------------------|
// | suzanne    | Add > Mesh > Monkey                    | 2.73 m wide (size 2)          |
// | uv_sphere  | Add > Mesh > UV Sphere, 32 x 16        | radius 1                      |
// | cube       | Add > Mesh > Cube                      | 2 m edge                      |
// | plane      | Add > Mesh > Plane                     | 2 m edge, normal +Z           |
// | teapot     | the homework's teapot (Y-up OBJ)       | 3.5 m tall                    |
// | bunny      | the homework's bunny (Y-up OBJ)        | 3.5 m tall                    |
#include <string>
#include <vector>

#include "core/expected.h"
#include "scene/mesh.h"
#include "scene/scene_description.h"

namespace shadelab::scene {

std::vector<std::string> builtin_scene_mesh_names();
bool is_builtin_scene_mesh(const std::string& name);
Expected<Mesh> builtin_scene_mesh(const std::string& name);

// Turns a mesh read from a file of `extension`'s format into the Z-up scene space (a no-op for
// formats that are Z-up already).
void to_scene_space(Mesh& mesh, const std::string& extension);

// Flat: every corner takes its triangle's normal. Smooth: the file's normals if it has them
// (Blender keeps custom normals), else area-weighted smooth normals.
void apply_shading(Mesh& mesh, Shading shading);

}  // namespace shadelab::scene
