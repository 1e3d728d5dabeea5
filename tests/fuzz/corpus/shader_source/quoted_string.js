export default "#version 300 es\nprecision highp float;\nout vec4 c;\nvoid main() { c = vec4(1); }\n";
