// The studio's page: controls built from the key tables the server sends, every change sent as
// the JSON-pointer override --set takes, the picture painted at preview size while the input
// moves and at full size when it rests. Plain JavaScript: nothing to fetch from the internet.
'use strict';

const $ = (id) => document.getElementById(id);
const state = {
  catalog: null,
  frame: null,        // the shot's frame shown (null for a still)
  dragging: false,    // an input is moving: previews
  playing: false,
  frameSeq: 0,        // the newest frame asked for; older answers are dropped
  inflight: null,     // the frame request in flight: {preview, my}
  want: false,        // the size the newest state should be painted at
  dirty: false,       // the state changed while a preview was in flight
  pending: {},        // changes not yet sent: pointer -> value
  pendingUnset: [],
  pendingControls: {},
  sending: null,      // the change request in flight
  restTimer: 0,
  overrides: new Set(),
};

// ---- talking to the server ----------------------------------------------------------------

async function postJSON(url, body) {
  const r = await fetch(url, {method: 'POST', headers: {'Content-Type': 'application/json'},
                              body: JSON.stringify(body)});
  let j = {};
  try { j = await r.json(); } catch (e) { j = {error: 'the studio answered ' + r.status}; }
  return {ok: r.ok, status: r.status, body: j};
}

// Sends the pending changes, merged, one request at a time; resolves when all are applied.
function flushChanges() {
  if (state.sending) return state.sending.then(() => flushChanges());
  const set = state.pending, unset = state.pendingUnset, controls = state.pendingControls;
  if (Object.keys(set).length === 0 && unset.length === 0) return Promise.resolve(true);
  state.pending = {}; state.pendingUnset = []; state.pendingControls = {};
  state.sending = postJSON('/api/change', {set, unset}).then((r) => {
    state.sending = null;
    if (!r.ok) {
      // The same one line as the command line, beside the control; the picture stays.
      const ctl = controls[r.body.pointer] || Object.values(controls)[0];
      showError(ctl, r.body.error || 'refused');
      return false;
    }
    for (const c of Object.values(controls)) showError(c, '');
    applyCatalog(r.body.catalog, false);
    return true;
  });
  return state.sending;
}

function change(pointer, value, control) {
  state.pending[pointer] = value;
  state.pendingUnset = state.pendingUnset.filter((p) => p !== pointer);
  if (control) state.pendingControls[pointer] = control;
  schedule();
}

function unsetKeys(pointers) {
  for (const p of pointers) { delete state.pending[p]; state.pendingUnset.push(p); }
  schedule();
}

// A preview now (while the input moves), the full frame once it rests.
function schedule() {
  clearTimeout(state.restTimer);
  paint(state.dragging || state.playing);
}

function settle() {
  clearTimeout(state.restTimer);
  state.restTimer = setTimeout(() => { state.dragging = false; paint(false); }, 250);
}

// One frame in flight at a time. A preview in flight is let finish (it is what the user sees
// while moving) and the newest state is asked for when it lands; a full-size frame in flight
// is superseded at once: the server abandons it between stages for the newer request.
function paint(preview) {
  state.want = preview;
  if (state.inflight && state.inflight.preview) { state.dirty = true; return; }
  requestFrame();
}

async function requestFrame() {
  const preview = state.want;
  state.dirty = false;
  const my = ++state.frameSeq;
  state.inflight = {preview, my};
  try {
    await showFrameFromServer(preview, my);
  } finally {
    if (state.inflight && state.inflight.my === my) {
      state.inflight = null;
      if (state.dirty) requestFrame();
    }
  }
}

async function showFrameFromServer(preview, my) {
  const ok = await flushChanges();
  if (my !== state.frameSeq) return;
  if (!ok) return;  // refused: the last good picture stays, the message beside the control
  let url = '/api/frame?preview=' + (preview ? 1 : 0);
  if (preview && $('draft').checked) url += '&draft=1';
  if (state.frame !== null) url += '&frame=' + state.frame;
  const t0 = performance.now();
  let r;
  try { r = await fetch(url); } catch (e) { setStatus('the studio is not answering'); return; }
  if (r.status === 204 || my !== state.frameSeq) return;  // superseded
  if (!r.ok) {
    let j = {};
    try { j = await r.json(); } catch (e) {}
    showViewError(j.error || ('frame refused: ' + r.status));
    return;
  }
  const blob = await r.blob();
  if (my !== state.frameSeq) return;
  const img = $('picture');
  const old = img.src;
  img.src = URL.createObjectURL(blob);
  await img.decode().catch(() => {});
  img.dataset.exact = r.headers.get('X-Pleinair-Exact');
  img.dataset.preview = preview ? '1' : '0';
  img.dataset.seq = String(my);
  if (old.startsWith('blob:')) URL.revokeObjectURL(old);
  showViewError('');
  $('command').value = decodeURIComponent(r.headers.get('X-Pleinair-Command') || '');
  const [build, paintMs] = (r.headers.get('X-Pleinair-Ms') || '0 0').split(' ').map(Number);
  const rebuilt = r.headers.get('X-Pleinair-Rebuilt');
  setStatus((preview ? 'preview' : 'full size') +
            (r.headers.get('X-Pleinair-Exact') === '1' ? '' : ' (from the last shot)') +
            ': ' + (rebuilt !== 'none' ? rebuilt + ' rebuilt ' + build.toFixed(0) + ' ms, ' : '') +
            'painted ' + paintMs.toFixed(0) + ' ms, shown in ' + (performance.now() - t0).toFixed(0) + ' ms');
  document.body.dataset.frames = String((Number(document.body.dataset.frames) || 0) + 1);
  if ($('circles').checked) drawCircles(preview);
  else clearOverlay();
  if ($('explain').checked) loadExplain();
  if (state.playing) requestAnimationFrame(stepPlay);
}

function setStatus(text) { $('status').textContent = text; }
function showViewError(text) { $('view-error').textContent = text; $('view-error').hidden = !text; }

function showError(control, text) {
  if (!control) { showViewError(text); return; }
  const row = control.closest('.row');
  const el = row ? row.querySelector('.error') : null;
  if (!el) { showViewError(text); return; }
  el.textContent = text;
  el.hidden = !text;
}

// ---- controls from the key tables ---------------------------------------------------------

function tip(row) {
  let t = row.doc || '';
  if (row.lo !== undefined && row.hi !== undefined) t += `\nRange ${row.lo} to ${row.hi}`;
  if (row.unit) t += (row.lo !== undefined ? ', ' : '\nUnit: ') + row.unit;
  return t + '\n' + row.fullPointer;
}

function rounded(v, integer) {
  return integer ? Math.round(v) : Number(Number(v).toPrecision(6));
}

// A slider where the range is one a hand can sweep, and a number box always.
function numberInputs(wrap, value, row, integer, send) {
  const box = document.createElement('input');
  box.type = 'number';
  box.value = value;
  box.step = integer ? 1 : 'any';
  let slider = null;
  const finite = row.lo !== undefined && row.hi !== undefined;
  if (finite && row.hi - row.lo <= 1000) {
    slider = document.createElement('input');
    slider.type = 'range';
    slider.min = row.lo; slider.max = row.hi;
    slider.step = integer ? 1 : (row.hi - row.lo) / 500;
    slider.value = value;
    slider.addEventListener('input', () => {
      state.dragging = true;
      box.value = rounded(slider.value, integer);
      send(rounded(slider.value, integer), slider);
    });
    slider.addEventListener('change', () => { state.dragging = false; settle(); });
    wrap.appendChild(slider);
  }
  box.addEventListener('change', () => {
    const v = Number(box.value);
    if (box.value.trim() === '' || !Number.isFinite(v)) { send(box.value, box); return; }
    if (slider) slider.value = v;
    send(integer ? v : v, box);
  });
  wrap.appendChild(box);
  return box;
}

function hex(c) {
  return '#' + c.map((v) => Math.max(0, Math.min(255, Math.round(v * 255))).toString(16).padStart(2, '0')).join('');
}

function controlRow(parent, row, base) {
  const pointer = base + row.pointer;
  row.fullPointer = pointer;
  const div = document.createElement('div');
  div.className = 'row';
  div.dataset.pointer = pointer;
  if (state.overrides.has(pointer)) div.classList.add('changed');
  const label = document.createElement('label');
  label.textContent = row.pointer.split('/').pop();
  label.title = tip(row);
  const wrap = document.createElement('span');
  wrap.className = 'inputs';
  const send = (v, el) => { div.classList.add('changed'); change(pointer, v, el); };
  const k = row.kind;
  if (k === 'number' || k === 'integer' || k === 'seed') {
    numberInputs(wrap, row.value, row, k !== 'number', send);
  } else if (k === 'param') {
    // {base, var}: the base on a slider, the variation beside it.
    const whole = !!row.whole;
    numberInputs(wrap, row.value.base, row, whole, (v, el) => { div.classList.add('changed'); change(pointer + '/base', v, el); });
    const vr = document.createElement('input');
    vr.type = 'number'; vr.step = 'any'; vr.value = row.value.var; vr.title = 'variation (±)';
    vr.addEventListener('change', () => { div.classList.add('changed'); change(pointer + '/var', Number(vr.value), vr); settle(); });
    const pm = document.createElement('span'); pm.className = 'unit'; pm.textContent = '±';
    wrap.append(pm, vr);
  } else if (k === 'boolean') {
    const cb = document.createElement('input');
    cb.type = 'checkbox'; cb.checked = !!row.value;
    cb.addEventListener('change', () => send(cb.checked, cb));
    wrap.appendChild(cb);
  } else if (k === 'vector') {
    const boxes = row.value.map((v) => {
      const b = document.createElement('input');
      b.type = 'number'; b.step = 'any'; b.value = v;
      wrap.appendChild(b);
      return b;
    });
    for (const b of boxes) b.addEventListener('change', () => send(boxes.map((x) => Number(x.value)), b));
  } else if (k === 'color') {
    const c = document.createElement('input');
    c.type = 'color'; c.value = hex(row.value);
    c.addEventListener('input', () => {
      state.dragging = true;
      const v = [1, 3, 5].map((i) => Number((parseInt(c.value.substr(i, 2), 16) / 255).toFixed(3)));
      send(v, c);
    });
    c.addEventListener('change', () => { state.dragging = false; settle(); });
    wrap.appendChild(c);
  } else if (k === 'choice' && row.choices) {
    const s = document.createElement('select');
    for (const ch of row.choices) s.add(new Option(ch, ch, false, ch === row.value));
    s.addEventListener('change', () => send(s.value, s));
    wrap.appendChild(s);
  } else {
    const t = document.createElement('input');
    t.type = 'text'; t.value = typeof row.value === 'string' ? row.value : JSON.stringify(row.value);
    t.addEventListener('change', () => send(t.value, t));
    wrap.appendChild(t);
  }
  if (row.unit) {
    const u = document.createElement('span'); u.className = 'unit'; u.textContent = row.unit;
    wrap.appendChild(u);
  }
  const err = document.createElement('div');
  err.className = 'error'; err.hidden = true;
  div.append(label, wrap, err);
  parent.appendChild(div);
}

// Rows of one key table, nested as the preset file nests them.
function keyTable(parent, rows, base) {
  const groups = {'': parent};
  for (const row of rows) {
    const parentPtr = row.pointer.substring(0, row.pointer.lastIndexOf('/'));
    const into = groups[parentPtr] || parent;
    if (row.kind === 'group') {
      const fs = document.createElement('fieldset');
      const lg = document.createElement('legend');
      lg.textContent = row.pointer.split('/').pop();
      lg.title = row.doc || '';
      fs.appendChild(lg);
      into.appendChild(fs);
      groups[row.pointer] = fs;
    } else {
      controlRow(into, row, base);
    }
  }
}

function choiceRow(parent, pointer, label, value, choices, doc) {
  controlRow(parent, {pointer: '', kind: 'choice', value, choices, doc}, pointer);
  parent.lastChild.querySelector('label').textContent = label;
}

function section(title, open) {
  const d = document.createElement('details');
  d.open = !!open;
  const s = document.createElement('summary');
  s.textContent = title;
  d.appendChild(s);
  $('controls').appendChild(d);
  return d;
}

function buildControls(cat) {
  const root = $('controls');
  root.textContent = '';
  cat.families.forEach((f, i) => {
    const tree = section(`${f.name}: tree (${f.preset})`, i === 0);
    choiceRow(tree, f.pointer + '/preset', 'preset', f.preset, cat.tree_presets,
              'The tree preset the family grows from (presets/trees).');
    keyTable(tree, f.tree, f.pointer + '/tree');
    const leaf = section(`${f.name}: leaf shader and palette`, false);
    keyTable(leaf, f.leaf_shader, f.pointer + '/leaf_shader_keys');
    choiceRow(leaf, f.pointer + '/leaf_palette', 'palette', '', [''].concat(cat.palettes),
              "The leaves' palette (empty: the shader's own).");
    const bark = section(`${f.name}: bark shader and palette`, false);
    keyTable(bark, f.bark_shader, f.pointer + '/bark_shader_keys');
    choiceRow(bark, f.pointer + '/bark_palette', 'palette', '', [''].concat(cat.palettes),
              "The bark's palette (empty: the shader's own).");
  });
  // The wind: scrub the timeline to watch the trees move (a still shows its time 0).
  if (cat.wind) keyTable(section('wind', false), cat.wind, '');
}

function applyCatalog(cat, rebuild) {
  state.catalog = cat;
  state.overrides = new Set(cat.overrides.map((o) => o.pointer));
  if (rebuild) buildControls(cat);
}

// ---- the camera: orbit, walk, zoom -------------------------------------------------------

const cam = {position: null, look_at: null};

function fmt(v) { return v.map((x) => Number(x.toFixed(3))); }

function sendCamera() {
  change('/camera/position', fmt(cam.position));
  change('/camera/look_at', fmt(cam.look_at));
}

function orbit(dx, dy) {
  const p = cam.position, c = cam.look_at;
  const off = [p[0] - c[0], p[1] - c[1], p[2] - c[2]];
  const r = Math.hypot(...off);
  let yaw = Math.atan2(off[0], off[2]);
  let pitch = Math.asin(Math.max(-1, Math.min(1, off[1] / r)));
  yaw -= dx * 0.008;
  pitch = Math.max(-1.4, Math.min(1.4, pitch + dy * 0.008));
  cam.position = [c[0] + r * Math.cos(pitch) * Math.sin(yaw), c[1] + r * Math.sin(pitch),
                  c[2] + r * Math.cos(pitch) * Math.cos(yaw)];
}

function walk(forward, side) {
  const p = cam.position, c = cam.look_at;
  const f = [c[0] - p[0], 0, c[2] - p[2]];
  const n = Math.hypot(f[0], f[2]) || 1;
  const step = Math.max(0.2, Math.hypot(c[0] - p[0], c[1] - p[1], c[2] - p[2]) * 0.04);
  const fx = f[0] / n, fz = f[2] / n;
  const d = [fx * forward * step - fz * side * step, 0, fz * forward * step + fx * side * step];
  cam.position = p.map((v, i) => v + d[i]);
  cam.look_at = c.map((v, i) => v + d[i]);
}

function zoom(factor) {
  const p = cam.position, c = cam.look_at;
  cam.position = c.map((v, i) => v + (p[i] - v) * factor);
}

function cameraControls() {
  const vp = $('viewport');
  let last = null;
  const movable = () => state.catalog && !state.catalog.camera.track;
  vp.addEventListener('pointerdown', (e) => {
    if (!movable()) return;
    last = [e.clientX, e.clientY, e.shiftKey];
    vp.setPointerCapture(e.pointerId);
    vp.classList.add('dragging');
  });
  vp.addEventListener('pointermove', (e) => {
    if (!last) return;
    const dx = e.clientX - last[0], dy = e.clientY - last[1];
    if (Math.abs(dx) + Math.abs(dy) < 2) return;
    last = [e.clientX, e.clientY, last[2]];
    state.dragging = true;
    if (e.shiftKey) walk(-dy * 0.05, dx * 0.05);
    else orbit(dx, dy);
    sendCamera();
  });
  const end = () => {
    if (!last) return;
    last = null;
    vp.classList.remove('dragging');
    settle();
  };
  vp.addEventListener('pointerup', end);
  vp.addEventListener('pointercancel', end);
  vp.addEventListener('wheel', (e) => {
    if (!movable()) return;
    e.preventDefault();
    state.dragging = true;
    zoom(e.deltaY > 0 ? 1.08 : 1 / 1.08);
    sendCamera();
    settle();
  }, {passive: false});
  vp.addEventListener('keydown', (e) => {
    if (!movable()) return;
    const k = {ArrowUp: [1, 0], w: [1, 0], ArrowDown: [-1, 0], s: [-1, 0],
               ArrowLeft: [0, -1], a: [0, -1], ArrowRight: [0, 1], d: [0, 1]}[e.key];
    if (!k) return;
    e.preventDefault();
    state.dragging = true;
    walk(k[0], k[1]);
    sendCamera();
    settle();
  });
}

// ---- the shot's timeline ---------------------------------------------------------------

function stepPlay() {
  if (!state.playing) return;
  const s = $('frame');
  let f = Number(s.value) + 1;
  if (f > Number(s.max)) f = Number(s.min);
  s.value = f;
  showFrame(f, true);
}

function showFrame(f, preview) {
  state.frame = f;
  $('frame-label').textContent = `frame ${f} of ${$('frame').max}`;
  paint(preview);
}

function timeline(cat) {
  if (!cat.animated) return;
  $('timeline').hidden = false;
  const s = $('frame');
  s.min = cat.frames[0]; s.max = cat.frames[1]; s.value = cat.frames[0];
  state.frame = cat.frames[0];
  $('frame-label').textContent = `frame ${s.value} of ${s.max}`;
  s.addEventListener('input', () => { state.dragging = true; showFrame(Number(s.value), true); });
  s.addEventListener('change', () => { state.dragging = false; settle(); });
  $('play').addEventListener('click', () => {
    state.playing = !state.playing;
    $('play').textContent = state.playing ? 'Pause' : 'Play';
    if (state.playing) stepPlay(); else settle();
  });
}

// ---- overlays and panels ------------------------------------------------------------------

function clearOverlay() {
  const cv = $('overlay');
  cv.getContext('2d').clearRect(0, 0, cv.width, cv.height);
}

async function drawCircles(preview) {
  let url = '/api/circles?preview=' + (preview ? 1 : 0);
  if (state.frame !== null) url += '&frame=' + state.frame;
  const r = await fetch(url);
  if (!r.ok) return;
  const rings = await r.json();
  const img = $('picture'), cv = $('overlay');
  cv.width = img.naturalWidth; cv.height = img.naturalHeight;
  const g = cv.getContext('2d');
  g.clearRect(0, 0, cv.width, cv.height);
  const colours = {'near field': '#f0e68c', 'leaf near': '#8fd18f', 'leaf far': '#3f8f3f',
                   'trunk near': '#d9a066', 'trunk far': '#8f5a2a'};
  g.lineWidth = Math.max(1, cv.width / 480);
  g.font = `${Math.max(10, cv.width / 60)}px system-ui`;
  for (const ring of rings) {
    g.strokeStyle = colours[ring.name] || '#fff';
    g.fillStyle = g.strokeStyle;
    g.beginPath();
    let pen = false, labelAt = null;
    for (const p of ring.points) {
      if (!p) { pen = false; continue; }
      if (pen) g.lineTo(p[0], p[1]); else g.moveTo(p[0], p[1]);
      pen = true;
      const inside = p[1] > 12 && p[1] < cv.height - 4 && p[0] > 0 && p[0] < cv.width - 80;
      if (inside && (!labelAt || Math.abs(p[0] - cv.width / 2) < Math.abs(labelAt[0] - cv.width / 2))) labelAt = p;
    }
    g.stroke();
    if (labelAt) g.fillText(`${ring.name} ${ring.radius} m`, labelAt[0] + 4, labelAt[1] - 4);
  }
}

async function loadExplain() {
  const r = await fetch('/api/explain');
  if (r.ok) $('explain-panel').textContent = await r.text();
}

// ---- the tree's tools ---------------------------------------------------------------------

// What each step of the thesis's tool shows, as overrides: the tree's keys (under its
// family's /tree) and, for the leaves alone, the scene's bark coverage.
function stepOverrides(step, base) {
  const noLeaves = {[base + '/leaves/probability']: 0};
  switch (step) {
    case 'trunk': return {[base + '/branches/enabled']: false, [base + '/twigs/enabled']: false, ...noLeaves};
    case 'branches': return noLeaves;
    case 'lod': return {[base + '/twigs/enabled']: false, ...noLeaves};
    case 'leaves': return {'/render/bark_coverage': 0};
    default: return {};
  }
}

function treeTools(cat) {
  const f = cat.families[0];
  if (!f || cat.families.length !== 1) return;
  $('tree-tools').hidden = false;
  const base = f.pointer + '/tree';
  $('step').addEventListener('change', () => {
    const step = stepOverrides($('step').value, base);
    // Every key some step sets, so that leaving a step clears what it set.
    const steps = [...$('step').options].map((o) => o.value);
    const every = Object.keys(Object.assign({}, ...steps.map((k) => stepOverrides(k, base))));
    unsetKeys(every.filter((k) => !(k in step)));
    for (const [k, v] of Object.entries(step)) change(k, v);
  });
  $('reseed').hidden = f.trees.length === 0;
  $('reseed').addEventListener('click', () => {
    for (const t of state.catalog.families[0].trees)
      change(`/trees/${t.index}/seed`, 1 + Math.floor(Math.random() * 999999));
  });
  $('keep').addEventListener('click', async () => {
    const r = await postJSON('/api/keep', {family: f.name});
    setStatus(r.ok ? 'kept as ' + r.body.file : (r.body.error || 'not kept'));
  });
  $('contact').addEventListener('click', async () => {
    setStatus('painting the contact sheet...');
    const r = await fetch('/api/contact?family=' + encodeURIComponent(f.name));
    if (!r.ok) { setStatus('no contact sheet'); return; }
    $('sheet-image').src = URL.createObjectURL(await r.blob());
    $('sheet').hidden = false;
    setStatus('');
  });
  $('sheet-close').addEventListener('click', () => { $('sheet').hidden = true; });
}

// ---- start --------------------------------------------------------------------------------

async function start() {
  const r = await fetch('/api/catalog');
  const cat = await r.json();
  applyCatalog(cat, true);
  $('scene-name').textContent = cat.scene;
  $('scene-description').textContent = cat.description;
  cam.position = cat.camera.position.slice();
  cam.look_at = cat.camera.look_at.slice();
  if (cat.camera.track) $('viewport').title = 'The camera follows the shot\'s track: scrub the timeline.';
  timeline(cat);
  treeTools(cat);
  cameraControls();
  $('copy').addEventListener('click', () => { $('command').select(); document.execCommand('copy'); });
  $('circles').addEventListener('change', () => ($('circles').checked ? drawCircles($('picture').dataset.preview === '1') : clearOverlay()));
  $('explain').addEventListener('change', () => {
    $('explain-panel').hidden = !$('explain').checked;
    if ($('explain').checked) loadExplain();
  });
  paint(false);
}

start();
