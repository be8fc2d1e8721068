// SVG charts of a simulation: q(t) per coordinate and the phase portrait (q, q̇), drawn from
// the even grid the engine computed (its `series`). Only scaling to the picture happens here;
// every number plotted comes from the engine.
const NS = 'http://www.w3.org/2000/svg';
const COLOURS = ['#1f5fa8', '#b3401b', '#2b7a3d', '#7a3e9d', '#8a6d00', '#00738a'];
const W = 480;
const H = 300;
const M = { left: 62, right: 14, top: 16, bottom: 44 };

function el(tag, attrs = {}, text) {
  const e = document.createElementNS(NS, tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, String(v));
  if (text !== undefined) e.textContent = text;
  return e;
}

/** The finite range of some arrays, widened when flat. */
function range(arrays) {
  let lo = Infinity;
  let hi = -Infinity;
  for (const a of arrays) {
    for (const x of a) {
      if (typeof x === 'number' && Number.isFinite(x)) {
        lo = Math.min(lo, x);
        hi = Math.max(hi, x);
      }
    }
  }
  if (!Number.isFinite(lo)) return [-1, 1];
  if (hi - lo < 1e-12 * Math.max(1, Math.abs(lo))) {
    const pad = Math.max(Math.abs(lo) * 0.1, 1e-6);
    return [lo - pad, hi + pad];
  }
  return [lo, hi];
}

/** Tick values: about five round numbers across [lo, hi]. */
function ticks(lo, hi) {
  const raw = (hi - lo) / 5;
  const mag = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 5, 10].map((f) => f * mag).find((s) => s >= raw) ?? raw;
  const out = [];
  for (let v = Math.ceil(lo / step) * step; v <= hi + step * 1e-9; v += step) out.push(v);
  return out;
}

function fmt(v) {
  if (v === 0) return '0';
  const a = Math.abs(v);
  return a >= 1e4 || a < 1e-3 ? v.toExponential(1) : String(Number(v.toPrecision(4)));
}

/** One chart: several (xs, ys) curves, named, with axis labels. */
function chart(title, xLabel, yLabel, curves) {
  const svg = el('svg', { viewBox: `0 0 ${W} ${H}`, role: 'img', class: 'chart' });
  svg.append(el('title', {}, title));
  const [x0, x1] = range(curves.map((c) => c.xs));
  const [y0, y1] = range(curves.map((c) => c.ys));
  const sx = (x) => M.left + ((x - x0) / (x1 - x0)) * (W - M.left - M.right);
  const sy = (y) => H - M.bottom - ((y - y0) / (y1 - y0)) * (H - M.top - M.bottom);
  const axes = el('g', { class: 'axes' });
  axes.append(el('rect', { x: M.left, y: M.top, width: W - M.left - M.right, height: H - M.top - M.bottom, fill: 'none', stroke: '#777' }));
  for (const t of ticks(x0, x1)) {
    axes.append(el('line', { x1: sx(t), x2: sx(t), y1: H - M.bottom, y2: H - M.bottom + 5, stroke: '#777' }));
    axes.append(el('text', { x: sx(t), y: H - M.bottom + 18, 'text-anchor': 'middle' }, fmt(t)));
  }
  for (const t of ticks(y0, y1)) {
    axes.append(el('line', { x1: M.left - 5, x2: M.left, y1: sy(t), y2: sy(t), stroke: '#777' }));
    axes.append(el('text', { x: M.left - 8, y: sy(t) + 4, 'text-anchor': 'end' }, fmt(t)));
  }
  axes.append(el('text', { x: (M.left + W - M.right) / 2, y: H - 6, 'text-anchor': 'middle', class: 'label' }, xLabel));
  axes.append(el('text', { x: 14, y: (M.top + H - M.bottom) / 2, 'text-anchor': 'middle', class: 'label', transform: `rotate(-90 14 ${(M.top + H - M.bottom) / 2})` }, yLabel));
  svg.append(axes);
  curves.forEach((c, k) => {
    let d = '';
    let pen = false;
    for (let i = 0; i < c.xs.length; i++) {
      const x = c.xs[i];
      const y = c.ys[i];
      if (typeof x !== 'number' || typeof y !== 'number') {
        pen = false;
        continue;
      }
      d += `${pen ? 'L' : 'M'}${sx(x).toFixed(1)},${sy(y).toFixed(1)}`;
      pen = true;
    }
    svg.append(el('path', { d, fill: 'none', stroke: COLOURS[k % COLOURS.length], 'stroke-width': 1.6, class: 'curve' }));
  });
  if (curves.length > 1) {
    // The legend on a white card, so the curves passing under it do not cross its names.
    svg.append(el('rect', { x: W - M.right - 96, y: M.top + 2, width: 94, height: 16 * curves.length + 6, fill: '#fff', 'fill-opacity': 0.9, stroke: '#c9ccd1' }));
    curves.forEach((c, k) => {
      const y = M.top + 14 + 16 * k;
      svg.append(el('line', { x1: W - M.right - 90, x2: W - M.right - 70, y1: y - 4, y2: y - 4, stroke: COLOURS[k % COLOURS.length], 'stroke-width': 2 }));
      svg.append(el('text', { x: W - M.right - 66, y }, c.name));
    });
  }
  return svg;
}

function unit(u) {
  return u ? ` [${u}]` : '';
}

/** The simulation's pictures: q(t) of every coordinate, then one phase portrait per coordinate.
 * Names are shown as the engine names them (`labels`: θ₁, `rate_labels`: θ̇₁), as the REPL does. */
export function plots(series) {
  const out = [];
  const t = series.t ?? [];
  const names = series.names ?? [];
  const shown = names.map((n, i) => series.labels?.[i] ?? n);
  const rates = names.map((n, i) => series.rate_labels?.[i] ?? `${n}'`);
  const units = series.units ?? {};
  const curves = shown.map((n, i) => ({ name: n, xs: t, ys: series.q[i] }));
  const sameUnit = new Set((units.coordinates ?? []).map((u) => u ?? '')).size <= 1;
  const qLabel = shown.length === 1 ? `${shown[0]}${unit(units.coordinates?.[0])}` : `coordinates${sameUnit ? unit(units.coordinates?.[0]) : ''}`;
  out.push(chart(`The coordinates against time: ${shown.join(', ')}`, `t${unit(units.time)}`, qLabel, curves));
  shown.forEach((n, i) => {
    out.push(chart(`Phase portrait of ${n}: ${rates[i]} against ${n}`, `${n}${unit(units.coordinates?.[i])}`, `${rates[i]}${unit(units.velocities?.[i])}`,
      [{ name: n, xs: series.q[i], ys: series.v[i] }]));
  });
  return out;
}
