// ez-tree's tree generation timed in Node, to set pleinair's beside it (BENCHMARKS.md, "Trees
// from the side"): each shipped preset generated 5 times to warm up, then 50 (200 when under
// 5 ms), median wall time per tree, with its vertex and leaf counts. ez-tree's source runs
// unmodified; hooks.mjs only resolves its bundler-style imports.
//   git clone https://github.com/dgreenheck/ez-tree /tmp/ez-tree   (48dc193 was measured)
//   cd /tmp/ez-tree && npm install --no-save three@0.167 && cd -   (ez-tree imports three)
//   cd tests/bench/eztree && EZTREE=/tmp/ez-tree [PRESETS="Oak Large"] node --import ./register.mjs bench.mjs
import { performance } from 'node:perf_hooks';
import { createHash } from 'node:crypto';
import { pathToFileURL } from 'node:url';
const root = pathToFileURL((process.env.EZTREE || './ez-tree') + '/').href;
const { Tree } = await import(root + 'src/lib/tree.js');
const { TreePreset } = await import(root + 'src/lib/presets/index.js');

const WARMUP = 5;
const median = (a) => { const s = [...a].sort((x, y) => x - y); const n = s.length;
  return n % 2 ? s[(n - 1) / 2] : (s[n / 2 - 1] + s[n / 2]) / 2; };
const hashGeom = (t) => { const h = createHash('sha1');
  for (const m of [t.branchesMesh, t.leavesMesh]) {
    h.update(Buffer.from(m.geometry.attributes.position.array.buffer));
    h.update(Buffer.from(m.geometry.index.array.buffer)); }
  return h.digest('hex').slice(0, 10); };

function timeRuns(t, n) {
  const times = new Array(n);
  for (let i = 0; i < n; i++) {
    const t0 = performance.now();
    t.generate();
    times[i] = performance.now() - t0;
  }
  return times;
}

const rows = [];
let names = Object.keys(TreePreset);
if (process.env.PRESETS) names = names.filter((n) => process.env.PRESETS.split(',').includes(n));
if (process.env.REVERSE) names.reverse();
for (const name of names) {
  const t = new Tree();          // fresh Tree per preset (options.copy merges, so no leftovers)
  t.loadPreset(name);            // copies preset options and generates once
  const seed = t.options.seed;   // preset's own seed, unchanged for all runs
  const refHash = hashGeom(t);
  timeRuns(t, WARMUP);
  let times = timeRuns(t, 50);
  let n = 50;
  if (median(times) < 5) { times = timeRuns(t, 200); n = 200; }
  const sameOutput = hashGeom(t) === refHash;

  const bPos = t.branchesMesh.geometry.attributes.position.count;
  const bTri = t.branchesMesh.geometry.index.count / 3;
  const lPos = t.leavesMesh.geometry.attributes.position.count;
  const lTri = t.leavesMesh.geometry.index.count / 3;
  const quadsPerLeaf = t.options.leaves.billboard === 'double' ? 2 : 1;
  const leaves = lPos / 4 / quadsPerLeaf;
  const s = [...times].sort((a, b) => a - b);
  rows.push({ name, seed, type: t.options.type, n, med: median(times),
    p10: s[Math.floor(0.1 * (n - 1))], p90: s[Math.floor(0.9 * (n - 1))], min: s[0],
    bPos, bTri, lPos, lTri, leaves, billboard: t.options.leaves.billboard,
    trellis: !!t.options.trellis.enabled, sameOutput,
    u16overflow: bPos > 65535 || lPos > 65535 });
  console.error(`${name}: median ${median(times).toFixed(3)} ms (n=${n})`);
}

const f = (x) => x.toFixed(2);
let md = '| preset | seed | median ms per tree | p10–p90 ms | runs | branch vertices | branch tris | leaf count (quads) | leaf vertices | deterministic |\n';
md += '|---|---|---|---|---|---|---|---|---|---|\n';
for (const r of rows)
  md += `| ${r.name} | ${r.seed} | ${f(r.med)} | ${f(r.p10)}–${f(r.p90)} | ${r.n} | ${r.bPos} | ${r.bTri} | ${r.leaves} (${r.lPos / 4}, ${r.billboard}) | ${r.lPos} | ${r.sameOutput ? 'yes' : 'NO'}${r.u16overflow ? ' (>65535 verts: Uint16 index overflow!)' : ''}${r.trellis ? ' (trellis on)' : ''} |\n`;
console.log(md);
