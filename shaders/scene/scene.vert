// Every lit pass: positions and normals to the pass's camera space. uModelView and uNormalMatrix
// are composed in double on the CPU (camera-relative), so a scene far from the origin keeps its
// precision; uNormalMatrix is the inverse transpose, so non-uniform scale keeps normals normal.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;

uniform mat4 uModelView;
uniform mat4 uProjection;
uniform mat3 uNormalMatrix;

out vec3 vPosition;
out vec3 vNormal;

void main() {
  vec4 p = uModelView * vec4(aPosition, 1.0);
  vPosition = p.xyz;
  vNormal = uNormalMatrix * aNormal;
  gl_Position = uProjection * p;
}
