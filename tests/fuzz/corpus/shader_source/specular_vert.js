export default `#version 300 es

precision highp float;
precision highp int;

in vec4 aVertexPosition;
in vec4 aVertexNormal;

uniform mat4 uMeshToWorldMatrix;
uniform mat4 uMeshToWorldRotMatrix;
uniform mat4 uWorldToClipSpaceMatrix;

out vec4 vPosition;
out vec4 vNormal;

void main(void) {
    // world space normal and position; world space is camera space here (the eye is at the origin)
    vNormal = uMeshToWorldRotMatrix * aVertexNormal;
    vPosition = uMeshToWorldMatrix * aVertexPosition;
    gl_Position = uWorldToClipSpaceMatrix * vPosition;
}
`;
