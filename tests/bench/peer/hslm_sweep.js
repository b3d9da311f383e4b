// The standard EN 1991-2 HSLM check on a peer modal tool, for
// tests/bench/peer_ratio: HSLM-A1 to A10 x 101 speeds (100-400 km/h in steps
// of 3), 15 m simply supported span, f0 = 5 Hz, 15 t/m, 1 % damping, output
// at midspan; 1,010 runs. The peer is BeamDyn's web version (the JavaScript
// port of BeamDyn2D.m: Euler-Bernoulli elements, the lowest Nmod modes,
// each modal equation stepped by the exact Nigam-Jennings recurrence for a
// load linear within a step). Its directory is the first argument; this
// file only calls its public functions (buildModel, runTrain, buildTrains).
//
// Usage: node hslm_sweep.js PEER_DIR [--reps N] [--points midspan|all]
//   --reps N    sweeps in this process (default 2: the first includes the
//               JIT's warm-up, the later ones are warm)
//   --points    where the peer evaluates its outputs: midspan only (default,
//               what railvsi's study asks) or every node (0.5 m apart, the
//               peer's default)
// Prints, one item a line (read by tests/bench/peer_ratio):
//   model modes M f_hz F1 F2 ... fs_hz S dt_s D t_free_s T points P
//   rep K cpu_s C wall_s W jobs J     C: process.cpuUsage() user + system
//                                      around one whole sweep (model, trains,
//                                      1,010 runs); W: wall time of the same
//   peak TRAIN amax_mps2 A at_kmh V    per train, over its speeds
// The peak is runTrain's `amax`: per speed, max |vertical acceleration|
// over the output points and over the time samples t = k/fs, from the
// modal accelerations q'' = p - 2 zeta w q' - w^2 q at the samples (the
// modes' shapes at the point times q''); unfiltered (the tool applies no
// low-pass filter), no static correction (it does not apply to the
// acceleration), the record ending t_free_s after the last axle leaves.
'use strict';

const path = require('path');

function usage(msg) {
  if (msg) console.error('hslm_sweep.js: ' + msg);
  console.error('usage: node hslm_sweep.js PEER_DIR [--reps N] [--points midspan|all]');
  process.exit(2);
}

const args = process.argv.slice(2);
if (args.length < 1 || args[0].startsWith('--')) usage('give the peer directory first');
const peerDir = path.resolve(args[0]);
let reps = 2, points = 'midspan';
for (let i = 1; i < args.length; i++) {
  if (args[i] === '--reps' && i + 1 < args.length) reps = Number(args[++i]);
  else if (args[i] === '--points' && i + 1 < args.length) points = args[++i];
  else usage('unknown argument ' + args[i]);
}
if (!Number.isInteger(reps) || reps < 1) usage('--reps must be a positive integer');
if (points !== 'midspan' && points !== 'all') usage('--points is midspan or all');

let BD, TL;
try {
  BD = require(path.join(peerDir, 'beamdyn2d.js'));
  TL = require(path.join(peerDir, 'trainloads.js'));
} catch (e) {
  usage('cannot load the peer from ' + peerDir + ': ' + e.message);
}

// The study. EI from f0 of a simply supported span: f0 = pi/(2 L^2) sqrt(EI/m).
const L_m = 15, m_kg_per_m = 15e3, f0_hz = 5;
const EI_Nm2 = Math.pow(2 * L_m * L_m * f0_hz / Math.PI, 2) * m_kg_per_m;
const speeds_kmh = [];
for (let k = 0; k <= 100; k++) speeds_kmh.push(100 + 3 * k);

function input() {
  const inp = {
    L: [L_m], m: m_kg_per_m, EI: EI_Nm2,
    xi: 1.0,                      // damping ratio in %
    dL: 0.5,                      // element length, m
    bc: [[0, 1], [L_m, 1]],       // pinned at both ends
    v: speeds_kmh,
    W: 0,                         // point loads (no load distribution)
    Nmod: 3, fmax: 1e9,           // the three lowest modes, no cut-off
    statCorr: false, secForces: false,
    F_train: TL.buildTrains('HSLM-A', 20)
  };
  if (points === 'midspan') inp.x = [L_m / 2];
  return inp;
}

let peaks = null, model = null;
for (let r = 1; r <= reps; r++) {
  const c0 = process.cpuUsage();
  const t0 = process.hrtime.bigint();
  const inp = input();
  const mdl = BD.buildModel(inp);
  let jobs = 0;
  const these = [];
  for (const train of inp.F_train) {
    const out = BD.runTrain(mdl, inp, train, inp.v, inp.v);
    let a = -Infinity, at = NaN;
    for (let i = 0; i < out.amax.length; i++) if (out.amax[i] > a) { a = out.amax[i]; at = inp.v[i]; }
    these.push({ train: train.name, a, at });
    jobs += inp.v.length;
  }
  const wall = Number(process.hrtime.bigint() - t0) / 1e9;
  const cpu = process.cpuUsage(c0);
  if (peaks && peaks.some((p, i) => p.a !== these[i].a)) {
    console.error('hslm_sweep.js: the peaks differ between repetitions');
    process.exit(1);
  }
  peaks = these;
  model = { mdl, inp };
  console.log(`rep ${r} cpu_s ${((cpu.user + cpu.system) / 1e6).toFixed(4)} wall_s ${wall.toFixed(4)} jobs ${jobs}`);
}

const { mdl, inp } = model;
console.log(`model modes ${mdl.Nmod} f_hz ${Array.from(mdl.f, f => f.toFixed(4)).join(' ')} fs_hz ${mdl.fs} ` +
            `dt_s ${(1 / mdl.fs).toPrecision(6)} t_free_s ${mdl.t_fr} points ${inp.x ? inp.x.length : mdl.x.length}`);
for (const p of peaks) console.log(`peak ${p.train} amax_mps2 ${p.a.toFixed(6)} at_kmh ${p.at}`);
