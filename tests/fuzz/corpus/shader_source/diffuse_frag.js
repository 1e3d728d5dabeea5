export default `#version 300 es

precision highp float;
precision highp int;

uniform vec4 uAmbientColor;
uniform vec4 uDiffuseColor;
uniform vec3 uLightPosition;
uniform vec4 uLightColor;

in vec3 vPosition;
in vec3 vNormal;
out vec4 fragColor;

void main(void) {
    vec3 N = normalize(vNormal);
    vec3 L = normalize(uLightPosition - vPosition);

    // D = k_d * max(0, N.L)
    vec4 diffuse = uDiffuseColor * uLightColor * max(0.0, dot(N, L));

    fragColor = uAmbientColor + diffuse;
}
`;
