// Line diff for the side-by-side profile comparison: Myers' O((N+M)·D) algorithm on what
// remains after the common prefix and suffix. Two profiles' outputs can differ on every line
// (other block numbers), so D is bounded: past MAX_EDITS the rest is shown as changed rows
// instead of searching further (no quadratic time on hostile input).
export const MAX_EDITS = 1500; // the trace of V vectors is MAX_EDITS² × 8 bytes at most (18 MB)

// Returns rows {kind: "same"|"changed"|"removed"|"added", left, right, leftLine, rightLine}.
export function lineDiff(a, b) {
  let prefix = 0;
  while (prefix < a.length && prefix < b.length && a[prefix] === b[prefix]) prefix++;
  let suffix = 0;
  while (suffix < a.length - prefix && suffix < b.length - prefix &&
    a[a.length - 1 - suffix] === b[b.length - 1 - suffix]) suffix++;
  const rows = [];
  for (let i = 0; i < prefix; i++) rows.push(same(a, i, i));
  const ops = middle(a.slice(prefix, a.length - suffix), b.slice(prefix, b.length - suffix));
  let i = prefix;
  let j = prefix;
  for (let k = 0; k < ops.length;) {
    if (ops[k] === "=") {
      rows.push(same(a, i++, j++));
      k++;
      continue;
    }
    // A run of edits: its removals and additions side by side as changed rows, the longer
    // side's rest as removed or added.
    let removed = 0;
    let added = 0;
    for (; k < ops.length && ops[k] !== "="; k++) {
      if (ops[k] === "-") removed++;
      else added++;
    }
    for (let r = 0; r < Math.max(removed, added); r++) {
      if (r < removed && r < added)
        rows.push({ kind: "changed", left: a[i], right: b[j], leftLine: ++i, rightLine: ++j });
      else if (r < removed) rows.push({ kind: "removed", left: a[i], leftLine: ++i });
      else rows.push({ kind: "added", right: b[j], rightLine: ++j });
    }
  }
  for (let s = 0; s < suffix; s++) rows.push(same(a, i++, j++));
  return rows;
}

function same(a, i, j) {
  return { kind: "same", left: a[i], right: a[i], leftLine: i + 1, rightLine: j + 1 };
}

// Edit script of "=", "-", "+" turning a into b.
function middle(a, b) {
  const n = a.length;
  const m = b.length;
  const max = Math.min(n + m, MAX_EDITS);
  const offset = max + 1;
  const v = new Int32Array(2 * max + 3);
  const trace = [];
  for (let d = 0; d <= max; d++) {
    trace.push(v.slice());
    for (let k = -d; k <= d; k += 2) {
      let x = k === -d || (k !== d && v[offset + k - 1] < v[offset + k + 1])
        ? v[offset + k + 1] : v[offset + k - 1] + 1;
      let y = x - k;
      while (x < n && y < m && a[x] === b[y]) { x++; y++; }
      v[offset + k] = x;
      if (x >= n && y >= m) return backtrack(trace, offset, n, m);
    }
  }
  // Too many edits: pair the lines up as changed, then the longer side's rest.
  const ops = [];
  for (let i = 0; i < Math.max(n, m); i++) {
    if (i < n) ops.push("-");
    if (i < m) ops.push("+");
  }
  return ops;
}

function backtrack(trace, offset, n, m) {
  const ops = [];
  let x = n;
  let y = m;
  for (let d = trace.length - 1; d >= 0; d--) {
    const v = trace[d];
    const k = x - y;
    const down = k === -d || (k !== d && v[offset + k - 1] < v[offset + k + 1]);
    const prevK = down ? k + 1 : k - 1;
    const prevX = d === 0 ? 0 : v[offset + prevK];
    const prevY = prevX - prevK;
    while (x > prevX && y > prevY) {
      ops.push("=");
      x--;
      y--;
    }
    if (d > 0) ops.push(down ? "+" : "-");
    x = prevX;
    y = prevY;
  }
  return ops.reverse();
}
