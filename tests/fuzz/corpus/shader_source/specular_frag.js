export default `#version 300 es

precision highp float;
precision highp int;

uniform vec4 uAmbientColor;
uniform vec4 uDiffuseColor;
uniform vec4 uSpecularColor;
uniform vec3 uLightPosition;
uniform vec4 uLightColor;

in vec3 vPosition;
in vec3 vNormal;
out vec4 fragColor;

void main(void) {
    float specularAlpha = 6.0;

    vec3 N = normalize(vNormal);
    vec3 L = normalize(uLightPosition - vPosition);
    float NdotL = dot(N, L);

    // D = k_d * max(0, N.L)
    vec4 color = uAmbientColor + uDiffuseColor * uLightColor * max(0.0, NdotL);

    // S = k_s * max(0, V.R)^alpha, only on the lit side; the eye is at the origin
    if (NdotL > 0.0) {
        vec3 V = normalize(-vPosition);
        vec3 R = reflect(-L, N);
        color += uSpecularColor * uLightColor * pow(max(0.0, dot(V, R)), specularAlpha);
    }
    fragColor = color;
}
`;
