export default `#version 300 es

precision highp float;
precision highp int;

flat in vec4 vNormal;
out vec4 fragColor;

void main(void) {
    // the normal's direction as a colour
    fragColor = vec4(normalize(abs(vNormal.xyz)), 1.0);
}
`;
