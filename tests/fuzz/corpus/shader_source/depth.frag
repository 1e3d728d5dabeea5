// Shadow maps write depth only; the id pass writes the object's index (1-based; 0 = nothing).
precision highp float;
uniform vec4 uId;
out vec4 fragColor;
void main() { fragColor = uId; }
