#pragma once
// Blender's conventions, so numbers copied from Blender's sidebar mean the same thing here.
//
// | Quantity        | Blender                                   | Here                               |
// |-----------------|-------------------------------------------|------------------------------------|
// | World axes      | Z up, -Y towards a front view             | same (scene space is Blender's)    |
// | Rotation        | Euler XYZ in degrees: R = Rz * Ry * Rx    | same, evaluated in double          |
// | Camera          | looks down its local -Z, +Y up            | same; view = inverse(T * R)        |
// | Lens            | focal length (mm) over sensor width (mm)  | tan(fov/2) = sensor / (2 lens)     |
// | Sensor fit auto | sensor spans the image's larger side      | same                               |
// | OBJ / glTF file | Y up, -Z forward; importer maps to Z up   | (x, y, z)file -> (x, -z, y)scene   |
// | STL / PLY file  | Z up already                              | unchanged                          |
//
// GL's view space is the camera's local frame, so the only axis change is the file import above.
#include <string>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace shadelab::scene {

// Blender's XYZ Euler (degrees) as a rotation matrix: X is applied first.
glm::dmat3 euler_xyz_degrees(const glm::dvec3& degrees);

// The rotation that points a camera (or light) at `target` as Blender's Track To constraint does
// (track -Z, up Y): local -Z towards the target, local +Y as close to world +Z as it can be.
glm::dmat3 look_at_rotation(const glm::dvec3& from, const glm::dvec3& target);

// Object placement: T * R * S.
glm::dmat4 object_matrix(const glm::dvec3& location, const glm::dmat3& rotation, const glm::dvec3& scale);

// Whether a mesh file's format is Y-up (OBJ, glTF, FBX, ...) and so is turned to Z-up on import.
bool format_is_y_up(const std::string& extension);
// (x, y, z) in a Y-up file -> (x, -z, y) in the Z-up scene, as Blender's OBJ and glTF importers do.
inline glm::dvec3 y_up_to_z_up(const glm::dvec3& v) { return {v.x, -v.z, v.y}; }

enum class SensorFit { automatic, horizontal, vertical };

// Half-extents of the image plane at distance 1 (perspective: tan of the half field of view) or in
// world units (orthographic: half the ortho scale along the fitted side).
struct ImagePlane {
  double half_width = 1, half_height = 1;
};
ImagePlane perspective_plane(double lens_mm, double sensor_mm, SensorFit fit, int width, int height);
ImagePlane orthographic_plane(double ortho_scale, SensorFit fit, int width, int height);

}  // namespace shadelab::scene
