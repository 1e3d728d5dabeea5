export default `#version 300 es

precision highp float;
precision highp int;

in vec4 aVertexPosition;
in vec4 aVertexNormal;

uniform mat4 uMeshToWorldMatrix;
uniform mat4 uMeshToWorldRotMatrix;
uniform mat4 uWorldToClipSpaceMatrix;

out vec4 vNormal;

void main(void) {
    // the world-space normal, interpolated across each triangle
    vNormal = uMeshToWorldRotMatrix * aVertexNormal;

    gl_Position = uWorldToClipSpaceMatrix * uMeshToWorldMatrix * aVertexPosition;
}
`;
