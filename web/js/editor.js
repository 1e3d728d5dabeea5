// A textarea with a line-number gutter and diagnostics shown at their lines.
export class Editor {
  constructor(root, name) {
    this.name = name;  // the file name diagnostics use ("phong_frag.js")
    this.textarea = root.querySelector("textarea");
    this.gutter = root.querySelector(".gutter");
    this.list = root.querySelector(".diagnostics");
    this.textarea.addEventListener("input", () => this.renumber());
    this.textarea.addEventListener("scroll", () => (this.gutter.scrollTop = this.textarea.scrollTop));
    this.renumber();
  }
  get text() { return this.textarea.value; }
  set text(value) { this.textarea.value = value; this.renumber(); this.show([]); }

  renumber(errorLines = this.errorLines ?? new Set()) {
    const lines = this.textarea.value.split("\n").length;
    this.gutter.innerHTML = "";
    for (let i = 1; i <= lines; ++i) {
      const n = document.createElement("div");
      n.textContent = i;
      if (errorLines.has(i)) n.className = "error-line";
      this.gutter.append(n);
    }
    this.gutter.scrollTop = this.textarea.scrollTop;
  }

  // diagnostics: [{line, column?, message, severity?}] in this file's lines.
  show(diagnostics) {
    this.errorLines = new Set(diagnostics.filter((d) => d.line > 0).map((d) => d.line));
    this.renumber();
    this.list.innerHTML = "";
    for (const d of diagnostics) {
      const item = document.createElement("li");
      const where = d.line > 0 ? `${this.name}:${d.line}${d.column ? ":" + d.column : ""}` : this.name;
      item.textContent = `${where}: ${d.severity ?? "error"}: ${d.message}`;
      item.dataset.line = d.line;
      item.tabIndex = 0;
      const jump = () => this.goTo(d.line);
      item.addEventListener("click", jump);
      item.addEventListener("keydown", (e) => e.key === "Enter" && jump());
      this.list.append(item);
    }
  }

  goTo(line) {
    if (!(line > 0)) return;
    const lines = this.textarea.value.split("\n");
    const start = lines.slice(0, line - 1).reduce((n, l) => n + l.length + 1, 0);
    this.textarea.focus();
    this.textarea.setSelectionRange(start, start + (lines[line - 1]?.length ?? 0));
  }
}
