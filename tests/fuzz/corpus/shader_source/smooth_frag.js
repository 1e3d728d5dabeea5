export default `#version 300 es

precision highp float;
precision highp int;

in vec4 vNormal;
out vec4 fragColor;

void main(void) {
    // the interpolated normal's direction as a colour, per fragment
    fragColor = vec4(normalize(abs(vNormal.xyz)), 1.0);
}
`;
