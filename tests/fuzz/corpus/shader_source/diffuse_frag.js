export default `#version 300 es

precision highp float;
precision highp int;

uniform vec4 uAmbientColor;
uniform vec4 uDiffuseColor;
uniform vec3 uLightPosition;
uniform vec4 uLightColor;

in vec4 vPosition;
in vec4 vNormal;
out vec4 fragColor;

void main(void) {
    vec3 N = normalize(vNormal.xyz);
    vec3 L = normalize(uLightPosition - vPosition.xyz);

    // D = k_d * max(0, N.L)
    vec4 diffuse = uDiffuseColor * uLightColor * max(0.0, dot(N, L));

    fragColor = uAmbientColor + diffuse;
}
`;
