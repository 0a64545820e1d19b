// SPDX-License-Identifier: MIT
// typeset.js: a symbol of the scene schema as the papers print it, for the
// page of `hystviz serve` (app.js) and the pages `hystviz export` writes:
// embed.c copies this file into both where they say "/* @embed … */".
// Markup: "u_{min,2}", "σ_0", "1/m^ν": sub- and superscripts.

// The symbol as nodes: a span.sym with <sub>/<sup> (HTML), or, with svg,
// the text and <tspan>s shifted to sub or super (an SVG <text>'s children).
function typeset(sym, svg) {
  const re = /([_^])(?:\{([^}]*)\}|(.))/gu, out = [];
  let last = 0, m;
  while ((m = re.exec(sym))) {
    if (m.index > last) out.push(sym.slice(last, m.index));
    let e;
    if (svg) {
      e = document.createElementNS('http://www.w3.org/2000/svg', 'tspan');
      e.setAttribute('baseline-shift', m[1] === '_' ? 'sub' : 'super'); // the tspan's own: the text after it is on the baseline
      e.setAttribute('font-size', '70%');
      e.setAttribute('font-style', 'normal');
    } else e = document.createElement(m[1] === '_' ? 'sub' : 'sup');
    e.textContent = m[2] !== undefined ? m[2] : m[3];
    out.push(e);
    last = re.lastIndex;
  }
  if (last < sym.length) out.push(sym.slice(last));
  if (svg) return out;
  const span = document.createElement('span');
  span.className = 'sym';
  span.append(...out);
  return span;
}

// the same as plain text, for messages and names: "u_min,2", "σ0"
function plain(sym) {
  return sym.replace(/_\{([^}]*)\}/g, '\u0001$1').replace(/[_^{}]/g, '').replace(/\u0001/g, '_');
}

// A preset's label ("Fig. 17: σ0 = 1, u_min,2 = 0.2") as nodes, each symbol of
// syms (markup; written plain in the label, followed by " =") typeset
function typesetLabel(text, syms) {
  const ps = syms.filter(Boolean).map(sym => [plain(sym), sym]).sort((a, b) => b[0].length - a[0].length);
  const out = [];
  let rest = text;
  for (;;) {
    let at = -1, hit = null;
    for (const [p, sym] of ps) {
      const k = rest.indexOf(p + ' =');
      if (k >= 0 && (at < 0 || k < at)) { at = k; hit = [p, sym]; }
    }
    if (!hit) break;
    if (at > 0) out.push(rest.slice(0, at));
    out.push(typeset(hit[1]));
    rest = rest.slice(at + hit[0].length);
  }
  if (rest) out.push(rest);
  return out;
}
