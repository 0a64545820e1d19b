// SPDX-License-Identifier: MIT
// app.js: the page of `hystviz serve` (no libraries, works offline).
// State lives in `hv` (also read by tests/serve/browser_test.py).
'use strict';
/* @embed typeset.js */

const hv = window.hv = {
  token: document.querySelector('meta[name="hystviz-token"]').content,
  page: Array.from(crypto.getRandomValues(new Uint8Array(8)), b => b.toString(16).padStart(2, '0')).join(''),
  scenes: [], info: null, sets: {}, lastKey: null, present: false, dragging: false,
  seq: 0, inflight: false, pending: false,
  svg: null, cmd: '', renders: 0, changes: 0, error: null, serverMs: NaN, serverCpuMs: NaN, pageMs: NaN,
  hover: null, hoverTimer: 0,
  frame: -1, frameB64: null, frameSeq: 0, frameInflight: false, framePending: -1, playing: false,
  pins: [], sliderPlay: null, speed: 1, axesHeld: null,
  fitKeys: new Set(), fitAbort: null, fit: null,
};
const $ = id => document.getElementById(id);
const enc = encodeURIComponent;

function el(tag, attrs, ...kids) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (k === 'class') e.className = v; else if (k.startsWith('on')) e.addEventListener(k.slice(2), v);
    else e.setAttribute(k, v);
  }
  for (const k of kids) e.append(k);
  return e;
}

// ---- catalogue ----------------------------------------------------------

async function loadCatalogue() {
  const r = await fetch('/api/scenes');
  const j = await r.json();
  hv.scenes = j.scenes;
  hv.dir = j.dir;
  const nav = $('catalogue');
  // the gallery's parts and order
  const parts = ['Minor loops of the Dahl and LuGre models', 'The Bouc-Wen benchmark', "Beyond the papers' figures",
    'Animations (scenes)', 'Animations (built in)'];
  const kids = [];
  let part = -1;
  for (const s of j.scenes) {
    if (s.part !== part) { part = s.part; kids.push(el('h4', {}, parts[part] || '')); }
    kids.push(el('a', { href: '#' + s.file, class: s.error ? 'bad' : '', title: s.error || s.caption, 'data-file': s.file },
      (s.label ? s.label + ' · ' : '') + s.name, ...(s.anim ? [el('span', { 'aria-hidden': 'true' }, ' ▶'),
        el('span', { class: 'sr' }, ' (animation)')] : []), el('small', {}, s.error ? s.error : s.caption)));
  }
  nav.replaceChildren(...kids);
  markCurrent();
  return j;
}

function markCurrent() {
  for (const a of $('catalogue').querySelectorAll('a'))
    a.classList.toggle('on', hv.info && a.dataset.file === hv.info.file);
}

// ---- the URL: #SCENE?KEY=VALUE&...&view=present&preset=NAME&frame=N --------

function parseHash() {
  const h = location.hash.slice(1), i = h.indexOf('?');
  const st = { file: decodeURIComponent(i < 0 ? h : h.slice(0, i)) || null, sets: {}, present: false, preset: null,
    frame: null };
  for (const [k, v] of new URLSearchParams(i < 0 ? '' : h.slice(i + 1))) {
    if (k === 'view' || k === 'present') st.present = k === 'present' || v === 'present';
    else if (k === 'preset') st.preset = v;
    else if (k === 'frame') st.frame = parseInt(v, 10);
    else if (/^[a-z]+\.[A-Za-z0-9_.-]+$/.test(k)) st.sets[k] = v;
  }
  return st;
}

function stateHash() {
  const p = new URLSearchParams();
  for (const [k, v] of Object.entries(hv.sets)) p.append(k, v);
  if (hv.preset) p.set('preset', hv.preset);
  if (hv.present) p.set('view', 'present');
  if (hv.info && hv.info.anim && hv.frame > 0) p.set('frame', hv.frame);
  const q = p.toString();
  return '#' + enc(hv.info ? hv.info.file : '') + (q ? '?' + q : '');
}

// a new history entry per change (a drag is one change), so back/forward walk through them
function pushUrl(replace) {
  if (!hv.info) return;
  const h = stateHash();
  if (h === location.hash) return;
  if (replace) history.replaceState(null, '', h); else history.pushState(null, '', h);
}

// While a slider moves, the URL is written once it rests for URL_REST_MS or is
// let go, not at every input event: each history entry costs the page and the
// browser's main threads a few ms, taken from the render the move asked for.
// The first move of a drag decides push (a new entry) or replace.
const URL_REST_MS = 250;
function pushUrlSoon(replace) {
  if (!hv.urlTimer) hv.urlReplace = replace;
  clearTimeout(hv.urlTimer);
  hv.urlTimer = setTimeout(pushUrlNow, URL_REST_MS);
}
function pushUrlNow() {
  if (!hv.urlTimer) return;
  clearTimeout(hv.urlTimer);
  hv.urlTimer = 0;
  pushUrl(hv.urlReplace);
}

function applyUrl() {
  clearTimeout(hv.urlTimer); // back/forward (or a typed URL) wins over a write not yet made
  hv.urlTimer = 0;
  const st = parseHash();
  if (!st.file) return;
  if (!hv.info || st.file !== hv.info.file) { openScene(st.file, false, st); return; }
  if (stateHash() === location.hash) return;
  hv.sets = st.sets;
  hv.preset = st.preset;
  syncHeld();
  setPresent(st.present, true);
  buildControls(hv.info);
  requestRender();
}

// ---- a scene and its controls --------------------------------------------

// st: the state a URL asks for (values, view, preset, frame), or none
async function openScene(file, keep, st) {
  pushUrlNow(); // the scene left keeps its last values in the history
  const r = await fetch('/api/scene?scene=' + enc(file));
  if (r.status !== 200) { showError('no scene ' + file); return; }
  const info = await r.json();
  const same = hv.info && hv.info.file === file;
  hv.info = info;
  if (!keep || !same) {
    const theme = hv.sets['figure.theme'];
    hv.sets = st ? st.sets : theme ? { 'figure.theme': theme } : {};
    hv.preset = st ? st.preset : null;
    hv.lastKey = null; hv.svg = null; $('figure').replaceChildren(); hv.hover = null;
    sliderPlayStop();
    if (!same) { hv.pins = []; pinList(); hv.fitKeys = new Set(); fitStop(); $('fit').hidden = true; } // pins and fits belong to their scene
    syncHeld();
    $('newname').value = '';
    // the new figure where it can be seen (a switch keeps no scroll position)
    if (!same && !hv.present) $('title').scrollIntoView({ block: 'start' });
  }
  if (st && st.frame > 0 && info.anim && info.anim.frames > st.frame) { // the link's frame
    $('scrub').max = info.anim.frames - 1;
    $('scrub').value = st.frame;
  }
  const entry = hv.scenes.find(s => s.file === file);
  $('title').textContent = (entry && entry.label ? entry.label + ' · ' : '') + (info.name || file);
  $('caption').textContent = info.caption;
  $('text').textContent = info.text;
  labelFigure();
  markCurrent();
  buildControls(info);
  keyHelp();
  if (st) setPresent(st.present, true);
  // a built-in animation has frames only: no still figure, no controls
  $('stage').hidden = $('share').hidden = !!info.builtin;
  $('message').hidden = true;
  setupAnim(info, (same && keep) || !!(st && st.frame > 0));
  pushUrl(true);
  if (info.error) { showError(info.error); return; }
  if (!info.builtin) requestRender();
}

// The label of a control: the schema's symbol typeset (typeset.js), the
// series it belongs to, the unit.
function ctlName(c) {
  const parts = c.key.split('.'), series = parts.length > 2 ? ' (' + parts[1] + ')' : '';
  return (c.sym ? plain(c.sym) : parts[parts.length - 1]) + series;
}
// a unit as a screen reader reads it: "J/m³", "A/m" (the markup's ^2, ^3 as superscript digits)
function unitText(u) {
  const sup = { '-': '⁻', 0: '⁰', 1: '¹', 2: '²', 3: '³', 4: '⁴', 5: '⁵', 6: '⁶', 7: '⁷', 8: '⁸', 9: '⁹' };
  return plain(u.replace(/\^\{?(-?\d+)\}?/g, (_, d) => Array.from(d, x => sup[x]).join('')));
}
// a slider's accessible name: "σ0 (T)", "γ g20"; its value as text: "6 T"
function sliderName(c) { return ctlName(c) + (c.unit ? ' (' + unitText(c.unit) + ')' : ''); }
function valueText(c) { return curOf(c) + (c.unit ? ' ' + unitText(c.unit) : ''); }
function labelNode(c) {
  const parts = c.key.split('.');
  const name = c.sym ? typeset(c.sym) : el('span', { class: 'sym' }, parts[parts.length - 1]);
  const kids = [name];
  if (parts.length > 2) kids.push(el('span', { class: 'of' }, ' ' + parts[1]));
  if (c.unit) kids.push(el('span', { class: 'unit' }, ' [', typeset(c.unit), ']'));
  return el('span', { class: 'k' }, ...kids);
}

// ---- slider domains: valid given the other current values -------------------

function ctlOf(key) { return hv.info && hv.info.controls.find(c => c.key === key); }
function curOf(c) { return hv.sets[c.key] !== undefined ? hv.sets[c.key] : c.value; }
function numOf(key) { const c = ctlOf(key); return c ? parseFloat(curOf(c)) : NaN; }

// [lo, hi] of the slider now: its own range cut to the keys it must stay
// strictly between (c.above < value < c.below), one step in from them, and for
// a key the work grows with, below the value that would pass serve's work
// budget (the last render's estimate); fixed while one drag lasts
function domain(c) {
  if (hv.dragging && hv.frozen && hv.frozen.key === c.key) return hv.frozen.d;
  let lo = c.lo, hi = c.hi;
  const a = c.above ? numOf(c.above) : NaN, b = c.below ? numOf(c.below) : NaN;
  if (isFinite(a) && a >= lo) lo = a;
  if (isFinite(b) && b <= hi) hi = b;
  const lg = c.log && lo > 0, d = (hi - lo) / 1000, f = lg ? Math.pow(hi / lo, 1 / 1000) : 1;
  if (isFinite(a) && lo === a) lo = lg ? lo * f : lo + d;
  if (isFinite(b) && hi === b) hi = lg ? hi / f : hi - d;
  if (c.work && hv.work > 0 && hv.budget > 0) {
    const v = parseFloat(curOf(c)), w = 0.98 * v * hv.budget / hv.work;
    if (w < hi) hi = Math.max(w, v);
  }
  return { lo, hi, a, b };
}
function toPos(c, v) {
  const { lo, hi } = domain(c);
  const t = c.log ? Math.log(v / lo) / Math.log(hi / lo) : (v - lo) / (hi - lo);
  return Math.max(0, Math.min(1000, Math.round(1000 * t)));
}
// the value text at slider position p: short, inside the domain, on the grid
// of c.per (a period in whole samples: k / fs)
function valueAt(c, p) {
  const { lo, hi, a, b } = domain(c), t = p / 1000;
  let v = c.log ? lo * Math.pow(hi / lo, t) : lo + (hi - lo) * t;
  if (c.int) return String(Math.max(Math.ceil(lo), Math.min(Math.floor(hi), Math.round(v))));
  if (c.per) {
    const fs = numOf(c.per);
    if (isFinite(fs) && fs > 0) {
      let k = Math.round(v * fs);
      if (k / fs > hi) k = Math.floor(hi * fs);
      if (k / fs < lo) k = Math.ceil(lo * fs);
      return String(Math.max(4, k) / fs);
    }
  }
  const inside = x => !(x <= a) && !(x >= b) && x >= Math.min(lo, c.lo) && x <= Math.max(hi, c.hi);
  for (let d = 4; d <= 17; d++) {
    const x = parseFloat(v.toPrecision(d));
    if (inside(x)) return String(x);
  }
  return String(v);
}

// a typed value: a number (a decimal comma read as a point), inside the
// domain; else one plain-language line and the slider stays
function checkTyped(c, text) {
  let t = text.trim();
  if (/^[+-]?\d+,\d+$/.test(t)) t = t.replace(',', '.');
  if (!/^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$/.test(t))
    return { err: ctlName(c) + ' takes one number, such as ' + c.value + (/,/.test(t) ? ' (a decimal point, not a comma)' : '') };
  const x = parseFloat(t);
  if (c.int && !Number.isInteger(x)) return { err: ctlName(c) + ' takes a whole number' };
  const { a, b } = domain(c), ca = c.above && ctlOf(c.above), cb = c.below && ctlOf(c.below);
  if (x <= a || x >= b) {
    const lim = [];
    if (ca) lim.push('greater than ' + ctlName(ca) + ' = ' + curOf(ca));
    if (cb) lim.push('less than ' + ctlName(cb) + ' = ' + curOf(cb));
    return { err: ctlName(c) + ' must be ' + lim.join(' and ') };
  }
  if (c.per) {
    const fs = numOf(c.per), n = x * fs;
    if (isFinite(n) && (Math.abs(n - Math.round(n)) > 1e-9 * n || Math.round(n) < 4))
      return { err: ctlName(c) + ' must hold a whole number (at least 4) of samples at ' + ctlName(ctlOf(c.per) || c) + ' = ' + fs
        + ': ' + (Math.max(4, Math.round(n)) / fs) + ' is the nearest' };
  }
  return { value: t };
}

// the sliders follow the others' values (their domains moved)
function syncSliders() {
  for (const r of $('controls').querySelectorAll('input[type=range][data-key]')) {
    const c = ctlOf(r.dataset.key);
    if (c) { r.value = toPos(c, parseFloat(curOf(c))); r.setAttribute('aria-valuetext', valueText(c)); }
  }
}

// the controls the presentation view shows: the scene's [controls] main, else the first three
function mainControls(info) {
  const m = info.controls.filter(c => c.main > 0).sort((x, y) => x.main - y.main);
  return m.length ? m : info.controls.slice(0, 3);
}

function buildControls(info) {
  const box = $('controls');
  const kids = [el('div', { class: 'row tools' },
    el('button', { type: 'button', onclick: resetValues, title: 'r' }, 'reset to file'),
    el('button', { type: 'button', onclick: () => setPresent(!hv.present), title: 'p', class: 'presentbtn' },
      'presentation (p)'),
    el('button', { type: 'button', class: 'keysbtn', onclick: toggleKeys, title: '?: the keys', 'aria-controls': 'keys',
      'aria-expanded': String(!$('keys').hidden) }, 'keys (?)'),
    el('button', { type: 'button', id: 'pin', onclick: () => { addPin(); say(hv.pins.length ? 'pinned: ' + hv.pins[hv.pins.length - 1].label : 'nothing to pin'); },
      title: 'g: keep the curves shown now, labelled with their values, in a lighter tone under the next ones' }, 'pin (g)'),
    el('button', { type: 'button', id: 'hold', onclick: () => holdAxes(!hv.axesHeld), class: hv.axesHeld ? 'on' : '',
      'aria-pressed': String(!!hv.axesHeld),
      title: 'l: hold the axes at the limits shown now (figure.xlim, figure.ylim); a slider played or dragged holds them over its whole range' },
      hv.axesHeld ? 'axes held (l)' : 'hold axes (l)'),
    speedSelect('speed'),
    el('button', { type: 'button', class: 'stepbtn', 'aria-label': 'step the slider back', title: ', (comma): the slider played or moved last, one step back',
      onclick: () => sliderStep(-1) }, '◀|'),
    el('button', { type: 'button', class: 'stepbtn', 'aria-label': 'step the slider on', title: '. (full stop): the slider played or moved last, one step on',
      onclick: () => sliderStep(1) }, '|▶'),
    ...(info.fit ? [el('button', { type: 'button', id: 'fitbtn', onclick: () => hv.fitAbort ? fitStop(true) : doFit(),
      title: 'fit the ticked [model] parameters to the measured data [data ' + info.fit + '] from the values shown (hystviz fit --free … --set …); the sliders take the estimates' },
      hv.fitAbort ? 'stop fit' : 'fit to data')] : []),
    el('label', { title: 'figure.theme = slides: dark background, thicker lines, larger text (t)' },
      el('input', { type: 'checkbox', id: 'slides', onchange: ev => setTheme(ev.target.checked) }), ' slides theme'),
    ...(info.presets || []).map((p, i) => el('button', { type: 'button', class: 'preset' + (hv.preset === p.name ? ' on' : ''),
      'data-preset': p.name, title: (i < 9 ? 'key ' + (i + 1) + ': ' : '') + p.sets.join('; '),
      onclick: () => applyPreset(i) }, ...typesetLabel(p.label, info.controls.map(c => c.sym))))),
    el('div', { class: 'row pins', id: 'pins' })];
  const mains = mainControls(info);
  for (const c of info.controls) {
    const cur = curOf(c);
    const title = c.key + ': ' + c.doc + (c.range ? ' (' + c.range + ')' : '');
    const range = el('input', { type: 'range', min: 0, max: 1000, step: 1, 'data-key': c.key, 'aria-label': sliderName(c), title,
      'aria-valuetext': valueText(c) });
    const box = el('input', { type: 'text', value: cur, 'data-key': c.key, 'aria-label': sliderName(c) + ', exact value',
      inputmode: 'decimal' });
    const err = el('div', { class: 'err', 'data-key': c.key });
    const play = el('button', { type: 'button', class: 'playkey' + (hv.sliderPlay && hv.sliderPlay.key === c.key ? ' on' : ''),
      'data-key': c.key, 'aria-label': 'play ' + ctlName(c), 'aria-pressed': String(!!(hv.sliderPlay && hv.sliderPlay.key === c.key)), title: 'play: move ' + ctlName(c) + ' back and forth over its range (space stops)',
      onclick: () => toggleSliderPlay(c.key) }, hv.sliderPlay && hv.sliderPlay.key === c.key ? '■' : '▶');
    // a scene with measured data: a [model] number key may be ticked as a free key of the fit
    const fitOk = info.fit && /^model\.[^.]+$/.test(c.key) && !c.int;
    const tick = fitOk ? [el('label', { class: 'fitkey', title: 'fit ' + ctlName(c) + ' to the measured data (the fit button)' },
      el('input', { type: 'checkbox', 'data-key': c.key, 'aria-label': 'fit ' + ctlName(c),
        onchange: ev => { if (ev.target.checked) hv.fitKeys.add(c.key); else hv.fitKeys.delete(c.key); } }), ' fit')] : [];
    if (fitOk && hv.fitKeys.has(c.key)) tick[0].firstChild.checked = true;
    const div = el('div', { class: 'ctl' + (hv.sets[c.key] !== undefined ? ' changed' : '') + (mains.includes(c) ? ' main' : ''),
      'data-key': c.key },
      el('label', { title }, labelNode(c), el('span', { class: 'file' }, 'file: ' + c.value + (c.set ? '' : ' (default)'))),
      range, el('div', { class: 'row' }, box, play, ...tick, el('span', { class: 'note' }, c.range + (c.log ? ' · log slider' : ''))), err);
    range.value = toPos(c, parseFloat(cur));
    const apply = (v) => {
      if (v === c.value) delete hv.sets[c.key]; else hv.sets[c.key] = v;
      div.classList.toggle('changed', hv.sets[c.key] !== undefined);
      range.setAttribute('aria-valuetext', valueText(c));
      hv.lastKey = c.key;
      hv.preset = null;
      requestRender();
    };
    range.addEventListener('input', () => {
      if (!hv.dragging) hv.frozen = { key: c.key, d: domain(c) };
      const v = valueAt(c, +range.value);
      box.value = v;
      apply(v);
      pushUrlSoon(hv.dragging);
      hv.dragging = true;
    });
    range.addEventListener('change', () => { hv.dragging = false; pushUrlNow(); syncSliders(); });
    // a drag (pointer or touch) holds the axes over the slider's range, as its ▶ does
    range.addEventListener('pointerdown', () => holdForRange(c.key));
    box.addEventListener('change', () => {
      const t = checkTyped(c, box.value);
      if (t.err) { showNote(c.key, t.err); return; }
      box.value = t.value;
      range.value = toPos(c, parseFloat(t.value));
      apply(t.value);
      pushUrl(false);
      syncSliders();
    });
    kids.push(div);
  }
  box.replaceChildren(...kids);
  pinList();
  $('slides').checked = hv.sets['figure.theme'] === 'slides';
  document.body.classList.toggle('slides', hv.sets['figure.theme'] === 'slides');
}

// a preset of the scene ([preset NAME]): its values replace the page's (the theme stays)
function applyPreset(i) {
  const p = hv.info && hv.info.presets && hv.info.presets[i];
  if (!p) return;
  sliderPlayStop();
  const theme = hv.sets['figure.theme'];
  hv.sets = {};
  for (const a of p.sets) { const e = a.indexOf('='); hv.sets[a.slice(0, e).trim()] = a.slice(e + 1).trim(); }
  if (theme) hv.sets['figure.theme'] = theme;
  syncHeld();
  buildControls(hv.info);
  hv.preset = p.name;
  for (const b of document.querySelectorAll('button.preset')) b.classList.toggle('on', b.dataset.preset === p.name);
  pushUrl(false);
  requestRender();
}

function resetValues() {
  sliderPlayStop();
  const theme = hv.sets['figure.theme'];
  hv.sets = theme ? { 'figure.theme': theme } : {};
  hv.preset = null;
  syncHeld();
  buildControls(hv.info);
  pushUrl(false);
  requestRender();
}

function setTheme(on) {
  if (on) hv.sets['figure.theme'] = 'slides'; else delete hv.sets['figure.theme'];
  $('slides').checked = on;
  document.body.classList.toggle('slides', on);
  pushUrl(false);
  requestRender();
}

// ---- fitting: the ticked [model] keys to the scene's measured data -------------
// POST /api/fit with the values shown (they are the start and the fixed values)
// and a new sequence number of the page: a render asked for while it runs (a
// slider moved) stops it on the server, as does "stop fit" (the connection
// closes).  The answer's estimates become the sliders' values (one render).

function fitStop(said) {
  if (!hv.fitAbort) return;
  hv.fitAbort.abort();
  hv.fitAbort = null;
  const b = $('fitbtn');
  if (b) b.textContent = 'fit to data';
  if (said) say('fit stopped');
}

function fitNum(v) { return v === null || v === undefined ? '–' : Number(v).toPrecision(6).replace(/\.?0+(e|$)/, '$1'); }

function showFit(j) {
  const names = j.params.map(p => { const c = ctlOf(p.key); return c ? ctlName(c) : p.key; });
  $('fitcap').textContent = 'estimates from ' + j.points + ' measured points of [data ' + j.data.join('], [data ') + ']';
  $('fitrows').replaceChildren(...j.params.map((p, i) => el('tr', {},
    el('th', { scope: 'row' }, names[i]), el('td', {}, fitNum(p.start)), el('td', {}, fitNum(p.estimate)),
    el('td', {}, fitNum(p.se)), el('td', {}, '[' + fitNum(p.ci_lo) + ', ' + fitNum(p.ci_hi) + ']'),
    el('td', {}, p.unidentifiable ? 'unidentifiable: the data do not determine it' : ''))));
  $('fitstats').textContent = 'RMS ' + fitNum(j.rms) + ', normalised RMS ' + fitNum(j.nrms) + ', max error ' +
    fitNum(j.max_error) + ' · ' + j.iterations + ' iterations, ' + j.evaluations + ' model evaluations, ' +
    j.seconds.toFixed(2) + ' s';
  const un = j.params.filter(p => p.unidentifiable).map(p => { const c = ctlOf(p.key); return c ? ctlName(c) : p.key; });
  const nm = k => { const c = ctlOf(k); return c ? ctlName(c) : k; };
  $('fitflags').textContent = (un.length ? 'unidentifiable: ' + un.join(', ') + '. ' : '') +
    (j.correlated.length ? 'correlated (|r| > 0.95): ' + j.correlated.map(q => nm(q[0]) + ' and ' + nm(q[1]) + ' (r = ' + q[2].toFixed(3) + ')').join(', ')
      : 'no pair correlated above |r| = 0.95');
  $('fit').hidden = false;
  say('fit done: ' + names.map((n, i) => n + ' = ' + fitNum(j.params[i].estimate)).join(', ') + '; RMS ' + fitNum(j.rms) +
    (un.length ? '; unidentifiable: ' + un.join(', ') : ''));
}

async function doFit() {
  if (!hv.info || !hv.info.fit) return;
  const keys = hv.info.controls.filter(c => hv.fitKeys.has(c.key)).map(c => c.key.slice(6));
  if (!keys.length) { flash('tick the parameters to fit (the "fit" box beside each slider of the model)'); return; }
  sliderPlayStop();
  const ctl = hv.fitAbort = new AbortController();
  $('fitbtn').textContent = 'stop fit';
  say('fitting ' + keys.join(', ') + '…');
  const my = ++hv.seq;
  try {
    const r = await fetch('/api/fit?' + query() + '&free=' + enc(keys.join(',')) + '&page=' + hv.page + '&seq=' + my,
      { method: 'POST', signal: ctl.signal });
    const j = await r.json();
    if (hv.fitAbort !== ctl) return; // stopped meanwhile
    if (r.status === 200) {
      hv.fit = j;
      for (const p of j.params) {
        const c = ctlOf(p.key), v = String(p.estimate);
        if (c && v === c.value) delete hv.sets[p.key]; else hv.sets[p.key] = v;
      }
      hv.preset = null;
      buildControls(hv.info);
      showFit(j);
      pushUrl(false);
      requestRender();
    } else if (r.status === 409) say('fit stopped: the page asked for something newer');
    else showError(j.error || ('HTTP ' + r.status));
  } catch (e) {
    if (e.name !== 'AbortError') showError('the fit got no answer: ' + e);
  }
  if (hv.fitAbort === ctl) { hv.fitAbort = null; const b = $('fitbtn'); if (b) b.textContent = 'fit to data'; }
}

// ---- rendering -------------------------------------------------------------

function query() {
  let q = 'scene=' + enc(hv.info.file);
  for (const [k, v] of Object.entries(hv.sets)) q += '&set=' + enc(k + '=' + v);
  return q;
}

function requestRender() {
  if (!hv.info) return;
  animSetsChanged();
  if (hv.inflight) { hv.pending = true; return; }
  doRender();
}

async function doRender() {
  hv.inflight = true;
  hv.pending = false;
  const my = ++hv.seq, t0 = performance.now();
  const q = query();
  try {
    const r = await fetch('/api/render?' + q + '&fmt=json&page=' + hv.page + '&seq=' + my);
    const j = await r.json();
    if (r.status === 503 && (hv.busyRetries = (hv.busyRetries || 0) + 1) <= 5) {
      // the server gave this turn to another client and asks to come back: again after Retry-After
      // (a newer request already waiting goes instead, at once; no error is shown for this one)
      if (!hv.pending) await new Promise(res => setTimeout(res, 1000 * (Number(r.headers.get('Retry-After')) || 1)));
      hv.pending = true;
    } else {
      hv.busyRetries = 0;
      if (r.status === 200) show(j, q, t0);
      else if (r.status !== 409) showError(j.error || ('HTTP ' + r.status));
    }
  } catch (e) {
    showError('the server did not answer: ' + e);
  }
  hv.inflight = false;
  if (hv.pending) doRender();
  else if (hv.sliderPlay) requestAnimationFrame(sliderPlayStep); // the next step once the server has answered
}

function show(j, q, t0) {
  const fig = $('figure');
  fig.innerHTML = j.svg;
  delete fig.dataset.title; // this figure's own <title>, if it has one (labelFigure)
  drawGhost();
  fig.classList.remove('stale');
  hv.svg = j.svg;
  hv.cmd = j.cmd;
  hv.error = null;
  hv.map = j.map;
  hv.serverMs = 1000 * j.seconds;
  hv.serverCpuMs = 1000 * j.cpu;
  hv.work = j.work;
  hv.budget = j.budget;
  hv.pageMs = performance.now() - t0;
  hv.renders++;
  $('cmd').textContent = j.cmd;
  if (typeof j.caption === 'string') $('caption').textContent = j.caption; // its placeholders say the values drawn
  labelFigure();
  $('message').hidden = true;
  for (const e of document.querySelectorAll('.ctl .err')) e.textContent = '';
  $('status').textContent = 'live · render ' + hv.serverMs.toFixed(1) + ' ms on the server, ' + hv.pageMs.toFixed(1) + ' ms in the page';
  $('measured').textContent = j.errors.length
    ? j.errors.map(e => e.series + ': max error ' + e.err.toPrecision(3) + ' against the ' + (e.ref || 'exact answer')).join(' · ')
    : 'no exact answer to compare with';
  const dl = $('downloads');
  dl.replaceChildren('download:', ...['svg', 'pdf', 'png', 'csv'].map(f =>
    el('a', { href: '/api/render?' + q + '&fmt=' + f + '&name=download', download: '', 'aria-label': 'download ' + f.toUpperCase() },
      f.toUpperCase())));
  hv.hover = null;
  clearTimeout(hv.hoverTimer);
  hv.hoverTimer = setTimeout(() => loadHover(q), 300);
  document.dispatchEvent(new CustomEvent('hv-rendered'));
}

// a message next to one control, the figure and values unchanged
function showNote(key, msg) {
  for (const e of document.querySelectorAll('.ctl .err')) e.textContent = e.dataset.key === key ? msg : '';
}

function showError(msg) {
  // the CLI's message without its "--set KEY=VALUE: " (the control says which)
  const m = /^--set ([^=:\s]+)=[^:]*: /.exec(msg);
  if (m && hv.info && hv.info.controls.some(c => c.key === m[1])) { msg = msg.slice(m[0].length); hv.lastKey = m[1]; }
  hv.error = msg;
  $('message').textContent = msg;
  $('message').hidden = false;
  say(msg, true);
  $('figure').classList.add('stale');
  labelFigure();
  // next to the control the message names, else the one moved last
  let key = null;
  if (hv.info) for (const c of hv.info.controls) if (msg.includes(c.key + '=')) key = c.key;
  key = key || hv.lastKey;
  for (const e of document.querySelectorAll('.ctl .err')) e.textContent = e.dataset.key === key ? msg : '';
  document.dispatchEvent(new CustomEvent('hv-error'));
}

// ---- compare: pins, the curves shown now kept under the next ones ---------------
// A figure's curves are its unfilled, round-joined strokes (axes, ticks and
// frames are mitre-joined, text is filled glyphs): copied from the SVG pinned,
// each in a lighter tone of its own colour (mixed with the background), drawn
// just before the new figure's first curve so the new curves lie on top, and
// labelled at the end of its longest curve with the values that made it
// ("σ0 = 6").  Several are kept; each has a chip with × to remove it.  The
// server's SVG (hv.svg) stays as it came.

function curvesOf(svgText) {
  const doc = new DOMParser().parseFromString(svgText, 'image/svg+xml');
  return Array.from(doc.querySelectorAll('path')).filter(p => {
    const st = p.getAttribute('style') || '';
    return /fill:none/.test(st) && /stroke-linejoin:round/.test(st);
  });
}

// "σ0 = 6, u_min,2 = 0.3": the main controls' values now (parts: [symbol markup, plain name, value])
function pinParts() {
  return mainControls(hv.info).map(c => [c.sym, ctlName(c), curOf(c)]);
}
// the label as nodes: each symbol typeset as its slider's label (HTML: sub/sup; SVG: tspans)
function pinNodes(parts, svg) {
  const out = [];
  parts.forEach(([sym, name, v], k) => {
    if (k) out.push(', ');
    if (!sym) out.push(name);
    else if (!svg) out.push(typeset(sym));
    else out.push(...typeset(sym, true));
    out.push(' = ' + v);
  });
  return out;
}

// a colour of the SVG (cairo writes rgb(R%,G%,B%) or #rrggbb) mixed with bg: t of the way
function lighter(col, bg, t) {
  let v = null, m;
  if ((m = /rgb\(\s*([\d.]+)%\s*,\s*([\d.]+)%\s*,\s*([\d.]+)%\s*\)/.exec(col))) v = [m[1], m[2], m[3]].map(x => 2.55 * x);
  else if ((m = /rgb\(\s*([\d.]+)\s*,\s*([\d.]+)\s*,\s*([\d.]+)\s*\)/.exec(col))) v = [+m[1], +m[2], +m[3]];
  else if ((m = /^#([0-9a-f]{6})$/i.exec(col))) v = [0, 2, 4].map(k => parseInt(m[1].slice(k, k + 2), 16));
  if (!v) return col;
  return 'rgb(' + v.map((x, k) => Math.round(x + (bg[k] - x) * t)).join(',') + ')';
}

// whether an SVG colour is a colour (not black, grey or white): its channels differ by more than 15 %
function coloured(col) {
  const v = lighter(col, [0, 0, 0], 0).match(/\d+/g);
  return !!v && v.length === 3 && Math.max(...v.map(Number)) - Math.min(...v.map(Number)) > 38;
}

function addPin() {
  if (!hv.svg || !hv.info) return;
  const parts = pinParts(), label = parts.map(p => p[1] + ' = ' + p[2]).join(', ');
  if (hv.pins.some(p => p.label === label)) return; // that one is kept already
  hv.pinSeq = (hv.pinSeq || 0) + 1;
  hv.pins.push({ id: hv.pinSeq, label, parts, curves: curvesOf(hv.svg) });
  pinList();
  redrawPins();
}

function removePin(id) {
  hv.pins = hv.pins.filter(p => p.id !== id);
  pinList();
  redrawPins();
}

function pinList() {
  const box = $('pins');
  if (!box) return;
  box.replaceChildren(...hv.pins.map(p => el('span', { class: 'pinchip', 'data-pin': p.id, title: p.label }, 'pin: ', ...pinNodes(p.parts),
    el('button', { type: 'button', class: 'dismiss', 'aria-label': 'remove pin ' + p.label, title: 'remove this pin',
      onclick: () => removePin(p.id) }, '×'))));
  box.hidden = !hv.pins.length;
  labelFigure();
}

function redrawPins() {
  const svg = $('figure').querySelector('svg');
  if (!svg) return;
  for (const g of svg.querySelectorAll('g.ghost, text.pinlabel')) g.remove();
  drawGhost();
}

function drawGhost() {
  const svg = $('figure').querySelector('svg');
  if (!svg || !hv.pins.length) return;
  const slides = hv.sets['figure.theme'] === 'slides', bg = slides ? [28, 31, 36] : [255, 255, 255];
  const vb = svg.viewBox && svg.viewBox.baseVal, fs = vb && vb.height ? vb.height / 36 : 10;
  const first = Array.from(svg.querySelectorAll('path')).find(p => /fill:none/.test(p.getAttribute('style') || '')
    && /stroke-linejoin:round/.test(p.getAttribute('style') || ''));
  const NS = 'http://www.w3.org/2000/svg';
  hv.pins.forEach((pin, k) => {
    const g = document.createElementNS(NS, 'g');
    g.setAttribute('class', 'ghost');
    g.setAttribute('data-pin', pin.id);
    const t = 0.5 + 0.12 * Math.min(2, hv.pins.length - 1 - k); // older pins fainter
    let end = null, best = -1;
    for (const p of pin.curves) {
      const q = document.importNode(p, true), st = q.getAttribute('style') || '';
      q.setAttribute('style', st.replace(/stroke:([^;]+)/, (_, c) => 'stroke:' + lighter(c.trim(), bg, t)));
      g.append(q);
      // the label at the end of the longest coloured curve (black, grey and white ones are the references)
      const d = q.getAttribute('d') || '', nums = d.match(/-?[\d.]+(e-?\d+)?/g) || [];
      const score = d.length + (coloured((/stroke:([^;]+)/.exec(st) || [])[1] || '') ? 1e9 : 0);
      if (nums.length >= 2 && score > best) { best = score; end = [+nums[nums.length - 2], +nums[nums.length - 1]]; }
    }
    if (first) first.parentNode.insertBefore(g, first); else svg.append(g);
    if (end) { // on top of the figure, with a halo of the background
      const tx = document.createElementNS(NS, 'text'), right = vb && vb.width && end[0] > vb.x + 0.6 * vb.width;
      tx.setAttribute('x', end[0] + (right ? -fs * 0.4 : fs * 0.4)); // inside the figure: to the left of a point on the right
      tx.setAttribute('y', end[1] + (end[1] < (vb ? vb.y : 0) + 2 * fs ? 1.2 * fs : -fs * 0.4));
      tx.setAttribute('text-anchor', right ? 'end' : 'start');
      tx.setAttribute('font-size', fs);
      tx.setAttribute('font-family', 'STIXGeneral, DejaVu Serif, serif');
      tx.setAttribute('fill', slides ? '#c8ccd4' : '#444');
      tx.setAttribute('stroke', slides ? '#1c1f24' : '#fff');
      tx.setAttribute('stroke-width', fs * 0.25);
      tx.setAttribute('paint-order', 'stroke');
      tx.setAttribute('class', 'pinlabel');
      tx.setAttribute('data-pin', pin.id);
      tx.setAttribute('font-style', 'italic');
      tx.setAttribute('aria-label', pin.label);
      tx.append(...pinNodes(pin.parts, true));
      svg.append(tx);
    }
  });
}

// ---- hold the axes: figure.xlim and figure.ylim set from the limits drawn ---------
// Held, the figure is what `hystviz render … --set figure.xlim=… --set
// figure.ylim=…` writes (the command line shows them).  Played or dragged, a
// slider holds them over its whole range: the union of the limits the server
// draws at the slider's two ends and now (two renders, JSON, the map of the
// first panel; a drag holds them if it still goes on when those two are
// in).  l (or the button) releases them.

function roundOut(lo, hi) {
  const w = hi - lo;
  if (!(w > 0) || !isFinite(w)) return [lo, hi];
  const st = Math.pow(10, Math.floor(Math.log10(w)) - 2);
  const f = x => parseFloat(x.toPrecision(12));
  return [f(Math.floor(lo / st) * st), f(Math.ceil(hi / st) * st)];
}

function setLimits(m) {
  if (!m) return;
  const x = m.xlog ? [m.xlo, m.xhi] : roundOut(m.xlo, m.xhi), y = m.ylog ? [m.ylo, m.yhi] : roundOut(m.ylo, m.yhi);
  hv.sets['figure.xlim'] = x[0] + ', ' + x[1];
  hv.sets['figure.ylim'] = y[0] + ', ' + y[1];
  hv.axesHeld = { x, y };
}

// held or not as hv.sets say (a link, back/forward, a preset, reset)
function syncHeld() {
  const x = hv.sets['figure.xlim'], y = hv.sets['figure.ylim'];
  hv.axesHeld = x || y ? { x, y } : null;
  holdButton();
}

function holdButton() {
  const b = $('hold');
  if (b) {
    b.textContent = hv.axesHeld ? 'axes held (l)' : 'hold axes (l)';
    b.classList.toggle('on', !!hv.axesHeld);
    b.setAttribute('aria-pressed', String(!!hv.axesHeld));
  }
}

function holdAxes(on) {
  if (!hv.info) return;
  if (on && hv.map) setLimits(hv.map);
  else { hv.axesHeld = null; delete hv.sets['figure.xlim']; delete hv.sets['figure.ylim']; }
  holdButton();
  pushUrl(false);
  requestRender();
}

// the limits the server draws with KEY=VALUE (the others as now, the axes free)
async function limitsAt(key, value, tag) {
  let q = 'scene=' + enc(hv.info.file);
  for (const [k, v] of Object.entries(hv.sets))
    if (k !== key && k !== 'figure.xlim' && k !== 'figure.ylim') q += '&set=' + enc(k + '=' + v);
  q += '&set=' + enc(key + '=' + value);
  try {
    // a page id of its own each (both render side by side; neither replaces the figure's request)
    const r = await fetch('/api/render?' + q + '&fmt=json&page=' + hv.page + 'l' + tag + '&seq=' + (hv.limSeq = (hv.limSeq || 0) + 1));
    if (r.status !== 200) return null;
    return (await r.json()).map || null;
  } catch (e) { return null; }
}

// holds the axes over the whole range of slider KEY (unless held already)
async function holdForRange(key) {
  if (hv.axesHeld || hv.holding || !hv.map || !hv.info) return;
  const c = ctlOf(key);
  if (!c) return;
  hv.holding = true;
  const now = hv.map, file = hv.info.file;
  const [a, b] = await Promise.all([limitsAt(key, valueAt(c, 0), 0), limitsAt(key, valueAt(c, 1000), 1)]);
  hv.holding = false;
  // still playing or dragging that slider (let go meanwhile: the figure stays as it is)
  const moving = (hv.sliderPlay && hv.sliderPlay.key === key) || (hv.dragging && hv.frozen && hv.frozen.key === key);
  if (!hv.info || hv.info.file !== file || hv.axesHeld || !moving) return;
  const u = { xlo: now.xlo, xhi: now.xhi, ylo: now.ylo, yhi: now.yhi, xlog: now.xlog, ylog: now.ylog };
  for (const m of [a, b]) if (m && m.xlog === u.xlog && m.ylog === u.ylog) {
    u.xlo = Math.min(u.xlo, m.xlo); u.xhi = Math.max(u.xhi, m.xhi);
    u.ylo = Math.min(u.ylo, m.ylo); u.yhi = Math.max(u.yhi, m.yhi);
  }
  setLimits(u);
  holdButton();
  requestRender();
}

// ---- play a slider (Desmos): its value back and forth over its domain -----------
// One step each time the server has answered the last one (never two requests
// at once), 1/50 of the slider's travel; the values are the slider's own
// (valueAt: inside the domain given the other values).  Stopped by its button,
// space, a preset, reset or another scene.

const PLAY_STEP = 20; // of the slider's 1000 positions
const PLAY_MS = 50;   // at 1x at most one step each 50 ms (20 a second): 1/speed times that

// the play speed (¼×, ½×, 1×, 2×) of clips and of a slider's ▶: one for both
const SPEEDS = [0.25, 0.5, 1, 2];
function speedText(v) { return v === 0.25 ? '¼×' : v === 0.5 ? '½×' : v + '×'; }
function speedSelect(id) {
  const s = el('select', { id, class: 'speedsel', 'aria-label': 'play speed', title: '[ and ]: play speed of clips and of a slider\'s ▶',
    onchange: ev => setSpeed(+ev.target.value) }, ...SPEEDS.map(v => el('option', { value: v }, speedText(v))));
  s.value = String(hv.speed);
  return s;
}
function setSpeed(v) {
  if (!SPEEDS.includes(v)) return;
  hv.speed = v;
  for (const s of document.querySelectorAll('select.speedsel')) s.value = String(v);
  if (hv.playing) { anim.due = performance.now(); }
}
function speedStep(dir) {
  const k = SPEEDS.indexOf(hv.speed) + dir;
  if (k >= 0 && k < SPEEDS.length) setSpeed(SPEEDS[k]);
  flash('speed ' + speedText(hv.speed));
}

function toggleSliderPlay(key) {
  const was = hv.sliderPlay && hv.sliderPlay.key;
  sliderPlayStop();
  if (was === key) return;
  const c = ctlOf(key), r = $('controls').querySelector('input[type=range][data-key="' + key + '"]');
  if (!c || !r) return;
  hv.sliderPlay = { key, dir: +r.value >= 1000 ? -1 : 1, pos: +r.value, steps: 0, at: 0 };
  hv.lastKey = key;
  hv.frozen = { key, d: domain(c) };
  hv.dragging = true; // one change in the history, the domain held
  playButtons();
  holdForRange(key); // the axes hold over the slider's whole range
  if (!hv.inflight) sliderPlayStep();
}

function sliderPlayStop() {
  if (!hv.sliderPlay) return;
  clearTimeout(hv.sliderPlay.timer);
  hv.sliderPlay = null;
  hv.dragging = false;
  playButtons();
  syncSliders();
  pushUrl(true);
}

function playButtons() {
  for (const b of document.querySelectorAll('button.playkey')) {
    const on = !!hv.sliderPlay && hv.sliderPlay.key === b.dataset.key;
    b.textContent = on ? '■' : '▶';
    b.classList.toggle('on', on);
    b.setAttribute('aria-pressed', String(on));
  }
}

function sliderPlayStep() {
  const sp = hv.sliderPlay;
  if (!sp || hv.inflight) return;
  const wait = sp.at + PLAY_MS / hv.speed - performance.now();
  if (wait > 1) { clearTimeout(sp.timer); sp.timer = setTimeout(sliderPlayStep, wait); return; }
  const r = $('controls').querySelector('input[type=range][data-key="' + sp.key + '"]');
  if (!r) { sliderPlayStop(); return; }
  let p = sp.pos + sp.dir * PLAY_STEP;
  if (p >= 1000) { p = 1000; sp.dir = -1; } else if (p <= 0) { p = 0; sp.dir = 1; }
  sp.pos = p;
  sp.steps++;
  sp.at = performance.now();
  r.value = p;
  r.dispatchEvent(new Event('input'));
}

// one step (1/50 of the travel) of the slider played, else the one moved last,
// else the first main one; a play stops there
function sliderStep(dir) {
  if (!hv.info) return;
  const key = (hv.sliderPlay && hv.sliderPlay.key) || (hv.lastKey && ctlOf(hv.lastKey) && hv.lastKey)
    || (mainControls(hv.info)[0] || {}).key;
  sliderPlayStop();
  const r = key && $('controls').querySelector('input[type=range][data-key="' + key + '"]');
  if (r) stepSlider(r, dir);
}

// ---- values under the cursor -------------------------------------------------

async function loadHover(q) {
  if (q !== query()) return;
  try {
    const r = await fetch('/api/render?' + q + '&fmt=json&hover=1');
    if (r.status !== 200) return;
    const j = await r.json();
    if (q === query()) hv.hover = j;
  } catch (e) { /* no hover this time */ }
}

function nearest(px, py) {
  const m = hv.hover.map;
  const tr = (v, lg) => lg ? Math.log10(v) : v;
  const sx = x => m.x0 + (tr(x, m.xlog) - tr(m.xlo, m.xlog)) / (tr(m.xhi, m.xlog) - tr(m.xlo, m.xlog)) * m.w;
  const sy = y => m.y0 + m.h - (tr(y, m.ylog) - tr(m.ylo, m.ylog)) / (tr(m.yhi, m.ylog) - tr(m.ylo, m.ylog)) * m.h;
  let best = null, bd = Infinity;
  for (const s of hv.hover.series) {
    for (let i = 0; i < s.x.length; i++) {
      if (s.x[i] === null) continue;
      const dx = sx(s.x[i]) - px, dy = sy(s.y[i]) - py, d = dx * dx + dy * dy;
      if (d < bd) { bd = d; best = { name: s.name, x: s.x[i], y: s.y[i] }; }
    }
  }
  return bd <= 144 ? best : null; // within 12 pt
}

$('figure').addEventListener('mousemove', ev => {
  const svg = $('figure').querySelector('svg'), tip = $('tip');
  if (!svg || !hv.hover) { tip.hidden = true; return; }
  const pt = svg.createSVGPoint();
  pt.x = ev.clientX; pt.y = ev.clientY;
  const p = pt.matrixTransform(svg.getScreenCTM().inverse());
  const hit = nearest(p.x, p.y);
  if (!hit) { tip.hidden = true; return; }
  const xn = hv.hover.xname || 'x';
  tip.textContent = hit.name + ': ' + xn + ' = ' + hit.x.toPrecision(5) + ', y = ' + hit.y.toPrecision(5);
  const box = $('figbox').getBoundingClientRect();
  tip.style.left = (ev.clientX - box.left + 12) + 'px';
  tip.style.top = (ev.clientY - box.top + 12) + 'px';
  tip.hidden = false;
});
$('figure').addEventListener('mouseleave', () => { $('tip').hidden = true; });

// ---- animations ------------------------------------------------------------------
// Frames are PNGs from the server's warm frame workers: byte for byte `hystviz animate
// SCENE --frames i:i+1 --set …` (the sliders' overrides).  Playing streams windows of
// frames ahead (/api/frames), decodes a few ahead (createImageBitmap) and shows the
// frames one by one at the clip's rate on a canvas, so the scene's easing is seen as
// written; a frame not there yet holds the clock (the clip slows, it never skips).
// A slider moved while playing drops what was fetched for the old values: the next
// frames shown use the new ones.  Paused, frame i comes alone (/api/frame).

const anim = hv.anim = {
  n: 0, fps: 30, key: '', png: new Map(), bmp: new Map(), decoding: new Set(), bad: new Map(),
  stream: null, streamEnd: -1, pos: 0, last: 0, shown: 0, stalls: 0, raf: 0, error: null,
  skipped: 0, viaImg: 0, loop: true,
};
const WINDOW_S = 2;     // seconds of frames asked for ahead by one stream
const DECODE_AHEAD = 8; // frames decoded ahead of the one shown
const DECODE_PAR = 3;   // decodes at a time
const BUFFER = 6;       // frames decoded ahead before the clock runs
const DEBT = 8;         // clip frames a late page may make up (then the clip slows instead)

function animKey() {
  return hv.info ? hv.info.file + '\n' + Object.entries(hv.sets).map(([k, v]) => k + '=' + v).join('\n') : '';
}

function animSets() {
  let q = '';
  if (hv.info && !hv.info.builtin) for (const [k, v] of Object.entries(hv.sets)) q += '&set=' + enc(k + '=' + v);
  return q;
}

function animClear() {
  if (anim.stream) anim.stream.abort();
  anim.stream = null;
  anim.streamEnd = -1;
  for (const b of anim.bmp.values()) b.close();
  anim.png.clear();
  anim.bmp.clear();
  anim.decoding.clear();
  anim.bad.clear();
  frameWarn('');
  anim.key = animKey();
}

// the sliders changed (called by requestRender): frames not yet shown use the new values
function animSetsChanged() {
  if (!hv.info || !hv.info.anim || anim.key === animKey()) return;
  animClear();
  if (hv.playing) animFetch();
  else requestFrame(+$('scrub').value);
}

function setupAnim(info, keep) {
  const sec = $('anim');
  animStop();
  animClear();
  document.body.classList.toggle('anim', !!info.anim);
  if (!info.anim) { sec.hidden = true; return; }
  sec.hidden = false;
  if (info.anim.error) {
    $('frameinfo').textContent = info.anim.error;
    $('framenote').textContent = '';
    return;
  }
  anim.n = info.anim.frames;
  anim.fps = info.anim.fps || 30;
  $('scrub').max = anim.n - 1;
  if (!keep) { $('scrub').value = 0; hv.frame = -1; }
  $('framenote').textContent = 'Frame i is the PNG that `hystviz animate ' + info.path
    + (info.builtin ? '' : ' --set …') + ' --frames i:i+1` writes (OpenGL, from a warm hystviz-animate worker); '
    + 'play shows ' + anim.fps + ' frames a second' + (info.builtin ? '.' : ', with the values of the sliders above.');
  requestFrame(+$('scrub').value);
  fitFrame();
}

function showBitmap(b) {
  const c = $('frame');
  if (c.width !== b.width || c.height !== b.height) { c.width = b.width; c.height = b.height; fitFrame(); }
  c.getContext('2d').drawImage(b, 0, 0);
}

// A frame's PNG as something the canvas draws: createImageBitmap, else an
// <img> from a blob URL (decode()), which some PNGs that createImageBitmap
// refuses pass (issue 38: an incomplete Huffman code zlib tolerates); its
// close() frees the URL.  Rejects with the reason where neither decodes.
async function decodeFrame(buf) {
  const blob = new Blob([buf], { type: 'image/png' });
  let first;
  try { return await createImageBitmap(blob); } catch (e) { first = e; }
  const url = URL.createObjectURL(blob), img = new Image();
  try {
    img.src = url;
    await img.decode();
    anim.viaImg++;
    img.close = () => URL.revokeObjectURL(url);
    return img;
  } catch (e) {
    URL.revokeObjectURL(url);
    throw new Error('this browser cannot decode its PNG (' + buf.byteLength + ' bytes; ' + (first && first.message || first) + ')');
  }
}

// the line under the clip that says which frames were skipped and why (stays until the clip changes)
function frameWarn(msg) {
  const w = $('framewarn');
  if (!w) return;
  w.textContent = msg;
  w.hidden = !msg;
  if (msg) say(msg);
}

// The presentation view: the frame as large as the space left for it allows, its aspect kept
function fitFrame() {
  const c = $('frame'), box = $('framebox');
  if (!c || !box) return;
  if (!hv.present) { c.style.width = c.style.height = ''; return; }
  const w = box.clientWidth, h = box.clientHeight, s = Math.min(w / c.width, h / c.height);
  if (!(s > 0)) return;
  c.style.width = Math.floor(c.width * s) + 'px';
  c.style.height = Math.floor(c.height * s) + 'px';
}
window.addEventListener('resize', fitFrame);
if (window.ResizeObserver) new ResizeObserver(fitFrame).observe($('framebox'));

function b64(buf) {
  let s = '';
  const u8 = new Uint8Array(buf);
  for (let k = 0; k < u8.length; k += 0x8000) s += String.fromCharCode.apply(null, u8.subarray(k, k + 0x8000));
  return btoa(s);
}

// ---- paused: one frame at a time

function requestFrame(i) {
  if (hv.playing) return;
  if (hv.frameInflight) { hv.framePending = i; return; }
  loadFrame(i);
}

async function loadFrame(i) {
  hv.frameInflight = true;
  hv.framePending = -1;
  const my = ++hv.frameSeq, key = animKey();
  $('frameinfo').textContent = 'frame ' + i + ' / ' + anim.n + ' (rendering…)';
  let buf = anim.png.get(i);
  try {
    if (!buf) {
      const r = await fetch('/api/frame?scene=' + enc(hv.info.file) + animSets() + '&frame=' + i + '&page=' + hv.page + 'f&seq=' + my);
      if (r.status === 200) buf = await r.arrayBuffer();
      else if (r.status !== 409) {
        const j = await r.json().catch(() => ({}));
        $('frameinfo').textContent = 'frame ' + i + ': ' + (j.error || 'HTTP ' + r.status);
      }
    }
  } catch (e) {
    $('frameinfo').textContent = 'frame ' + i + ': the server did not answer (' + e.message + ')';
  }
  if (buf && key === animKey() && !hv.playing) {
    try {
      const b = await decodeFrame(buf);
      showBitmap(b);
      b.close();
      $('frameinfo').textContent = 'frame ' + i + ' / ' + anim.n + ' · ' + clipTime(i);
      labelFrame(i);
    } catch (e) { // the server answered: the frame is here, the browser cannot show it
      $('frameinfo').textContent = 'frame ' + i + ' / ' + anim.n + ' · ' + clipTime(i);
      frameWarn('frame ' + i + ' came from the server, but ' + e.message + '; the frame before it stays on screen');
    }
    hv.frameB64 = b64(buf);
    hv.frame = i;
    document.dispatchEvent(new CustomEvent('hv-frame'));
  }
  hv.frameInflight = false;
  if (hv.framePending >= 0 && !hv.playing) loadFrame(hv.framePending);
}

// ---- playing: streamed windows, decoded ahead, shown at the clip's rate

// Fetches the next window of frames not yet here, from the one being shown.
function animFetch() {
  if (anim.stream || !hv.playing) return;
  let from = anim.pos, k = 0;
  while (k < anim.n && anim.png.has(from)) { from = (from + 1) % anim.n; k++; }
  if (k >= Math.ceil(WINDOW_S * anim.fps) || k === anim.n) return; // enough ahead
  const to = Math.min(anim.n, from + Math.ceil(WINDOW_S * anim.fps));
  const ctl = new AbortController(), key = anim.key;
  anim.stream = ctl;
  anim.streamEnd = to;
  const url = '/api/frames?scene=' + enc(hv.info.file) + animSets() + '&from=' + from + '&to=' + to
    + '&page=' + hv.page + 's&seq=' + (++hv.frameSeq);
  readStream(url, ctl, key).finally(() => {
    if (anim.stream === ctl) { anim.stream = null; animFetch(); }
  });
}

// Reads records "TAG NUM LEN\n<bytes>" (anim_worker.h) as they arrive.  The
// chunks wait in a list until a record is whole and are then joined once, so
// each byte is copied once: joining every chunk onto what was left (as this
// did before) copied a stream's bytes again per record and held the page's
// main thread for 40-70 ms when the network handed over many frames at once.
async function readStream(url, ctl, key) {
  let r;
  try { r = await fetch(url, { signal: ctl.signal }); } catch (e) { return; }
  if (r.status !== 200) {
    const j = await r.json().catch(() => ({}));
    if (r.status !== 409) animFail(j.error || ('HTTP ' + r.status));
    return;
  }
  const rd = r.body.getReader(), text = new TextDecoder();
  const parts = [];
  let have = 0, head = null;
  const take = n => { // the first n bytes waiting, as one array of their own
    const out = new Uint8Array(n);
    for (let k = 0; k < n;) {
      const p = parts[0], m = Math.min(p.length, n - k);
      out.set(m === p.length ? p : p.subarray(0, m), k);
      k += m;
      if (m === p.length) parts.shift(); else parts[0] = p.subarray(m);
    }
    have -= n;
    return out;
  };
  const lineEnd = () => { // where the header line waiting ends, or -1
    for (let k = 0, at = 0; k < parts.length; at += parts[k].length, k++) {
      const i = parts[k].indexOf(10);
      if (i >= 0) return at + i;
    }
    return -1;
  };
  try {
    for (;;) {
      const { done, value } = await rd.read();
      if (done) return;
      parts.push(value);
      have += value.length;
      for (;;) {
        if (!head) {
          const nl = lineEnd();
          if (nl < 0) break;
          const [tag, num, len] = text.decode(take(nl + 1)).trim().split(' ');
          head = { tag, num: +num, len: +len };
          if (!(head.len >= 0)) { animFail('the server sent a frame stream this page cannot read'); return; }
        }
        if (have < head.len) break;
        const data = take(head.len), h = head;
        head = null;
        if (key !== anim.key) return;
        if (h.tag === 'frame') { anim.png.set(h.num, data.buffer); decodeAhead(); }
        else if (h.tag === 'error') { animFail(text.decode(data)); return; }
      }
    }
  } catch (e) { /* aborted: the sliders moved or play stopped */ }
}

function animFail(msg) {
  anim.error = msg;
  $('frameinfo').textContent = 'frame ' + anim.pos + ': ' + msg;
  say('frame ' + anim.pos + ': ' + msg, true);
  animStop();
}

// Decodes the frames about to be shown; closes those behind.
function decodeAhead() {
  const cur = anim.pos;
  for (const [i, b] of anim.bmp) {
    const ahead = (i - cur + anim.n) % anim.n;
    if (ahead > DECODE_AHEAD) { b.close(); anim.bmp.delete(i); }
  }
  for (let d = 0; d <= DECODE_AHEAD; d++) {
    const i = (cur + d) % anim.n, buf = anim.png.get(i), key = anim.key;
    if (!buf || anim.bmp.has(i) || anim.decoding.has(i)) continue;
    if (anim.decoding.size >= DECODE_PAR) break;
    if (anim.bad.has(i)) continue;
    anim.decoding.add(i);
    decodeFrame(buf).then(b => {
      anim.decoding.delete(i);
      if (key === anim.key) { anim.bmp.set(i, b); decodeAhead(); } else b.close();
    }, e => { // neither decoder takes it: skipped when due, with a note (play goes on)
      anim.decoding.delete(i);
      if (key === anim.key) anim.bad.set(i, e.message);
    });
  }
}

// Frame anim.pos is due at anim.due; each display frame shows at most one clip
// frame, so none is skipped: a late display frame (the page held up, or the
// frame not yet decoded) is made up by the next ones, at most DEBT clip frames
// (a longer wait slows the clip rather than racing it).  The clock waits for
// BUFFER frames decoded ahead when play starts, as a video player buffers.
function bufferedAhead() {
  const want = Math.min(BUFFER, anim.n);
  let k = 0;
  while (k < want && (anim.bmp.has((anim.pos + k) % anim.n) || anim.bad.has((anim.pos + k) % anim.n))) k++;
  return k >= want;
}

function tick(now) {
  if (!hv.playing) return;
  const i = anim.pos, period = 1000 / (anim.fps * hv.speed);
  if (anim.buffering) {
    if (bufferedAhead() || now - anim.bufferSince > 1000) { anim.buffering = false; anim.due = now; }
    else anim.stalls++;
  }
  if (!anim.buffering && now + 2 >= anim.due) { // due (2 ms early is on time: display frames are not exact)
    const b = anim.bmp.get(i);
    if (!b && anim.bad.has(i)) { // undecodable: skipped, said under the clip, and play goes on
      anim.skipped++;
      frameWarn('frame ' + i + ' skipped: it came from the server, but ' + anim.bad.get(i)
        + (anim.skipped > 1 ? ' (' + anim.skipped + ' frames skipped so far)' : ''));
      anim.pos = (i + 1) % anim.n;
      anim.due = Math.max(anim.due + period, now - DEBT * period);
    } else if (b) {
      showBitmap(b);
      if (anim.shown && now - anim.shownAt > anim.maxGap) anim.maxGap = now - anim.shownAt;
      anim.shownAt = now;
      hv.frame = i;
      anim.shown++;
      anim.pos = (i + 1) % anim.n;
      anim.due = Math.max(anim.due + period, now - DEBT * period);
      if (i === anim.n - 1 && !anim.loop) { animStop(); return; } // the last frame, loop off: stop there
    } else anim.stalls++; // not decoded yet: shown when it is, and the frames after it catch up
  }
  if (now - (anim.textAt || 0) > 250) { // the scrubber and the line below it 4 times a second: no layout per frame
    anim.textAt = now;
    $('scrub').value = hv.frame;
    const rate = anim.shown / Math.max(1e-3, (now - anim.t0) / 1000);
    $('frameinfo').textContent = 'frame ' + hv.frame + ' / ' + anim.n + ' · ' + clipTime(hv.frame) + ' · '
      + rate.toFixed(0) + ' of the ' + +(anim.fps * hv.speed).toFixed(2) + ' frames/s shown';
    labelFrame(hv.frame);
  }
  decodeAhead();
  animFetch();
  anim.raf = requestAnimationFrame(tick);
}

function animPlay() {
  if (!hv.info || !hv.info.anim || !anim.n) return;
  hv.playing = true;
  $('play').textContent = 'pause';
  anim.error = null;
  anim.pos = (+$('scrub').value + 1) % anim.n;
  if (!anim.loop && +$('scrub').value >= anim.n - 1) anim.pos = 0; // loop off, at the end: from the start
  anim.skipped = 0;
  anim.last = anim.due = anim.bufferSince = performance.now();
  anim.buffering = true;
  anim.shown = 0;
  anim.stalls = 0;
  anim.maxGap = 0;
  anim.t0 = anim.last;
  animFetch();
  anim.raf = requestAnimationFrame(tick);
}

// "1.20 s / 6.00 s": the clip time of frame i
function clipTime(i) {
  return (Math.max(0, i) / anim.fps).toFixed(2) + ' s / ' + (anim.n / anim.fps).toFixed(2) + ' s';
}

// one frame back or on (paused there; at the ends it wraps when loop is on)
function frameStep(dir) {
  if (!hv.info || !hv.info.anim || !anim.n) return;
  if (hv.playing) animStop();
  let i = +$('scrub').value + dir;
  if (i < 0) i = anim.loop ? anim.n - 1 : 0;
  if (i >= anim.n) i = anim.loop ? 0 : anim.n - 1;
  $('scrub').value = i;
  requestFrame(i);
}

function animStop() {
  if (anim.stream) anim.stream.abort();
  anim.stream = null;
  cancelAnimationFrame(anim.raf);
  const was = hv.playing;
  hv.playing = false;
  $('play').textContent = 'play';
  if (was && hv.frame >= 0) $('scrub').value = hv.frame;
  if (was && hv.frame >= 0 && anim.png.has(hv.frame)) { // paused on frame i: its bytes, as the scrubber's
    hv.frameB64 = b64(anim.png.get(hv.frame));
    $('frameinfo').textContent = 'frame ' + hv.frame + ' / ' + anim.n + ' · ' + clipTime(hv.frame);
    document.dispatchEvent(new CustomEvent('hv-frame'));
  }
  if (hv.frame >= 0) labelFrame(hv.frame);
}

$('scrub').addEventListener('input', () => { if (hv.playing) animStop(); requestFrame(+$('scrub').value); });
$('play').addEventListener('click', () => { if (hv.playing) animStop(); else animPlay(); });
$('keysbtn').addEventListener('click', toggleKeys);
$('stepback').addEventListener('click', () => frameStep(-1));
$('stepon').addEventListener('click', () => frameStep(1));
$('loop').addEventListener('change', ev => { anim.loop = ev.target.checked; });
$('animspeed').replaceWith(speedSelect('animspeed'));

// ---- sharing --------------------------------------------------------------------------

$('copy').addEventListener('click', () => {
  if (navigator.clipboard) navigator.clipboard.writeText(hv.cmd);
});

// saving is on only when the server was started with --allow-save (the page then has a token)
$('saverow').hidden = !hv.token;
$('save').addEventListener('click', async () => {
  const name = $('newname').value.trim();
  const r = await fetch('/api/save?' + query() + '&name=' + enc(name), {
    method: 'POST', headers: { 'X-Hystviz-Token': hv.token },
  });
  const j = await r.json().catch(() => ({}));
  // stays until dismissed (the reload the new file triggers keeps it)
  $('saved').replaceChildren(r.status === 201
    ? el('span', {}, 'saved as ', el('a', { href: '#' + j.file }, j.path))
    : el('span', { class: 'err' }, j.error || ('HTTP ' + r.status)),
    el('button', { type: 'button', class: 'dismiss', title: 'dismiss', onclick: () => $('saved').replaceChildren() }, '×'));
});

// ---- reload on save -----------------------------------------------------------------------

function listen() {
  const es = new EventSource('/events?page=' + hv.page);
  es.addEventListener('hello', () => { $('status').textContent = 'live'; });
  es.addEventListener('change', async () => {
    hv.changes++;
    await loadCatalogue();
    if (hv.info) await openScene(hv.info.file, true);
  });
  es.onerror = () => {
    if ($('status').textContent !== 'connection lost, retrying…') say('connection to the server lost, retrying');
    $('status').textContent = 'connection lost, retrying…';
  };
}

// ---- screen readers and the keyboard (issue 38 item 6) ---------------------------------

// A message said by a screen reader: into a live region that is always in the page
// (#alert, assertive, for errors; #say, polite, for notes and the keys' answers); the
// same text twice in a row is said again.
function say(msg, urgent) {
  const r = $(urgent ? 'alert' : 'say');
  if (!r || !msg) return;
  r.textContent = r.textContent === msg ? msg + '\u00a0' : msg;
}

// The figure's accessible name and description (#figure is role="img", focusable; the
// SVG inside it is presentational): the name is the SVG's own <title>, else the
// caption, else the scene's title, followed by the pins kept for comparison; the
// description is the SVG's <desc> where it has one (else the caption, if the title named it).  The <title> is taken out of the
// page's copy of the SVG once read (hv.svg keeps the server's bytes): inline, it would
// be a browser tooltip over the whole figure, on top of the page's own (#tip).
function labelFigure() {
  const fig = $('figure'), svg = fig.querySelector('svg');
  const t = svg && svg.querySelector(':scope > title'), d = svg && svg.querySelector(':scope > desc');
  if (t) { fig.dataset.title = t.textContent.trim(); t.remove(); } // read once: the name says it (no browser tooltip over the figure)
  else if (!svg) delete fig.dataset.title;
  let name = fig.dataset.title || $('caption').textContent.trim() || $('title').textContent.trim();
  if (!svg) name = (name ? name + ': ' : '') + (hv.error ? 'no figure: ' + hv.error : 'the figure is being drawn');
  else if (hv.error) name += ' (the figure before the refused value: ' + hv.error + ')';
  if (svg && hv.pins.length) name += '; pinned for comparison: ' + hv.pins.map(p => p.label).join('; ');
  fig.setAttribute('aria-label', name || 'the figure');
  if (d && d.textContent.trim()) { d.id = 'figdesc'; fig.setAttribute('aria-describedby', 'figdesc'); }
  else if (fig.dataset.title && $('caption').textContent.trim()) fig.setAttribute('aria-describedby', 'caption'); // named by its title
  else fig.removeAttribute('aria-describedby');
}

// the frame shown, said by the canvas (role="img") and the scrubber
function labelFrame(i) {
  if (!hv.info || !anim.n) return;
  const where = 'frame ' + i + ' of ' + anim.n + ', ' + clipTime(i);
  $('scrub').setAttribute('aria-valuetext', where);
  $('frame').setAttribute('aria-label', 'animation ' + (hv.info.name || hv.info.file) + ', ' + (hv.playing ? 'playing' : where));
}

function toggleKeys(show) {
  const k = $('keys'), on = show === undefined ? k.hidden : show;
  k.hidden = !on;
  for (const b of document.querySelectorAll('#keysbtn, .keysbtn')) b.setAttribute('aria-expanded', String(on));
}

// The skip link (the page's first focusable element) takes the focus to the controls:
// those of the figure, or a built-in clip's player (no figure, no sliders).  The page's
// URL is its state (#SCENE?...), so the link never changes it.
$('skip').addEventListener('click', ev => {
  ev.preventDefault();
  const t = $('stage').hidden ? $('anim') : $('controls');
  t.focus({ preventScroll: true });
  t.scrollIntoView({ block: 'nearest' });
});

// ---- presentation view: the figure and the main controls, nothing else ------------

function setPresent(on, fromUrl) {
  hv.present = !!on;
  document.body.classList.toggle('present', hv.present);
  fitFrame();
  if (!fromUrl) pushUrl(false);
  if (hv.present) {
    // arrows step the first main slider at once
    const first = $('controls').querySelector('.ctl.main input[type=range]');
    if (first && !(document.activeElement && document.activeElement.dataset && document.activeElement.dataset.key))
      first.focus({ preventScroll: true });
    window.scrollTo(0, 0);
  }
}

// ←/→ on a control's slider: one fiftieth of its travel (one unit for a whole number)
function stepSlider(range, dir) {
  const c = ctlOf(range.dataset.key);
  if (!c) return;
  if (c.int) {
    const { lo, hi } = domain(c), v = Math.max(Math.ceil(lo), Math.min(Math.floor(hi), Math.round(parseFloat(curOf(c))) + dir));
    range.value = toPos(c, v);
  } else range.value = Math.max(0, Math.min(1000, +range.value + 20 * dir));
  hv.dragging = false;
  range.dispatchEvent(new Event('input'));
  range.dispatchEvent(new Event('change'));
}

// A short line over the figure for a key's answer ("no preset 7: this scene has 3")
function flash(msg) {
  const f = $('flash');
  f.textContent = msg;
  f.hidden = false;
  say(msg);
  clearTimeout(hv.flashTimer);
  hv.flashTimer = setTimeout(() => { f.hidden = true; }, 2500);
}

const animOpen = () => !$('anim').hidden && anim.n > 0;
// The keys: what the help (key ?) lists is this table, so each key it lists does something
const KEYS = [
  ['p', 'presentation view on/off', () => setPresent(!hv.present)],
  ['f', 'full screen', () => { if (document.fullscreenElement) document.exitFullscreen(); else document.documentElement.requestFullscreen().catch(() => flash('full screen refused by the browser')); }],
  ['r', 'reset to the file\'s values', () => resetValues()],
  ['t', 'slides theme on/off', () => setTheme(hv.sets['figure.theme'] !== 'slides')],
  ['g', 'pin the curves shown now (labelled with their values)', () => { addPin(); flash(hv.pins.length ? 'pinned: ' + hv.pins[hv.pins.length - 1].label : 'nothing to pin'); }],
  ['l', 'hold the axes / release them', () => { holdAxes(!hv.axesHeld); flash(hv.axesHeld ? 'axes held' : 'axes free'); }],
  ['space', 'play/pause the clip, or stop a slider\'s ▶', null],
  [',', 'one step back (the clip\'s frame, or the slider played or moved last)', () => animOpen() ? frameStep(-1) : sliderStep(-1)],
  ['.', 'one step on (the clip\'s frame, or the slider played or moved last)', () => animOpen() ? frameStep(1) : sliderStep(1)],
  ['[', 'slower (¼×, ½×, 1×, 2×)', () => speedStep(-1)],
  [']', 'faster', () => speedStep(1)],
  ['←/→', 'step the focused slider', null],
  ['1–9', 'the scene\'s presets', null],
  ['?', 'this list of keys', () => toggleKeys()],
];

// the help: the keys of KEYS; 1–9 says how many presets this scene has
function keyHelp() {
  const n = hv.info && hv.info.presets ? hv.info.presets.length : 0;
  $('keylist').replaceChildren(...KEYS.filter(k => k[0] !== '1–9' || n > 0).map(k => el('li', {},
    el('kbd', {}, k[0] === '1–9' ? (n > 1 ? '1–' + Math.min(9, n) : '1') : k[0]), ' ',
    k[0] === '1–9' ? 'the scene\'s presets (' + n + ')' : k[1])));
}

document.addEventListener('keydown', ev => {
  if (ev.ctrlKey || ev.metaKey || ev.altKey) return;
  const t = ev.target;
  if (t && (t.tagName === 'TEXTAREA' || (t.tagName === 'INPUT' && t.type === 'text'))) return;
  if (ev.key === 'ArrowLeft' || ev.key === 'ArrowRight') {
    if (t && t.type === 'range' && t.dataset.key) { ev.preventDefault(); stepSlider(t, ev.key === 'ArrowRight' ? 1 : -1); }
    return;
  }
  if (ev.key === 'Escape' && !$('keys').hidden) { toggleKeys(false); return; }
  if (!hv.info) return;
  const k = KEYS.find(x => x[0] === ev.key && x[2]);
  if (k) { ev.preventDefault(); k[2](); }
  else if (ev.key === ' ' && hv.sliderPlay) { ev.preventDefault(); sliderPlayStop(); }
  else if (ev.key === ' ' && !$('anim').hidden && !(t && t.tagName === 'BUTTON')) { ev.preventDefault(); $('play').click(); }
  else if (/^[1-9]$/.test(ev.key)) {
    const n = hv.info.presets ? hv.info.presets.length : 0;
    if (+ev.key <= n) applyPreset(+ev.key - 1);
    else flash(n ? 'no preset ' + ev.key + ': this scene has ' + n + ' (keys 1–' + n + ')' : 'no preset ' + ev.key + ': this scene has none');
  }
});

// the frame shown (paused) goes into the URL, so a link opens on it
document.addEventListener('hv-frame', () => { if (!hv.playing) pushUrl(true); });

// back/forward, a link pasted or a catalogue entry clicked
window.addEventListener('popstate', applyUrl);
window.addEventListener('hashchange', applyUrl);

(async () => {
  const j = await loadCatalogue();
  listen();
  const st = parseHash();
  const f = st.file || j.first || (j.scenes[0] && j.scenes[0].file);
  if (f) openScene(f, false, st);
})();
