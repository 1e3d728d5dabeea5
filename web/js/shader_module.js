// A student's shader file as their page imports it: a JS module whose default export is the GLSL
// (`export default \`#version 300 es ...\``), or raw GLSL. The module is imported for real (a Blob
// URL), so the text is exactly what their browser would compile.

// The file line where the GLSL string starts, so driver messages can point into the file.
function lineOffsetOfString(text) {
  const at = text.search(/export\s+default\s*[`'"]/);
  if (at < 0) return 0;
  const quote = text.slice(at).search(/[`'"]/) + at;
  return text.slice(0, quote).split("\n").length - 1;
}

export function looksLikeModule(text) {
  return /^\s*(\/\/[^\n]*\n\s*|\/\*[\s\S]*?\*\/\s*)*export\b/.test(text.replace(/^\uFEFF/, ""));
}

// -> { glsl, lineOffset } or throws Error with .line (file line) when the module does not load.
export async function glslFromFile(text) {
  if (!looksLikeModule(text)) return { glsl: text.replace(/\r\n?/g, "\n"), lineOffset: 0 };
  const url = URL.createObjectURL(new Blob([text], { type: "text/javascript" }));
  try {
    const module = await import(url);
    if (typeof module.default !== "string") throw new Error("the module's default export is not a string");
    return { glsl: module.default.replace(/\r\n?/g, "\n"), lineOffset: lineOffsetOfString(text) };
  } catch (e) {
    const error = new Error(`the JS module does not load: ${e.message}`);
    error.line = 0;
    throw error;
  } finally {
    URL.revokeObjectURL(url);
  }
}
