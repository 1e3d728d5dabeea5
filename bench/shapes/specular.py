"""The specular checkpoint's fragment stage written in five shapes, as students write it (and a
sixth held out), and the mistakes typed into each (bench/shapes_bench.py). Written here for the harness, not taken from any
student: the shapes are the ones issue 79 names.

A shape is the body of `main` (and any helpers) between the reference's declarations and the
module's end. A mistake is one or more (old, new) replacements of text that occurs once in the
shape; `group` says whether it changes something the program computes or leaves something out.
"""

REFERENCE = """void main(void) {
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
}"""

# A tutorial's names and order: lightDir, reflectDir, spec, the guard on the clamped diffuse.
TUTORIAL = """void main(void) {
    float specularAlpha = 6.0;
    vec3 norm = normalize(vNormal);
    vec3 lightDir = normalize(uLightPosition - vPosition);
    float diff = max(dot(norm, lightDir), 0.0);
    vec4 color = uAmbientColor + diff * uDiffuseColor * uLightColor;
    if (diff > 0.0) {
        vec3 viewDir = normalize(-vPosition);
        vec3 reflectDir = reflect(-lightDir, norm);
        float spec = pow(max(dot(viewDir, reflectDir), 0.0), specularAlpha);
        color += spec * uSpecularColor * uLightColor;
    }
    fragColor = color;
}"""

# Coefficient locals, each term added to fragColor with +=, R = -reflect(L, N): the shape of a
# real student's program (written here from that description).
COEFFICIENTS = """void main(void) {
    float specularAlpha = 6.0;
    vec3 N = normalize(vNormal);
    vec3 L = normalize(uLightPosition - vPosition);
    vec3 V = normalize(-vPosition);
    vec3 R = -reflect(L, N);

    float coeffDiffuse = max(dot(N, L), 0.0);
    float coeffSpecular = 0.0;
    if (coeffDiffuse > 0.0) {
        coeffSpecular = pow(max(dot(R, V), 0.0), specularAlpha);
    }

    fragColor = uAmbientColor;
    fragColor += coeffDiffuse * uDiffuseColor * uLightColor;
    fragColor += coeffSpecular * uSpecularColor * uLightColor;
}"""

# The guard as arithmetic: a multiplied max(sign(N.L), 0), one expression for the colour.
ARITHMETIC_GUARD = """void main(void) {
    float specularAlpha = 6.0;
    vec3 n = normalize(vNormal);
    vec3 l = normalize(uLightPosition - vPosition);
    vec3 v = normalize(-vPosition);
    vec3 r = reflect(-l, n);
    float lambert = max(dot(n, l), 0.0);
    float lit = max(sign(dot(n, l)), 0.0);
    float phong = lit * pow(max(dot(v, r), 0.0), specularAlpha);
    fragColor = uAmbientColor + lambert * uDiffuseColor * uLightColor + phong * uSpecularColor * uLightColor;
}"""

# Each term in a helper function, the guard an early return.
HELPERS = """vec4 diffuseTerm(vec3 n, vec3 l) {
    return uDiffuseColor * uLightColor * max(dot(n, l), 0.0);
}

vec4 specularTerm(vec3 n, vec3 l, vec3 v) {
    float specularAlpha = 6.0;
    if (dot(n, l) <= 0.0) {
        return vec4(0.0);
    }
    vec3 r = reflect(-l, n);
    return uSpecularColor * uLightColor * pow(max(dot(v, r), 0.0), specularAlpha);
}

void main(void) {
    vec3 n = normalize(vNormal);
    vec3 l = normalize(uLightPosition - vPosition);
    vec3 v = normalize(-vPosition);
    fragColor = uAmbientColor + diffuseTerm(n, l) + specularTerm(n, l, v);
}"""

# Held out: written after the search's rules were, by the same hands but never read while writing
# them, so its figures are a check on the five above (bench/shapes_bench.py runs it only when
# named). The guard by step(), a const exponent, a term in a vec4 of its own, other names.
STEP_GUARD = """void main(void) {
    const float shininess = 6.0;
    vec3 normal = normalize(vNormal);
    vec3 toLight = normalize(uLightPosition - vPosition);
    vec3 toEye = normalize(-vPosition);
    vec3 mirrored = reflect(-toLight, normal);
    float cosTheta = dot(normal, toLight);
    float kd = max(cosTheta, 0.0);
    float ks = step(0.0, cosTheta) * pow(max(dot(mirrored, toEye), 0.0), shininess);
    vec4 ambient = uAmbientColor;
    vec4 diffuse = kd * uDiffuseColor * uLightColor;
    vec4 specular = ks * uSpecularColor * uLightColor;
    fragColor = ambient + diffuse + specular;
}"""

CHANGES, LEFT_OUT = "changes", "leaves out"

# Per shape: mistake name -> (group, [(old, new), ...]).
MISTAKES = {
    "reference": {
        "L not normalised": (CHANGES, [("vec3 L = normalize(uLightPosition - vPosition);", "vec3 L = uLightPosition - vPosition;")]),
        "L from the light": (CHANGES, [("uLightPosition - vPosition", "vPosition - uLightPosition")]),
        "V from the eye": (CHANGES, [("normalize(-vPosition)", "normalize(vPosition)")]),
        "R's sign": (CHANGES, [("reflect(-L, N)", "reflect(L, N)")]),
        "exponent changed": (CHANGES, [("specularAlpha = 6.0", "specularAlpha = 16.0")]),
        "V computed as L": (CHANGES, [("vec3 V = normalize(-vPosition);", "vec3 V = L;")]),
        "guard left out": (LEFT_OUT, [("if (NdotL > 0.0) {", "{")]),
        "light colour left out of the diffuse": (LEFT_OUT, [("uDiffuseColor * uLightColor * max", "uDiffuseColor * max")]),
        "light colour left out of the specular": (LEFT_OUT, [("uSpecularColor * uLightColor * pow", "uSpecularColor * pow")]),
        "max left out of the diffuse": (LEFT_OUT, [("max(0.0, NdotL)", "NdotL")]),
        "exponent left out": (LEFT_OUT, [("pow(max(0.0, dot(V, R)), specularAlpha)", "max(0.0, dot(V, R))")]),
        "ambient left out": (LEFT_OUT, [("uAmbientColor + uDiffuseColor", "uDiffuseColor")]),
        "specular term left out": (LEFT_OUT, [("        color += uSpecularColor * uLightColor * pow(max(0.0, dot(V, R)), specularAlpha);\n", "")]),
        "N not normalised": (LEFT_OUT, [("vec3 N = normalize(vNormal);", "vec3 N = vNormal;")]),
        "swizzle": (CHANGES, [("fragColor = color;", "fragColor = color.bgra;")]),
        "half vector": (CHANGES, [("vec3 R = reflect(-L, N);", "vec3 R = normalize(L + V);")]),
    },
    "tutorial": {
        "L not normalised": (CHANGES, [("vec3 lightDir = normalize(uLightPosition - vPosition);", "vec3 lightDir = uLightPosition - vPosition;")]),
        "L from the light": (CHANGES, [("uLightPosition - vPosition", "vPosition - uLightPosition")]),
        "V from the eye": (CHANGES, [("normalize(-vPosition)", "normalize(vPosition)")]),
        "R's sign": (CHANGES, [("reflect(-lightDir, norm)", "reflect(lightDir, norm)")]),
        "exponent changed": (CHANGES, [("specularAlpha = 6.0", "specularAlpha = 16.0")]),
        "V computed as L": (CHANGES, [("vec3 viewDir = normalize(-vPosition);", "vec3 viewDir = lightDir;")]),
        "guard left out": (LEFT_OUT, [("if (diff > 0.0) {", "{")]),
        "light colour left out of the diffuse": (LEFT_OUT, [("diff * uDiffuseColor * uLightColor", "diff * uDiffuseColor")]),
        "light colour left out of the specular": (LEFT_OUT, [("spec * uSpecularColor * uLightColor", "spec * uSpecularColor")]),
        "max left out of the diffuse": (LEFT_OUT, [("max(dot(norm, lightDir), 0.0)", "dot(norm, lightDir)")]),
        "exponent left out": (LEFT_OUT, [("pow(max(dot(viewDir, reflectDir), 0.0), specularAlpha)", "max(dot(viewDir, reflectDir), 0.0)")]),
        "ambient left out": (LEFT_OUT, [("uAmbientColor + diff", "diff")]),
        "specular term left out": (LEFT_OUT, [("        color += spec * uSpecularColor * uLightColor;\n", "")]),
        "N not normalised": (LEFT_OUT, [("vec3 norm = normalize(vNormal);", "vec3 norm = vNormal;")]),
        "swizzle": (CHANGES, [("fragColor = color;", "fragColor = color.bgra;")]),
        "half vector": (CHANGES, [("vec3 reflectDir = reflect(-lightDir, norm);", "vec3 reflectDir = normalize(lightDir + viewDir);")]),
    },
    "coefficients": {
        "L not normalised": (CHANGES, [("vec3 L = normalize(uLightPosition - vPosition);", "vec3 L = uLightPosition - vPosition;")]),
        "L from the light": (CHANGES, [("uLightPosition - vPosition", "vPosition - uLightPosition")]),
        "V from the eye": (CHANGES, [("normalize(-vPosition)", "normalize(vPosition)")]),
        "R's sign": (CHANGES, [("vec3 R = -reflect(L, N);", "vec3 R = reflect(L, N);")]),
        "exponent changed": (CHANGES, [("specularAlpha = 6.0", "specularAlpha = 16.0")]),
        "V computed as L": (CHANGES, [("vec3 V = normalize(-vPosition);", "vec3 V = L;")]),
        "guard left out": (LEFT_OUT, [("    if (coeffDiffuse > 0.0) {\n        coeffSpecular = pow(max(dot(R, V), 0.0), specularAlpha);\n    }\n",
                                       "    coeffSpecular = pow(max(dot(R, V), 0.0), specularAlpha);\n")]),
        "light colour left out of the diffuse": (LEFT_OUT, [("coeffDiffuse * uDiffuseColor * uLightColor", "coeffDiffuse * uDiffuseColor")]),
        "light colour left out of the specular": (LEFT_OUT, [("coeffSpecular * uSpecularColor * uLightColor", "coeffSpecular * uSpecularColor")]),
        "max left out of the diffuse": (LEFT_OUT, [("max(dot(N, L), 0.0)", "dot(N, L)")]),
        "exponent left out": (LEFT_OUT, [("pow(max(dot(R, V), 0.0), specularAlpha)", "max(dot(R, V), 0.0)")]),
        "ambient left out": (LEFT_OUT, [("    fragColor = uAmbientColor;\n    fragColor += coeffDiffuse", "    fragColor = coeffDiffuse")]),
        "specular term left out": (LEFT_OUT, [("    fragColor += coeffSpecular * uSpecularColor * uLightColor;\n", "")]),
        "N not normalised": (LEFT_OUT, [("vec3 N = normalize(vNormal);", "vec3 N = vNormal;")]),
        "swizzle": (CHANGES, [("fragColor = uAmbientColor;", "fragColor = uAmbientColor.bgra;")]),
        "half vector": (CHANGES, [("vec3 R = -reflect(L, N);", "vec3 R = normalize(L + V);")]),
    },
    "arithmetic guard": {
        "L not normalised": (CHANGES, [("vec3 l = normalize(uLightPosition - vPosition);", "vec3 l = uLightPosition - vPosition;")]),
        "L from the light": (CHANGES, [("uLightPosition - vPosition", "vPosition - uLightPosition")]),
        "V from the eye": (CHANGES, [("normalize(-vPosition)", "normalize(vPosition)")]),
        "R's sign": (CHANGES, [("reflect(-l, n)", "reflect(l, n)")]),
        "exponent changed": (CHANGES, [("specularAlpha = 6.0", "specularAlpha = 16.0")]),
        "V computed as L": (CHANGES, [("vec3 v = normalize(-vPosition);", "vec3 v = l;")]),
        "guard left out": (LEFT_OUT, [("float phong = lit * pow", "float phong = pow")]),
        "light colour left out of the diffuse": (LEFT_OUT, [("lambert * uDiffuseColor * uLightColor", "lambert * uDiffuseColor")]),
        "light colour left out of the specular": (LEFT_OUT, [("phong * uSpecularColor * uLightColor", "phong * uSpecularColor")]),
        "max left out of the diffuse": (LEFT_OUT, [("float lambert = max(dot(n, l), 0.0);", "float lambert = dot(n, l);")]),
        "exponent left out": (LEFT_OUT, [("pow(max(dot(v, r), 0.0), specularAlpha)", "max(dot(v, r), 0.0)")]),
        "ambient left out": (LEFT_OUT, [("fragColor = uAmbientColor + lambert", "fragColor = lambert")]),
        "specular term left out": (LEFT_OUT, [(" + phong * uSpecularColor * uLightColor;", ";")]),
        "N not normalised": (LEFT_OUT, [("vec3 n = normalize(vNormal);", "vec3 n = vNormal;")]),
        "swizzle": (CHANGES, [("fragColor = uAmbientColor + lambert", "fragColor = uAmbientColor.bgra + lambert")]),
        "half vector": (CHANGES, [("vec3 r = reflect(-l, n);", "vec3 r = normalize(l + v);")]),
    },
    "helpers": {
        "L not normalised": (CHANGES, [("vec3 l = normalize(uLightPosition - vPosition);", "vec3 l = uLightPosition - vPosition;")]),
        "L from the light": (CHANGES, [("uLightPosition - vPosition", "vPosition - uLightPosition")]),
        "V from the eye": (CHANGES, [("normalize(-vPosition)", "normalize(vPosition)")]),
        "R's sign": (CHANGES, [("reflect(-l, n)", "reflect(l, n)")]),
        "exponent changed": (CHANGES, [("specularAlpha = 6.0", "specularAlpha = 16.0")]),
        "V computed as L": (CHANGES, [("vec3 v = normalize(-vPosition);", "vec3 v = l;")]),
        "guard left out": (LEFT_OUT, [("    if (dot(n, l) <= 0.0) {\n        return vec4(0.0);\n    }\n", "")]),
        "light colour left out of the diffuse": (LEFT_OUT, [("return uDiffuseColor * uLightColor * max", "return uDiffuseColor * max")]),
        "light colour left out of the specular": (LEFT_OUT, [("return uSpecularColor * uLightColor * pow", "return uSpecularColor * pow")]),
        "max left out of the diffuse": (LEFT_OUT, [("max(dot(n, l), 0.0);\n}", "dot(n, l);\n}")]),
        "exponent left out": (LEFT_OUT, [("pow(max(dot(v, r), 0.0), specularAlpha)", "max(dot(v, r), 0.0)")]),
        "ambient left out": (LEFT_OUT, [("fragColor = uAmbientColor + diffuseTerm", "fragColor = diffuseTerm")]),
        "specular term left out": (LEFT_OUT, [(" + specularTerm(n, l, v);", ";")]),
        "N not normalised": (LEFT_OUT, [("vec3 n = normalize(vNormal);", "vec3 n = vNormal;")]),
        "swizzle": (CHANGES, [("fragColor = uAmbientColor + diffuseTerm", "fragColor = uAmbientColor.bgra + diffuseTerm")]),
        "half vector": (CHANGES, [("vec3 r = reflect(-l, n);", "vec3 r = normalize(l + v);")]),
    },
}

MISTAKES["step guard"] = {
    "L not normalised": (CHANGES, [("vec3 toLight = normalize(uLightPosition - vPosition);", "vec3 toLight = uLightPosition - vPosition;")]),
    "L from the light": (CHANGES, [("uLightPosition - vPosition", "vPosition - uLightPosition")]),
    "V from the eye": (CHANGES, [("normalize(-vPosition)", "normalize(vPosition)")]),
    "R's sign": (CHANGES, [("reflect(-toLight, normal)", "reflect(toLight, normal)")]),
    "exponent changed": (CHANGES, [("shininess = 6.0", "shininess = 16.0")]),
    "V computed as L": (CHANGES, [("vec3 toEye = normalize(-vPosition);", "vec3 toEye = toLight;")]),
    "guard left out": (LEFT_OUT, [("step(0.0, cosTheta) * pow", "pow")]),
    "light colour left out of the diffuse": (LEFT_OUT, [("kd * uDiffuseColor * uLightColor", "kd * uDiffuseColor")]),
    "light colour left out of the specular": (LEFT_OUT, [("ks * uSpecularColor * uLightColor", "ks * uSpecularColor")]),
    "max left out of the diffuse": (LEFT_OUT, [("float kd = max(cosTheta, 0.0);", "float kd = cosTheta;")]),
    "exponent left out": (LEFT_OUT, [("pow(max(dot(mirrored, toEye), 0.0), shininess)", "max(dot(mirrored, toEye), 0.0)")]),
    "ambient left out": (LEFT_OUT, [("fragColor = ambient + ", "fragColor = ")]),
    "specular term left out": (LEFT_OUT, [(" + specular;", ";")]),
    "N not normalised": (LEFT_OUT, [("vec3 normal = normalize(vNormal);", "vec3 normal = vNormal;")]),
    "swizzle": (CHANGES, [("vec4 ambient = uAmbientColor;", "vec4 ambient = uAmbientColor.bgra;")]),
    "half vector": (CHANGES, [("vec3 mirrored = reflect(-toLight, normal);", "vec3 mirrored = normalize(toLight + toEye);")]),
}

SHAPES = {"reference": REFERENCE, "tutorial": TUTORIAL, "coefficients": COEFFICIENTS, "arithmetic guard": ARITHMETIC_GUARD, "helpers": HELPERS,
          "step guard": STEP_GUARD}
HELD_OUT = ("step guard",)
