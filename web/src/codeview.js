// A read-only code view with line numbers that stays fast for millions of lines: it keeps the
// lines in an array and puts only the visible ones (plus a margin) into the DOM.

const LINE_HEIGHT = 18; // px; matches .code-line in index.html
const MARGIN_LINES = 20;
// Browsers cap an element's height (about 16.7 M px in Chromium); past that lines are mapped
// onto the scroll range proportionally.
const MAX_SCROLL_PX = 15_000_000;

export class CodeView {
  constructor(element, { label, onLineClick }) {
    this.element = element;
    this.lines = [];
    this.current = 0; // 1-based, 0 = none
    this.marked = new Set();
    this.onLineClick = onLineClick;
    element.classList.add("code");
    element.tabIndex = 0;
    element.setAttribute("role", "listbox");
    element.setAttribute("aria-label", label);
    this.spacer = document.createElement("div");
    this.spacer.className = "code-spacer";
    this.window = document.createElement("div");
    this.window.className = "code-window";
    element.append(this.spacer, this.window);
    this.pending = false;
    element.addEventListener("scroll", () => this.schedule());
    element.addEventListener("click", (event) => {
      const row = event.target.closest(".code-line");
      if (row) this.select(Number(row.dataset.line), { scroll: false, notify: true });
    });
    element.addEventListener("keydown", (event) => {
      const step = { ArrowDown: 1, ArrowUp: -1, PageDown: 30, PageUp: -30 }[event.key];
      if (!step || this.lines.length === 0) return;
      event.preventDefault();
      const next = Math.min(this.lines.length, Math.max(1, (this.current || 1) + step));
      this.select(next, { scroll: true, notify: true });
    });
  }

  clear() {
    this.lines = [];
    this.current = 0;
    this.marked = new Set();
    this.element.scrollTop = 0;
    this.schedule();
  }

  append(line) {
    this.lines.push(line);
  }

  get lineCount() {
    return this.lines.length;
  }

  scale() {
    const full = this.lines.length * LINE_HEIGHT;
    return full > MAX_SCROLL_PX ? MAX_SCROLL_PX / full : 1;
  }

  // Coalesces redraws to one per animation frame.
  schedule() {
    if (this.pending) return;
    this.pending = true;
    requestAnimationFrame(() => {
      this.pending = false;
      this.render();
    });
  }

  render() {
    const total = this.lines.length;
    const scale = this.scale();
    this.spacer.style.height = `${Math.ceil(total * LINE_HEIGHT * scale)}px`;
    const top = this.element.scrollTop / scale;
    const first = Math.max(0, Math.floor(top / LINE_HEIGHT) - MARGIN_LINES);
    const visible = Math.ceil(this.element.clientHeight / LINE_HEIGHT) + 2 * MARGIN_LINES;
    const last = Math.min(total, first + visible);
    const digits = String(Math.max(total, 1)).length;
    this.window.style.transform = `translateY(${this.element.scrollTop + (first * LINE_HEIGHT - top)}px)`;
    const rows = [];
    for (let i = first; i < last; i++) {
      const row = document.createElement("div");
      const number = i + 1;
      row.className = "code-line";
      if (number === this.current) row.classList.add("current");
      if (this.marked.has(number)) row.classList.add("marked");
      row.dataset.line = String(number);
      row.setAttribute("role", "option");
      row.setAttribute("aria-selected", number === this.current ? "true" : "false");
      const gutter = document.createElement("span");
      gutter.className = "code-number";
      gutter.textContent = String(number).padStart(digits, " ");
      const text = document.createElement("span");
      text.textContent = this.lines[i];
      row.append(gutter, text);
      rows.push(row);
    }
    this.window.replaceChildren(...rows);
  }

  // Makes `line` current, scrolls it to the upper third of the view when asked.
  select(line, { scroll = true, notify = false } = {}) {
    if (!(line >= 1 && line <= this.lines.length)) return;
    this.current = line;
    if (scroll) {
      const y = (line - 1) * LINE_HEIGHT * this.scale();
      this.element.scrollTop = Math.max(0, y - this.element.clientHeight / 3);
    }
    this.render();
    if (notify && this.onLineClick) this.onLineClick(line);
  }

  mark(lines) {
    this.marked = new Set(lines);
    this.schedule();
  }
}
