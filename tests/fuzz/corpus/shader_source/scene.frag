// Scene shading. Compiled per feature set (scene_render/scene_program.cpp prepends the defines):
//   ENGINE_EEVEE or ENGINE_WORKBENCH, HAS_SHADOWS, SHADOW_TAPS, HAS_REFLECTION, HAS_SUBSURFACE,
//   HAS_EMISSION, RADIANCE_ONLY (the ground as the reflection pass sees it: no specular),
//   MAX_LIGHTS, MAX_SHADOW_VIEWS.
// Everything is in the pass's camera space; light values are in Blender's units (sun: W/m^2 of
// irradiance; point/spot/area: W/sr of intensity), so the output is scene-referred radiance.
precision highp float;
precision highp sampler2DArray;
precision highp sampler2DArrayShadow;

const float PI = 3.14159265358979;

in vec3 vPosition;
in vec3 vNormal;
out vec4 fragColor;

// Principled BSDF inputs.
uniform vec3 uBaseColor;
uniform float uMetallic, uRoughness, uSpecular, uAlpha;
#ifdef HAS_SUBSURFACE
uniform float uSubsurface;
uniform vec3 uSubsurfaceColor, uSubsurfaceWrap;  // wrap per channel, from the radius
#endif
#ifdef HAS_EMISSION
uniform vec3 uEmission;  // colour x strength
#endif

uniform bool uOrthographic;
uniform bool uFlipFacing;     // the object's transform mirrors it, so GL's front faces are its back
uniform vec3 uWorldUp;        // world +Z in camera space
uniform mat3 uWorldFromCamera;
uniform vec3 uWorld;          // world colour x strength: the environment's radiance
uniform vec3 uGroundBounce;   // radiance of the lit ground seen from above (uWorld without a ground)

// Lights: 0 point, 1 sun, 2 spot, 3 area.
uniform int uLightCount;
uniform int uLightType[MAX_LIGHTS];
uniform vec3 uLightValue[MAX_LIGHTS];      // sun: irradiance; others: intensity, colour included
uniform vec3 uLightPosition[MAX_LIGHTS];
uniform vec3 uLightDirection[MAX_LIGHTS];  // the way the light travels
uniform vec4 uLightShape[MAX_LIGHTS];      // x: source size (radius, or tan(angle/2) for a sun),
                                           // y: spot cos(size/2), z: spot blend width, w: first shadow view or -1

#ifdef HAS_SHADOWS
uniform sampler2DArrayShadow uShadowDepth;  // same texture, compare mode on ...
uniform sampler2DArray uShadowRaw;          // ... and off (blocker search)
uniform mat4 uShadowMatrix[MAX_SHADOW_VIEWS];  // camera space -> (uv * w, depth * w, w)
uniform vec4 uShadowA[MAX_SHADOW_VIEWS];       // x: perspective?, y: near, z: far, w: light size (see shadow())
uniform vec4 uShadowB[MAX_SHADOW_VIEWS];       // x: half extent (ortho) or tan(fov/2), y: texel size in world at
                                               // distance 1 (perspective) or in total (ortho), z: texel in uv
#endif

#ifdef HAS_REFLECTION
uniform sampler2D uReflection;   // the ground's radiance from above, mipmapped
uniform vec3 uCameraFromGround;  // camera position minus the ground's centre (world axes)
uniform float uGroundHalfSize;
uniform float uReflectionLevels;
#endif

#ifdef ENGINE_WORKBENCH
uniform vec3 uWorkbenchShadowDirection;  // towards the light, camera space
#endif

// Taps on a golden-angle spiral (even for any count), turned per pixel by interleaved gradient
// noise: a few taps then give fine grain instead of contour bands. The turn depends only on the
// pixel, so the same scene gives the same bytes.
float pixel_angle() { return 6.2831853 * fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715)))); }

// Walking the spiral: each tap turns the previous direction by the golden angle (no sin/cos per tap).
const mat2 kGoldenTurn = mat2(-0.73736888, 0.67549029, -0.67549029, -0.73736888);
float spiral_radius(int i, int n) { return sqrt((float(i) + 0.5) / float(n)); }

#ifdef HAS_SHADOWS
float linear_depth(float d, vec4 a) { return a.x > 0.5 ? a.y * a.z / (a.z - d * (a.z - a.y)) : a.y + d * (a.z - a.y); }

// Percentage-closer soft shadows: a blocker search sizes the penumbra from the light's size
// (a sun's angle, a lamp's radius), then SHADOW_TAPS compare taps filter over it.
float shadow(int view, vec3 P, vec3 N, vec3 L) {
  vec4 a = uShadowA[view], b = uShadowB[view];
  vec4 s0 = uShadowMatrix[view] * vec4(P, 1.0);
  float texel_world = b.y * (a.x > 0.5 ? s0.w : 1.0);
  float cos_l = clamp(dot(N, L), 0.0, 1.0);
  vec4 s = uShadowMatrix[view] * vec4(P + N * texel_world * (0.5 + 1.5 * sqrt(1.0 - cos_l * cos_l)), 1.0);
  if (!(s.w > 0.0)) return 1.0;
  vec3 uvz = s.xyz / s.w;
  if (any(lessThan(uvz, vec3(0.0))) || any(greaterThan(uvz, vec3(1.0)))) return 1.0;
  float layer = float(view);
  float zr = linear_depth(uvz.z, a);
  float to_uv = a.x > 0.5 ? 1.0 / (2.0 * b.x * zr) : 1.0 / (2.0 * b.x);

  // Blocker search over the widest penumbra (radius) a blocker at the near plane could cast.
  float turn = pixel_angle();
  vec2 start = vec2(cos(turn), sin(turn));
  float search = clamp(0.5 * (zr - a.y) * a.w * (a.x > 0.5 ? 1.0 / max(a.y, 1e-3) : 1.0) * to_uv, 2.0 * b.z, 0.01);
  const int blocker_taps = SHADOW_TAPS / 2 > 4 ? SHADOW_TAPS / 2 : 4;
  float blockers = 0.0, blocker_depth = 0.0;
  vec2 dir = start;
  for (int i = 0; i < blocker_taps; ++i, dir = kGoldenTurn * dir) {
    float d = texture(uShadowRaw, vec3(uvz.xy + search * spiral_radius(i, blocker_taps) * dir, layer)).r;
    float zb = linear_depth(d, a);
    if (d < uvz.z) {
      blockers += 1.0;
      blocker_depth += zb;
    }
  }
  if (blockers == 0.0) return 1.0;
  // Every search tap blocked: deep in the umbra (the filter would not reach past the search area).
  if (blockers == float(blocker_taps)) return 0.0;
  float zb = blocker_depth / blockers;
  float penumbra = (zr - zb) * a.w * (a.x > 0.5 ? 1.0 / max(zb, 1e-6) : 1.0) * to_uv;  // full width
  float radius = clamp(0.5 * penumbra, 1.0 * b.z, 0.01);
  float lit = 0.0;
  dir = start;
  for (int i = 0; i < SHADOW_TAPS; ++i, dir = kGoldenTurn * dir)
    lit += texture(uShadowDepth, vec4(uvz.xy + radius * spiral_radius(i, SHADOW_TAPS) * dir, layer, uvz.z));
  return lit / float(SHADOW_TAPS);
}

// A point light has six views (+X -X +Y -Y +Z -Z in world axes); the direction picks one.
int shadow_view(int first, int type, vec3 P, vec3 light_position) {
  if (type != 0) return first;
  vec3 d = uWorldFromCamera * (P - light_position);
  vec3 m = abs(d);
  if (m.x >= m.y && m.x >= m.z) return first + (d.x > 0.0 ? 0 : 1);
  if (m.y >= m.z) return first + (d.y > 0.0 ? 2 : 3);
  return first + (d.z > 0.0 ? 4 : 5);
}
#endif

float D_ggx(float n_dot_h, float a) {
  float a2 = a * a;
  float d = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
  return a2 / (PI * d * d);
}

// Height-correlated Smith visibility, G / (4 n.l n.v).
float V_smith(float n_dot_v, float n_dot_l, float a) {
  float a2 = a * a;
  float gv = n_dot_l * sqrt(n_dot_v * n_dot_v * (1.0 - a2) + a2);
  float gl = n_dot_v * sqrt(n_dot_l * n_dot_l * (1.0 - a2) + a2);
  return 0.5 / max(gv + gl, 1e-8);
}

vec3 F_schlick(vec3 f0, float cos_theta) { return f0 + (1.0 - f0) * pow(1.0 - clamp(cos_theta, 0.0, 1.0), 5.0); }

// Split-sum environment BRDF, Karis' analytic fit (no lookup table needed).
vec3 env_brdf(vec3 f0, float roughness, float n_dot_v) {
  const vec4 c0 = vec4(-1.0, -0.0275, -0.572, 0.022);
  const vec4 c1 = vec4(1.0, 0.0425, 1.04, -0.04);
  vec4 r = roughness * c0 + c1;
  float a004 = min(r.x * r.x, exp2(-9.28 * n_dot_v)) * r.x + r.y;
  vec2 ab = vec2(-1.04, 1.04) * a004 + r.zw;
  return f0 * ab.x + ab.y;
}

vec3 environment(vec3 R, float roughness) {
  float up = dot(R, uWorldUp);
  vec3 below = uGroundBounce;
#ifdef HAS_REFLECTION
  // The reflected ray meets the ground plane: read the ground's radiance there, blurred with distance
  // and roughness (cone footprint -> mip level).
  vec3 Rw = uWorldFromCamera * R;
  vec3 origin = uCameraFromGround + uWorldFromCamera * vPosition;
  if (Rw.z < -1e-4 && origin.z > 0.0) {
    float t = -origin.z / Rw.z;
    vec2 hit = origin.xy + t * Rw.xy;
    vec2 uv = hit / (2.0 * uGroundHalfSize) + 0.5;
    if (all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)))) {
      float footprint = max(roughness * roughness * t * 2.0, 1e-6) / (2.0 * uGroundHalfSize);
      float lod = clamp(log2(footprint * exp2(uReflectionLevels)) , 0.0, uReflectionLevels);
      below = textureLod(uReflection, uv, lod).rgb;
    } else {
      below = uWorld;
    }
  }
#endif
  // Rougher lobes see both hemispheres; blend across the horizon by the lobe's width.
  float w = max(roughness, 0.02);
  return mix(below, uWorld, smoothstep(-w, w, up));
}

void main() {
  vec3 V = uOrthographic ? vec3(0.0, 0.0, 1.0) : normalize(-vPosition);
  float n_length = length(vNormal);
  vec3 N = n_length > 1e-20 ? vNormal / n_length : V;  // a zero normal (degenerate triangle) faces the viewer
  if (gl_FrontFacing == uFlipFacing) N = -N;          // back faces are lit as Blender lights them

#ifdef ENGINE_WORKBENCH
  // Studio lighting fixed to the camera (Blender's Workbench default): key, fill and rim lights,
  // a soft ambient, a white specular.
  const vec3 key = vec3(-0.4082, 0.4082, 0.8165), fill = vec3(0.7071, -0.1414, 0.6928), rim = vec3(0.0, 0.6, -0.8);
  float light = 0.25 + 0.10 * dot(N, uWorldUp) + 0.60 * max(dot(N, key), 0.0) + 0.25 * max(dot(N, fill), 0.0) +
                0.20 * max(dot(N, rim), 0.0);
  float gloss = 1.0 - uRoughness;
  float highlight = (0.05 + 0.3 * gloss) * pow(max(dot(N, normalize(key + V)), 0.0), mix(8.0, 96.0, gloss));
  vec3 color = uBaseColor * light + highlight;
#ifdef HAS_SHADOWS
  // Blender's Workbench shadow: a fixed 50% darkening where the shadow light is blocked.
  float lit = dot(N, uWorkbenchShadowDirection) > 0.0 ? shadow(0, vPosition, N, uWorkbenchShadowDirection) : 1.0;
  color *= mix(0.5, 1.0, lit);
#endif
  fragColor = vec4(color, 1.0);
#else
  float n_dot_v = max(dot(N, V), 1e-4);
  float roughness = clamp(uRoughness, 0.0, 1.0);
  float alpha = max(roughness * roughness, 1e-3);
  vec3 albedo = uBaseColor;
#ifdef HAS_SUBSURFACE
  albedo = mix(uBaseColor, uSubsurfaceColor, uSubsurface);
#endif
  vec3 diffuse_color = albedo * (1.0 - uMetallic);
  vec3 f0 = mix(vec3(0.08 * uSpecular), uBaseColor, uMetallic);

  vec3 radiance = vec3(0.0);
  for (int i = 0; i < MAX_LIGHTS; ++i) {
    if (i >= uLightCount) break;
    int type = uLightType[i];
    vec4 shape = uLightShape[i];
    vec3 L, E;
    float source;  // angular size of the source seen from here (tan of half the angle)
    if (type == 1) {
      L = -uLightDirection[i];
      E = uLightValue[i];
      source = shape.x;
    } else {
      vec3 d = uLightPosition[i] - vPosition;
      float dist2 = dot(d, d);
      // A lamp is a sphere of its radius: a surface touching it gets a finite, not infinite, irradiance.
      float r2 = max(shape.x * shape.x, 1e-8);
      L = dist2 > 0.0 ? d * inversesqrt(dist2) : N;
      E = uLightValue[i] / max(dist2, r2);
      source = shape.x * inversesqrt(max(dist2, r2));
      float cos_emit = dot(-L, uLightDirection[i]);
      if (type == 2) E *= smoothstep(0.0, 1.0, (cos_emit - shape.y) / max(shape.z, 1e-6));
      if (type == 3) E *= max(cos_emit, 0.0);
    }
    float n_dot_l = dot(N, L);
#ifdef HAS_SUBSURFACE
    // Light that enters and scatters reaches past the terminator, reddest where the radius is largest.
    vec3 wrap = uSubsurfaceWrap;
    vec3 diffuse_term = max((vec3(n_dot_l) + wrap) / ((1.0 + wrap) * (1.0 + wrap)), 0.0);
    if (max(max(diffuse_term.r, diffuse_term.g), diffuse_term.b) <= 0.0) continue;
#else
    if (n_dot_l <= 0.0) continue;
    vec3 diffuse_term = vec3(n_dot_l);
#endif
    float visibility = 1.0;
#ifdef HAS_SHADOWS
    if (shape.w >= 0.0) visibility = shadow(shadow_view(int(shape.w), type, vPosition, uLightPosition[i]), vPosition, N, L);
#endif
    vec3 light = E * visibility;
    radiance += diffuse_color / PI * diffuse_term * light;
#ifndef RADIANCE_ONLY
    if (n_dot_l > 0.0) {
      // Karis' widening for a source of finite size, energy kept by the (a / a')^2 factor.
      float a_wide = min(alpha + 0.5 * source, 1.0);
      vec3 H = normalize(L + V);
      float spec = D_ggx(max(dot(N, H), 0.0), a_wide) * V_smith(n_dot_v, n_dot_l, a_wide) * (alpha * alpha) / (a_wide * a_wide);
      radiance += F_schlick(f0, dot(L, H)) * spec * n_dot_l * light;
    }
#endif
  }

  // The world: a uniform environment above, the lit ground below when there is one.
  float up = dot(N, uWorldUp);
  vec3 irradiance = mix(uGroundBounce, uWorld, 0.5 + 0.5 * up);
  radiance += diffuse_color * irradiance;
#ifndef RADIANCE_ONLY
  radiance += environment(reflect(-V, N), roughness) * env_brdf(f0, roughness, n_dot_v);
#endif
#ifdef HAS_EMISSION
  radiance += uEmission;
#endif
  fragColor = vec4(radiance, uAlpha);
#endif
}
