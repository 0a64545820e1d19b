// app.js: the page of `hystviz serve` (no libraries, works offline).
// State lives in `hv` (also read by tests/serve/browser_test.py).
'use strict';

const hv = window.hv = {
  token: document.querySelector('meta[name="hystviz-token"]').content,
  page: Array.from(crypto.getRandomValues(new Uint8Array(8)), b => b.toString(16).padStart(2, '0')).join(''),
  scenes: [], info: null, sets: {}, lastKey: null,
  seq: 0, inflight: false, pending: false,
  svg: null, cmd: '', renders: 0, changes: 0, error: null, serverMs: NaN, pageMs: NaN,
  hover: null, hoverTimer: 0,
  frame: -1, frameB64: null, frameSeq: 0, frameInflight: false, framePending: -1, playing: false,
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
      (s.label ? s.label + ' · ' : '') + s.name + (s.anim ? ' ▶' : ''), el('small', {}, s.error ? s.error : s.caption)));
  }
  nav.replaceChildren(...kids);
  markCurrent();
  return j;
}

function markCurrent() {
  for (const a of $('catalogue').querySelectorAll('a'))
    a.classList.toggle('on', hv.info && a.dataset.file === hv.info.file);
}

function currentFile() {
  const h = decodeURIComponent(location.hash.slice(1));
  return h || null;
}

// ---- a scene and its controls --------------------------------------------

function fmt(v, integer) {
  if (integer) return String(Math.round(v));
  return String(parseFloat(v.toPrecision(4)));
}
function toPos(c, v) {
  const t = c.log ? Math.log(v / c.lo) / Math.log(c.hi / c.lo) : (v - c.lo) / (c.hi - c.lo);
  return Math.max(0, Math.min(1000, Math.round(1000 * t)));
}
function fromPos(c, p) {
  const t = p / 1000;
  return c.log ? c.lo * Math.pow(c.hi / c.lo, t) : c.lo + (c.hi - c.lo) * t;
}

async function openScene(file, keep) {
  const r = await fetch('/api/scene?scene=' + enc(file));
  if (r.status !== 200) { showError('no scene ' + file); return; }
  const info = await r.json();
  const same = hv.info && hv.info.file === file;
  hv.info = info;
  if (!keep || !same) { hv.sets = {}; hv.lastKey = null; hv.svg = null; $('figure').replaceChildren(); hv.hover = null; }
  const entry = hv.scenes.find(s => s.file === file);
  $('title').textContent = (entry && entry.label ? entry.label + ' · ' : '') + (info.name || file);
  $('caption').textContent = info.caption;
  $('text').textContent = info.text;
  $('newname').value = '';
  $('saved').textContent = '';
  markCurrent();
  buildControls(info);
  // a built-in animation has frames only: no still figure, no controls
  $('stage').hidden = $('share').hidden = !!info.builtin;
  $('message').hidden = true;
  setupAnim(info, same && keep);
  if (info.error) { showError(info.error); return; }
  if (!info.builtin) requestRender();
}

function buildControls(info) {
  const box = $('controls');
  const kids = [el('div', { class: 'row' },
    el('button', { type: 'button', onclick: () => { hv.sets = {}; buildControls(hv.info); requestRender(); } }, 'reset to file'))];
  for (const c of info.controls) {
    const cur = hv.sets[c.key] !== undefined ? hv.sets[c.key] : c.value;
    const range = el('input', { type: 'range', min: 0, max: 1000, step: 1, 'data-key': c.key, 'aria-label': c.key });
    const box = el('input', { type: 'text', value: cur, 'data-key': c.key, 'aria-label': c.key + ' value' });
    const err = el('div', { class: 'err', 'data-key': c.key });
    const div = el('div', { class: 'ctl' + (hv.sets[c.key] !== undefined ? ' changed' : ''), 'data-key': c.key },
      el('label', { title: c.doc + (c.range ? ' (' + c.range + ')' : '') },
        el('span', { class: 'k' }, c.key), el('span', { class: 'file' }, 'file: ' + c.value + (c.set ? '' : ' (default)'))),
      range, el('div', { class: 'row' }, box, el('span', { class: 'note' }, c.range + (c.log ? ' · log slider' : ''))), err);
    range.value = toPos(c, parseFloat(cur));
    const apply = (v) => {
      if (v === c.value) delete hv.sets[c.key]; else hv.sets[c.key] = v;
      div.classList.toggle('changed', hv.sets[c.key] !== undefined);
      hv.lastKey = c.key;
      requestRender();
    };
    range.addEventListener('input', () => {
      const v = fmt(fromPos(c, +range.value), c.int);
      box.value = v;
      apply(v);
    });
    box.addEventListener('change', () => {
      const v = box.value.trim();
      const x = parseFloat(v);
      if (isFinite(x)) range.value = toPos(c, x);
      apply(v);
    });
    kids.push(div);
  }
  box.replaceChildren(...kids);
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
    if (r.status === 200) show(j, q, t0);
    else if (r.status !== 409) showError(j.error || ('HTTP ' + r.status));
  } catch (e) {
    showError('the server did not answer: ' + e);
  }
  hv.inflight = false;
  if (hv.pending) doRender();
}

function show(j, q, t0) {
  const fig = $('figure');
  fig.innerHTML = j.svg;
  fig.classList.remove('stale');
  hv.svg = j.svg;
  hv.cmd = j.cmd;
  hv.error = null;
  hv.map = j.map;
  hv.serverMs = 1000 * j.seconds;
  hv.pageMs = performance.now() - t0;
  hv.renders++;
  $('cmd').textContent = j.cmd;
  $('message').hidden = true;
  for (const e of document.querySelectorAll('.ctl .err')) e.textContent = '';
  $('status').textContent = 'live · render ' + hv.serverMs.toFixed(1) + ' ms on the server, ' + hv.pageMs.toFixed(1) + ' ms in the page';
  $('measured').textContent = j.errors.length
    ? j.errors.map(e => e.series + ': max error ' + e.err.toPrecision(3) + ' against the ' + (e.ref || 'exact answer')).join(' · ')
    : 'no exact answer to compare with';
  const dl = $('downloads');
  dl.replaceChildren('download:', ...['svg', 'pdf', 'png', 'csv'].map(f =>
    el('a', { href: '/api/render?' + q + '&fmt=' + f + '&name=download', download: '' }, f.toUpperCase())));
  hv.hover = null;
  clearTimeout(hv.hoverTimer);
  hv.hoverTimer = setTimeout(() => loadHover(q), 300);
  document.dispatchEvent(new CustomEvent('hv-rendered'));
}

function showError(msg) {
  hv.error = msg;
  $('message').textContent = msg;
  $('message').hidden = false;
  $('figure').classList.add('stale');
  // next to the control the message names, else the one moved last
  let key = null;
  if (hv.info) for (const c of hv.info.controls) if (msg.includes(c.key + '=')) key = c.key;
  key = key || hv.lastKey;
  for (const e of document.querySelectorAll('.ctl .err')) e.textContent = e.dataset.key === key ? msg : '';
  document.dispatchEvent(new CustomEvent('hv-error'));
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
// frames ahead (/api/frames), decodes a few ahead (createImageBitmap) and shows frame
// floor(t * fps) at the clip's rate on a canvas, so the scene's easing is seen as
// written; a frame not there yet holds the clock (the clip slows, it never skips).
// A slider moved while playing drops what was fetched for the old values: the next
// frames shown use the new ones.  Paused, frame i comes alone (/api/frame).

const anim = hv.anim = {
  n: 0, fps: 30, key: '', png: new Map(), bmp: new Map(), decoding: new Set(),
  stream: null, streamEnd: -1, pos: 0, last: 0, shown: 0, stalls: 0, raf: 0, error: null,
};
const WINDOW_S = 2;     // seconds of frames asked for ahead by one stream
const DECODE_AHEAD = 8; // frames decoded ahead of the one shown

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
}

function showBitmap(b) {
  const c = $('frame');
  if (c.width !== b.width || c.height !== b.height) { c.width = b.width; c.height = b.height; }
  c.getContext('2d').drawImage(b, 0, 0);
}

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
  try {
    let buf = anim.png.get(i);
    if (!buf) {
      const r = await fetch('/api/frame?scene=' + enc(hv.info.file) + animSets() + '&frame=' + i + '&page=' + hv.page + 'f&seq=' + my);
      if (r.status === 200) buf = await r.arrayBuffer();
      else if (r.status !== 409) {
        const j = await r.json();
        $('frameinfo').textContent = 'frame ' + i + ': ' + j.error;
      }
    }
    if (buf && key === animKey() && !hv.playing) {
      showBitmap(await createImageBitmap(new Blob([buf], { type: 'image/png' })));
      hv.frameB64 = b64(buf);
      hv.frame = i;
      $('frameinfo').textContent = 'frame ' + i + ' / ' + anim.n;
      document.dispatchEvent(new CustomEvent('hv-frame'));
    }
  } catch (e) {
    $('frameinfo').textContent = 'frame ' + i + ': the server did not answer';
  }
  hv.frameInflight = false;
  if (hv.framePending >= 0 && !hv.playing) loadFrame(hv.framePending);
}

// ---- playing: streamed windows, decoded ahead, shown at the clip's rate

// Fetches the next window of frames not yet here, from the one being shown.
function animFetch() {
  if (anim.stream || !hv.playing) return;
  let from = Math.floor(anim.pos) % anim.n, k = 0;
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

// Reads records "TAG NUM LEN\n<bytes>" (anim_worker.h) as they arrive.
async function readStream(url, ctl, key) {
  let r;
  try { r = await fetch(url, { signal: ctl.signal }); } catch (e) { return; }
  if (r.status !== 200) {
    const j = await r.json().catch(() => ({}));
    if (r.status !== 409) animFail(j.error || ('HTTP ' + r.status));
    return;
  }
  const rd = r.body.getReader();
  let buf = new Uint8Array(0);
  try {
    for (;;) {
      const { done, value } = await rd.read();
      if (done) return;
      const b = new Uint8Array(buf.length + value.length);
      b.set(buf); b.set(value, buf.length);
      buf = b;
      for (;;) {
        const nl = buf.indexOf(10);
        if (nl < 0) break;
        const [tag, num, len] = new TextDecoder().decode(buf.subarray(0, nl)).split(' ');
        if (buf.length < nl + 1 + +len) break;
        const data = buf.slice(nl + 1, nl + 1 + +len);
        buf = buf.slice(nl + 1 + +len);
        if (key !== anim.key) return;
        if (tag === 'frame') { anim.png.set(+num, data.buffer); decodeAhead(); }
        else if (tag === 'error') { animFail(new TextDecoder().decode(data)); return; }
      }
    }
  } catch (e) { /* aborted: the sliders moved or play stopped */ }
}

function animFail(msg) {
  anim.error = msg;
  $('frameinfo').textContent = 'frame ' + Math.floor(anim.pos) % anim.n + ': ' + msg;
  animStop();
}

// Decodes the frames about to be shown; closes those behind.
function decodeAhead() {
  const cur = Math.floor(anim.pos) % anim.n;
  for (const [i, b] of anim.bmp) {
    const ahead = (i - cur + anim.n) % anim.n;
    if (ahead > DECODE_AHEAD) { b.close(); anim.bmp.delete(i); }
  }
  for (let d = 0; d <= DECODE_AHEAD; d++) {
    const i = (cur + d) % anim.n, buf = anim.png.get(i), key = anim.key;
    if (!buf || anim.bmp.has(i) || anim.decoding.has(i)) continue;
    anim.decoding.add(i);
    createImageBitmap(new Blob([buf], { type: 'image/png' })).then(b => {
      anim.decoding.delete(i);
      if (key === anim.key) anim.bmp.set(i, b); else b.close();
    }, () => anim.decoding.delete(i));
  }
}

function tick(now) {
  if (!hv.playing) return;
  const dt = Math.min(0.25, (now - anim.last) / 1000);
  anim.last = now;
  const next = Math.floor(anim.pos + dt * anim.fps), i = next % anim.n;
  const b = anim.bmp.get(i);
  if (b) {
    if (i !== hv.frame) { showBitmap(b); hv.frame = i; anim.shown++; $('scrub').value = i; }
    anim.pos = anim.pos + dt * anim.fps;
    if (anim.pos >= anim.n) anim.pos -= anim.n;
    const rate = anim.shown / Math.max(1e-3, (now - anim.t0) / 1000);
    $('frameinfo').textContent = 'frame ' + i + ' / ' + anim.n + ' · ' + rate.toFixed(0) + ' of the clip\'s '
      + anim.fps + ' frames/s shown';
  } else
    anim.stalls++; // not here yet: the clock waits for it
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
  anim.last = performance.now();
  anim.shown = 0;
  anim.stalls = 0;
  anim.t0 = anim.last;
  animFetch();
  anim.raf = requestAnimationFrame(tick);
}

function animStop() {
  if (anim.stream) anim.stream.abort();
  anim.stream = null;
  cancelAnimationFrame(anim.raf);
  const was = hv.playing;
  hv.playing = false;
  $('play').textContent = 'play';
  if (was && hv.frame >= 0 && anim.png.has(hv.frame)) { // paused on frame i: its bytes, as the scrubber's
    hv.frameB64 = b64(anim.png.get(hv.frame));
    $('frameinfo').textContent = 'frame ' + hv.frame + ' / ' + anim.n;
    document.dispatchEvent(new CustomEvent('hv-frame'));
  }
}

$('scrub').addEventListener('input', () => { if (hv.playing) animStop(); requestFrame(+$('scrub').value); });
$('play').addEventListener('click', () => { if (hv.playing) animStop(); else animPlay(); });

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
  $('saved').replaceChildren(r.status === 201
    ? el('span', {}, 'saved as ', el('a', { href: '#' + j.file }, j.path))
    : el('span', { class: 'err' }, j.error || ('HTTP ' + r.status)));
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
  es.onerror = () => { $('status').textContent = 'connection lost, retrying…'; };
}

window.addEventListener('hashchange', () => { const f = currentFile(); if (f) openScene(f, false); });

(async () => {
  const j = await loadCatalogue();
  listen();
  const f = currentFile() || j.first || (j.scenes[0] && j.scenes[0].file);
  if (f) openScene(f, false);
})();
