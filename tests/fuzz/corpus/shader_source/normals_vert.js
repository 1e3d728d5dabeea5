export default `#version 300 es

precision highp float;
precision highp int;

in vec4 aVertexPosition;
in vec4 aVertexNormal;

uniform mat4 uMeshToWorldMatrix;
uniform mat4 uMeshToWorldRotMatrix;
uniform mat4 uWorldToClipSpaceMatrix;

out vec4 vColor;

void main(void) {
    // the normal colour, computed once per vertex and interpolated across each triangle
    vec4 normal = uMeshToWorldRotMatrix * aVertexNormal;
    vColor = vec4(normalize(abs(normal.xyz)), 1.0);

    gl_Position = uWorldToClipSpaceMatrix * uMeshToWorldMatrix * aVertexPosition;
}
`;
