// Scene-referred linear radiance to display values: Blender's Standard (the sRGB transfer
// function, clipped) or Filmic (OCIO's tables baked by image/view_transform.cpp).
precision highp float;
precision highp sampler3D;
in vec2 vUv;
uniform sampler2D uRadiance;
#ifdef VIEW_FILMIC
uniform sampler3D uFilmicCube;   // log2-allocated linear -> Filmic Log
uniform sampler2D uFilmicCurve;  // Filmic Log -> display, one row
uniform vec2 uLog2Range;         // [min, max] of the cube's log2 allocation
uniform float uCubeSize, uCurveSize;
#endif
out vec4 fragColor;

vec3 srgb_encode(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

void main() {
  vec3 radiance = texture(uRadiance, vUv).rgb;
  // A NaN never reaches the image: it shows as black, as Blender's compositor does.
  radiance = mix(radiance, vec3(0.0), vec3(isnan(radiance)));
  radiance = max(radiance, vec3(0.0));
#ifdef VIEW_FILMIC
  vec3 u = clamp((log2(max(radiance, vec3(1e-10))) - uLog2Range.x) / (uLog2Range.y - uLog2Range.x), 0.0, 1.0);
  // Sample the cube's own grid points at texel centres.
  vec3 logc = texture(uFilmicCube, (u * (uCubeSize - 1.0) + 0.5) / uCubeSize).rgb;
  vec3 t = (clamp(logc, 0.0, 1.0) * (uCurveSize - 1.0) + 0.5) / uCurveSize;
  fragColor = vec4(texture(uFilmicCurve, vec2(t.r, 0.5)).r, texture(uFilmicCurve, vec2(t.g, 0.5)).g,
                   texture(uFilmicCurve, vec2(t.b, 0.5)).b, 1.0);
#else
  fragColor = vec4(srgb_encode(radiance), 1.0);
#endif
}
