#pragma once
// Which passes and shader features a scene calls for, decided from the description alone (no GL),
// so "simulate only what the scene needs" is a pure function with its own tests.
//
// | Pass / feature     | Runs when                                                                  |
// |--------------------|----------------------------------------------------------------------------|
// | shadow (pass)      | Eevee: a light with castShadow and power > 0, and a drawn object to cast;  |
// |                    | Workbench: render.workbenchShadows and a drawn object                      |
// | reflection (pass)  | Eevee: a ground and a drawn glossy object (metallic > 0, or specular > 0   |
// |                    | with roughness < 0.5); the ground's lit radiance, seen by reflected rays   |
// | main (pass)        | always: the objects and the ground, lit                                     |
// | transparency       | Eevee: an object with alpha < 1 (drawn after the opaque ones, blended)     |
// | subsurface         | Eevee: an object or the ground with subsurface > 0 (shader variant)         |
// | emission           | Eevee: a material with emission x strength > 0 (shader variant)             |
// | view (pass)        | always: MSAA resolve and the view transform to display values              |
// | framing (pass)     | render.framing: an object-id pass, plus a guard-band pass for any object   |
// |                    | whose projection leaves the frame                                          |
#include <string>
#include <vector>

#include "scene/scene_description.h"

namespace shadelab::scene {

struct PassPlan {
  std::vector<int> drawn_objects;   // indices of objects with a non-zero scale and some triangles' worth of size
  std::vector<int> shadow_lights;   // lights that get a shadow map (Eevee), in scene order
  bool shadows = false;
  bool reflection = false;
  bool transparency = false;
  bool subsurface = false;
  bool emission = false;
  bool framing = false;

  std::vector<std::string> features() const;  // shader features compiled in, for the report
};

bool is_glossy(const Material& m);
PassPlan plan_passes(const SceneDescription& scene);

}  // namespace shadelab::scene
