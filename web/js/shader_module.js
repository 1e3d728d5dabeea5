// A student's shader file as their page imports it: a JS module whose default export is the GLSL
// (`export default \`#version 300 es ...\``), or raw GLSL.
//
// The module is read, never run: a file is a stranger's text, and importing it would run whatever
// follows the string in this page (a TA's, with their key). It is read by ECMAScript's grammar for
// what such a module may hold: white space and comments, `export default`, one template or string
// literal (its escapes and line terminators as the language defines them; `${` refused), then only
// white space, comments and `;`. Anything else is refused, as the server refuses it
// (server/shader/shader_source.cpp reads the same grammar), and tests/shader_source/module_cases.json
// holds the cases both readers are held to, each checked against Chromium's own import().

// ECMAScript's LineTerminator and WhiteSpace (U+FEFF and the Zs spaces among them).
const LINE_TERMINATORS = "\n\r\u2028\u2029";
const WHITE_SPACE = /[\t\v\f \u00a0\ufeff\u1680\u2000-\u200a\u202f\u205f\u3000]/;
const IDENTIFIER_PART = /[\p{ID_Continue}$\u200c\u200d\\]/u;

class ModuleError extends Error {
  constructor(text, at, message) {
    super(message);
    this.line = text.slice(0, at).split("\n").length;  // the file line, as an editor counts it
  }
}

function isSpace(c) {
  return c !== undefined && (LINE_TERMINATORS.includes(c) || WHITE_SPACE.test(c));
}

// The index after the white space and comments at `i`.
function skipSpace(text, i) {
  for (;;) {
    if (isSpace(text[i])) {
      ++i;
    } else if (text.startsWith("//", i)) {
      i += 2;
      while (i < text.length && !LINE_TERMINATORS.includes(text[i])) ++i;
    } else if (text.startsWith("/*", i)) {
      const end = text.indexOf("*/", i + 2);
      if (end < 0) throw new ModuleError(text, i, "a /* comment is never closed");
      i = end + 2;
    } else {
      return i;
    }
  }
}

function keywordAt(text, i, word) {
  return text.startsWith(word, i) && !IDENTIFIER_PART.test(text[i + word.length] ?? "");
}

const withoutBom = (text) => text.replace(/^\uFEFF/, "");

export function looksLikeModule(text) {
  const body = withoutBom(text);
  try {
    return keywordAt(body, skipSpace(body, 0), "export");
  } catch {
    return false;  // an unclosed comment before anything: not a module, raw text
  }
}

const SIMPLE_ESCAPES = { n: "\n", t: "\t", r: "\r", b: "\b", f: "\f", v: "\v" };
const HEX = /^[0-9a-fA-F]$/;
const BAD_UNICODE = "`\\u` must be followed by four hex digits or {a code point of at most 10FFFF}";

// The escape sequence whose backslash is at `at`: [its value, the index after it].
function escapeAt(text, at) {
  const c = text[at + 1];
  const fail = (message) => { throw new ModuleError(text, at, message); };
  if (c === undefined) return ["", at + 1];  // said unclosed where the string opened
  if (c in SIMPLE_ESCAPES) return [SIMPLE_ESCAPES[c], at + 2];
  if (c === "0" && !/[0-9]/.test(text[at + 2] ?? "")) return ["\0", at + 2];
  if (/[0-9]/.test(c)) fail(`\`\\${c}\` is an octal escape, which a module's strings and templates refuse`);
  if (c === "\r") return ["", text[at + 2] === "\n" ? at + 3 : at + 2];  // a line continuation
  if (LINE_TERMINATORS.includes(c)) return ["", at + 2];
  if (c === "x") {
    const digits = text.slice(at + 2, at + 4);
    if (digits.length < 2 || ![...digits].every((d) => HEX.test(d))) fail("`\\x` must be followed by two hex digits");
    return [String.fromCharCode(parseInt(digits, 16)), at + 4];
  }
  if (c === "u" && text[at + 2] === "{") {
    const close = text.indexOf("}", at + 3);
    const digits = close < 0 ? "" : text.slice(at + 3, close);
    if (!digits || ![...digits].every((d) => HEX.test(d)) || parseInt(digits, 16) > 0x10ffff) fail(BAD_UNICODE);
    return [String.fromCodePoint(parseInt(digits, 16)), close + 1];
  }
  if (c === "u") {
    const digits = text.slice(at + 2, at + 6);
    if (digits.length < 4 || ![...digits].every((d) => HEX.test(d))) fail(BAD_UNICODE);
    return [String.fromCharCode(parseInt(digits, 16)), at + 6];
  }
  return [c, at + 2];  // \\ \` \' \" \$ and the identity escapes
}

// The literal opened by the quote at `open`: [its value, the index after its closing quote].
function literalAt(text, open) {
  const quote = text[open];
  let value = "";
  for (let i = open + 1; ; ) {
    const c = text[i];
    if (c === undefined) throw new ModuleError(text, open, `the shader string opened here is never closed (missing ${quote})`);
    if (c === quote) return [value, i + 1];
    if (quote === "`" && c === "$" && text[i + 1] === "{")
      throw new ModuleError(text, i, "template interpolation ${...} cannot be evaluated here; write the value into the shader");
    if (quote !== "`" && (c === "\n" || c === "\r"))
      throw new ModuleError(text, i, "a quoted JS string cannot span lines; browsers reject this module (use back-ticks)");
    if (c === "\\") {
      const [escaped, next] = escapeAt(text, i);
      value += escaped;
      i = next;
    } else if (c === "\r") {
      value += "\n";  // a template reads CR and CR LF as LF
      i += text[i + 1] === "\n" ? 2 : 1;
    } else {
      value += c;
      ++i;
    }
  }
}

// The module's default export, read by the grammar above: { glsl, quote } where quote is the
// index of its opening quote, or throws a ModuleError.
function readModule(text) {
  let i = skipSpace(text, 0) + "export".length;
  i = skipSpace(text, i);
  if (!keywordAt(text, i, "default")) throw new ModuleError(text, i, "expected `export default` followed by the shader string");
  const quote = skipSpace(text, i + "default".length);
  if (!"`'\"".includes(text[quote] ?? "x"))
    throw new ModuleError(text, quote, "expected a string after `export default` (a back-tick `...` template or a quoted string)");
  let [glsl, end] = literalAt(text, quote);
  for (end = skipSpace(text, end); text[end] === ";"; end = skipSpace(text, end + 1));
  if (end < text.length) throw new ModuleError(text, end, "unexpected text after the shader string; the module should hold only `export default`");
  return { glsl, quote };
}

// -> { glsl, lineOffset } (lineOffset: the file line where the GLSL string starts, so driver
// messages point into the file), or throws an Error with .line (the file line) when the file is
// not a module this grammar reads.
export function glslFromFile(text) {
  const body = withoutBom(text);
  if (!looksLikeModule(body)) return { glsl: body.replace(/\r\n?/g, "\n"), lineOffset: 0 };
  try {
    const { glsl, quote } = readModule(body);
    return { glsl: glsl.replace(/\r\n?/g, "\n"), lineOffset: body.slice(0, quote).split("\n").length - 1 };
  } catch (e) {
    if (!(e instanceof ModuleError)) throw e;
    const error = new Error(`the JS module cannot be read: ${e.message}`);
    error.line = e.line;
    throw error;
  }
}
