// The homework page's WebGL2 view, as the course's hw2.js sets it up: default context attributes
// (antialias, premultiplied alpha), attributes aVertexPosition / aVertexNormal from a non-indexed
// triangle list, and what the course (GET /api/course) says: its camera (fovY, near, far, where
// the mesh stands) and its uniforms under every name it feeds them by.
import { multiply, perspective, rotationY, translation } from "./mat4.js";

// The course's uniforms as the view sets them: role (or first name) -> {names, value}.
export function courseUniforms(course) {
  const out = {};
  for (const u of course.uniforms) out[u.role || u.names[0]] = { names: u.names, value: u.value };
  return out;
}

// ANGLE: "ERROR: 0:12: 'foo' : undeclared identifier"; Mesa: "0:12(5): error: ...".
function parseLog(log, stage, lineOffset) {
  const out = [];
  for (const line of log.split("\n")) {
    const m = line.match(/^(?:ERROR|WARNING):\s*\d+:(\d+):\s*(.*)$/) || line.match(/^\d+:(\d+)\(\d+\):\s*(?:error|warning):\s*(.*)$/);
    if (m) out.push({ stage, line: Number(m[1]) + lineOffset, message: m[2].trim() });
    else if (line.trim()) out.push({ stage, line: 0, message: line.trim() });
  }
  return out;
}

export class GlView {
  constructor(canvas, course) {
    this.canvas = canvas;
    this.gl = canvas.getContext("webgl2");  // default attributes, as the student's page
    if (!this.gl) throw new Error("this browser has no WebGL2");
    this.camera = course.camera;
    this.program = null;
    this.mesh = null;
    this.uniforms = courseUniforms(course);
    this.active = [];
  }

  setMesh({ positions, normals }) {
    const gl = this.gl;
    const buffer = (data) => {
      const b = gl.createBuffer();
      gl.bindBuffer(gl.ARRAY_BUFFER, b);
      gl.bufferData(gl.ARRAY_BUFFER, data, gl.STATIC_DRAW);
      return b;
    };
    if (this.mesh) gl.deleteBuffer(this.mesh.position), gl.deleteBuffer(this.mesh.normal);
    this.mesh = { position: buffer(positions), normal: buffer(normals), count: positions.length / 3 };
  }

  // -> [] when the program links, else diagnostics with file lines.
  setProgram(vertex, fragment) {
    const gl = this.gl;
    const compile = (type, { glsl, lineOffset }, stage) => {
      const s = gl.createShader(type);
      gl.shaderSource(s, glsl);
      gl.compileShader(s);
      const errors = gl.getShaderParameter(s, gl.COMPILE_STATUS) ? [] : parseLog(gl.getShaderInfoLog(s) || "", stage, lineOffset);
      return { s, errors };
    };
    const vs = compile(gl.VERTEX_SHADER, vertex, "vertex");
    const fs = compile(gl.FRAGMENT_SHADER, fragment, "fragment");
    if (vs.errors.length || fs.errors.length) return [...vs.errors, ...fs.errors];
    const p = gl.createProgram();
    gl.attachShader(p, vs.s);
    gl.attachShader(p, fs.s);
    gl.linkProgram(p);
    if (!gl.getProgramParameter(p, gl.LINK_STATUS)) return parseLog(gl.getProgramInfoLog(p) || "link failed", "link", 0);
    if (this.program) gl.deleteProgram(this.program);
    this.program = p;
    this.active = [];
    for (let i = 0; i < gl.getProgramParameter(p, gl.ACTIVE_UNIFORMS); ++i) this.active.push(gl.getActiveUniform(p, i).name);
    return [];
  }

  // Draws frame state and mesh at `degrees` of rotation.
  draw(degrees) {
    const gl = this.gl, p = this.program;
    gl.viewport(0, 0, this.canvas.width, this.canvas.height);
    gl.clearColor(0, 0, 0, 1);
    gl.clearDepth(1);
    gl.enable(gl.DEPTH_TEST);
    gl.depthFunc(gl.LEQUAL);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    if (!p || !this.mesh) return;
    gl.useProgram(p);
    const rotation = rotationY((degrees * Math.PI) / 180);
    const c = this.camera;
    const projection = perspective((c.fovYDegrees * Math.PI) / 180, this.canvas.width / this.canvas.height, c.near, c.far);
    const set = (name, value) => {
      const loc = gl.getUniformLocation(p, name);
      if (!loc) return;
      if (value.length === 16) gl.uniformMatrix4fv(loc, false, value);
      else if (value.length === 4) gl.uniform4fv(loc, value);
      else if (value.length === 3) gl.uniform3fv(loc, value);
      while (gl.getError() !== gl.NO_ERROR);  // a type mismatch leaves the uniform at zero, as in hw2.js
    };
    set("uWorldToClipSpaceMatrix", projection);
    set("uMeshToWorldMatrix", multiply(translation(...c.meshTranslation), rotation));
    set("uMeshToWorldRotMatrix", rotation);
    for (const { names, value } of Object.values(this.uniforms)) for (const name of names) set(name, value);
    const attribute = (name, buffer) => {
      const loc = gl.getAttribLocation(p, name);
      if (loc < 0) return;
      gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
      gl.enableVertexAttribArray(loc);
      gl.vertexAttribPointer(loc, 3, gl.FLOAT, false, 0, 0);
    };
    attribute("aVertexPosition", this.mesh.position);
    attribute("aVertexNormal", this.mesh.normal);
    gl.drawArrays(gl.TRIANGLES, 0, this.mesh.count);
  }

  // The PNG the student's page saves for frame k: draw, then toBlob in the same task.
  captureFrame(degrees) {
    this.draw(degrees);
    return new Promise((resolve) => this.canvas.toBlob(resolve, "image/png"));
  }
}
