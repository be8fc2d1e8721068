// The page's controller: starts the engine (pkg/engine.js, the `web` crate), sends it the
// student's lines and draws its JSON responses (render.js), keeps progress in localStorage in
// the REPL's progress.json format, and survives an engine panic by starting a fresh instance
// of the already compiled module. No mathematics here: every verdict, reading, hint and
// simulation comes from the engine.
import { Engine, initSync, panicForTest, resetEngine, version } from './pkg/engine.js';
import { h, marked, response, statement } from './render.js';
import { inlineMath, tex } from './math.js';
import { plots } from './plot.js';

const KEY = { progress: 'lagrange.progress', files: 'lagrange.files', open: 'lagrange.open', lines: 'lagrange.lines' };
const $ = (id) => document.getElementById(id);
const els = {
  summary: $('summary'), alert: $('engine-alert'), list: $('problem-list'), title: $('problem-title'),
  source: $('problem-source'), statement: $('statement'), symbols: $('symbols'), parts: $('parts'),
  promptTitle: $('prompt-title'), prompt: $('prompt'), form: $('answer-form'), answer: $('answer'),
  answerLabel: $('answer-label'), preview: $('preview'), completions: $('completions'),
  feedback: $('feedback'), history: $('history'), simulation: $('simulation'), plots: $('plots'),
  simSummary: $('simulation-summary'), findings: $('findings'), progressNote: $('progress-note'),
};

/** Timings for the end-to-end test's report (performance.now() milliseconds). */
const timings = { ready: null, handle: [], preview: [] };
let module; // the compiled WebAssembly.Module, kept to restart after a panic
let engine;
let lastPanic = null;
let lines = []; // earlier lines, for ↑
let recall = -1;

globalThis.lagrangeEnginePanic = (message) => {
  lastPanic = message;
};

function store(key, value) {
  try {
    localStorage.setItem(key, value);
  } catch {
    els.progressNote.textContent = 'This browser does not let the page keep your progress; export it before you leave.';
  }
}

function load(key) {
  try {
    return localStorage.getItem(key);
  } catch {
    return null;
  }
}

/** Saved problem files: [{name, text}]. */
function savedFiles() {
  try {
    const f = JSON.parse(load(KEY.files) ?? '[]');
    return Array.isArray(f) ? f : [];
  } catch {
    return [];
  }
}

/** A fresh engine instance from the compiled module, with the saved progress and files. */
function start() {
  initSync({ module });
  engine = new Engine();
  const files = savedFiles();
  if (files.length) engine.addProblems(JSON.stringify(files));
  const saved = load(KEY.progress);
  if (saved) {
    const r = JSON.parse(engine.importProgress(saved));
    if (!r.ok) els.progressNote.textContent = `Your saved progress could not be read (${r.message}); it is kept aside until you make progress here.`;
  }
}

/**
 * Runs `f` (a call into the engine). A panic traps the module: the page says so, starts a
 * fresh instance with the saved progress, reopens the problem, and returns null.
 */
function guarded(f) {
  try {
    return f();
  } catch (e) {
    const what = lastPanic ?? String(e && e.message ? e.message : e);
    lastPanic = null;
    const open = load(KEY.open);
    try {
      // Forget the dead instance's object without calling into it, so its finalizer never
      // frees a pointer in the new instance.
      try {
        engine?.__destroy_into_raw();
      } catch {
        // nothing to forget
      }
      resetEngine();
      start();
      if (open) engine.handle(`:open ${open}`);
      els.alert.replaceChildren(h('p', {}, h('strong', {}, 'The engine stopped on an internal error'),
        ' and was restarted; your progress is kept. Please report it: ', h('code', {}, what)));
    } catch (again) {
      els.alert.replaceChildren(h('p', {}, h('strong', {}, 'The engine failed and could not be restarted: '),
        h('code', {}, String(again)), ' — reload the page.'));
    }
    els.alert.hidden = false;
    return null;
  }
}

function save() {
  const p = guarded(() => engine.progress());
  if (p !== null) store(KEY.progress, p);
}

/** Sends one line to the engine and shows its responses. */
function send(line) {
  const t0 = performance.now();
  const out = guarded(() => engine.handle(line));
  timings.handle.push({ line, ms: performance.now() - t0 });
  if (out === null) return;
  const first = JSON.parse(out);
  const all = [first, ...(first.more ?? [])];
  const shown = [];
  for (const r of all) {
    const node = response(r, line, ui);
    if (node) shown.push(node);
  }
  if (shown.length) {
    if (els.feedback.childElementCount) {
      const old = h('div', { class: 'entry' }, ...els.feedback.childNodes);
      els.history.prepend(old);
    }
    els.feedback.replaceChildren(h('p', { class: 'echo' }, h('span', { class: 'visually-hidden' }, 'You entered: '), h('code', {}, line)), ...shown);
  }
  save();
  refresh();
}

/** The problem list and the controls, from the engine's state. */
function refresh() {
  const p = guarded(() => engine.handle(':problems'));
  if (p !== null) ui.problems(JSON.parse(p));
  const s = JSON.parse(guarded(() => engine.state()) ?? '{}');
  const open = Boolean(s.problem);
  for (const b of els.form.querySelectorAll('button')) b.disabled = !open;
  els.answer.disabled = !open;
  for (const b of els.form.querySelectorAll('.tutor-only')) b.hidden = !s.tutor;
  $('tutor-button').hidden = Boolean(s.tutor);
  els.answerLabel.textContent = s.tutor ? `Your answer to step ${s.step}` : s.part ? `Your answer to part ${s.part}` : 'Your answer';
  if (s.problem) store(KEY.open, s.problem);
  for (const li of els.list.querySelectorAll('button[data-id]')) {
    if (li.dataset.id === s.problem) li.setAttribute('aria-current', 'true');
    else li.removeAttribute('aria-current');
  }
}

let currentParts = [];

const ui = {
  statement(r) {
    statement(r, els);
    currentParts = (r.parts ?? []).map((p, i) => ({ ...p, prompt_tex: r.prompts_tex?.[i] ?? p.prompt }));
    els.simulation.hidden = true;
    els.history.replaceChildren();
    els.feedback.replaceChildren();
    ui.parts();
  },
  parts() {
    const progress = JSON.parse(guarded(() => engine.handle(':parts')) ?? '{}');
    const state = new Map((progress.parts ?? []).map((p) => [p.id, p]));
    els.parts.replaceChildren(...currentParts.map((part, i) => {
      const st = state.get(part.id) ?? {};
      const b = h('button', { type: 'button', class: 'part-button', 'aria-current': st.current ? 'step' : null },
        h('span', { class: st.solved ? 'tick ok' : 'tick', 'aria-hidden': 'true' }, st.solved ? '✓' : '○'), ' ',
        h('span', { class: 'visually-hidden' }, st.solved ? 'solved: ' : 'not solved: '));
      inlineMath(b, part.prompt_tex);
      b.addEventListener('click', () => send(`:part ${i + 1}`));
      return h('li', {}, b);
    }));
  },
  part(r) {
    els.promptTitle.textContent = `Part ${r.number} of ${currentParts.length || '?'} — ${r.part}`;
    els.prompt.replaceChildren();
    inlineMath(els.prompt, r.prompt_tex ?? r.prompt);
    ui.parts();
  },
  step(s) {
    if (!s) {
      ui.parts();
      return;
    }
    els.promptTitle.textContent = `Step ${s.number} of ${s.total} — ${s.step}`;
    els.prompt.replaceChildren(s.prompt);
  },
  done() {
    els.promptTitle.textContent = 'Every part is solved';
    els.prompt.replaceChildren('Pick another problem, or revisit a part.');
    ui.parts();
  },
  problems(r) {
    let solved = 0;
    let parts = 0;
    els.list.replaceChildren(...r.problems.map((p) => {
      solved += p.solved;
      parts += p.parts;
      const b = h('button', { type: 'button', 'data-id': p.id },
        h('span', { class: 'title' }, p.title),
        h('span', { class: 'count' }, `${p.solved}/${p.parts}`),
        h('progress', { max: p.parts, value: p.solved, 'aria-label': `${p.title}: ${p.solved} of ${p.parts} parts solved` }));
      b.addEventListener('click', () => {
        send(`:open ${p.id}`);
        els.answer.focus();
      });
      return h('li', {}, b);
    }));
    els.summary.textContent = `${solved} of ${parts} parts solved in ${r.problems.length} problems.`;
  },
  simulation(r) {
    els.simulation.hidden = false;
    els.plots.replaceChildren(...plots(r.series ?? { t: [], names: [], q: [], v: [] }));
    els.simSummary.textContent = r.text ?? '';
  },
  suggestion(s) {
    els.answer.value = s;
    els.answer.focus();
    preview();
  },
};

/** The live preview: how the engine reads the line so far. */
function preview() {
  const t0 = performance.now();
  const line = els.answer.value;
  const out = guarded(() => engine.preview(line));
  if (out === null) return;
  const r = JSON.parse(out);
  if (r.kind === 'reading') {
    const m = h('span', { class: 'math' });
    tex(m, r.latex);
    const dim = r.dimension && r.dimension.known ? h('span', { class: 'dim' }, ` — dimension ${r.dimension.known}`) : null;
    els.preview.replaceChildren(h('span', { class: 'label' }, 'Read as '), m, dim);
  } else if (r.kind === 'error') {
    els.preview.replaceChildren(h('span', { class: 'icon warn', 'aria-hidden': 'true' }, '⚠ '), marked(line, r.start, r.end), ' ', r.message, r.help ? ` — ${r.help}` : '');
  } else if (r.kind === 'command') {
    els.preview.replaceChildren(h('span', { class: 'label' }, 'A command'));
  } else {
    els.preview.replaceChildren();
  }
  timings.preview.push({ chars: line.length, ms: performance.now() - t0 });
}

/** Tab: completes the name before the cursor; returns whether it did anything. */
function complete() {
  const input = els.answer;
  const before = input.value.slice(0, input.selectionStart);
  const r = JSON.parse(guarded(() => engine.complete(before)) ?? '{"candidates":[]}');
  const word = before.slice(r.start);
  if (!word || r.candidates.length === 0) return false;
  let common = r.candidates[0];
  for (const c of r.candidates) while (!c.startsWith(common)) common = common.slice(0, -1);
  const after = input.value.slice(input.selectionStart);
  if (common.length > word.length) {
    input.value = before.slice(0, r.start) + common + after;
    const at = r.start + common.length;
    input.setSelectionRange(at, at);
    preview();
  }
  els.completions.textContent = r.candidates.length > 1 ? `Completions: ${r.candidates.join('  ')}` : '';
  return true;
}

function bind() {
  els.form.addEventListener('submit', (e) => {
    e.preventDefault();
    const line = els.answer.value;
    if (line.trim() === '') return;
    lines.push(line);
    lines = lines.slice(-200);
    store(KEY.lines, JSON.stringify(lines));
    recall = -1;
    els.answer.value = '';
    els.completions.textContent = '';
    send(line);
    preview();
  });
  els.answer.addEventListener('input', preview);
  els.answer.addEventListener('keydown', (e) => {
    if (e.key === 'ArrowUp' && lines.length) {
      e.preventDefault();
      recall = recall === -1 ? lines.length - 1 : Math.max(0, recall - 1);
      els.answer.value = lines[recall];
      preview();
    } else if (e.key === 'ArrowDown' && recall !== -1) {
      e.preventDefault();
      recall += 1;
      els.answer.value = recall < lines.length ? lines[recall] : '';
      if (recall >= lines.length) recall = -1;
      preview();
    } else if (e.key === 'Tab' && !e.shiftKey && !e.altKey && !e.ctrlKey) {
      // Only when there is a name to complete: otherwise Tab moves the focus, as it should.
      if (complete()) e.preventDefault();
    } else if (e.key === 'Escape') {
      els.completions.textContent = '';
    }
  });
  for (const b of els.form.querySelectorAll('button[data-line]')) {
    b.addEventListener('click', () => send(b.dataset.line));
  }
  $('simulate').addEventListener('click', () => send(':simulate'));
  $('file-input').addEventListener('change', (e) => openFiles([...e.target.files]));
  $('import-input').addEventListener('change', (e) => importProgress(e.target.files[0]));
  $('export').addEventListener('click', exportProgress);
  document.addEventListener('dragover', (e) => e.preventDefault());
  document.addEventListener('drop', (e) => {
    e.preventDefault();
    const files = [...(e.dataTransfer?.files ?? [])];
    if (files.length) openFiles(files);
  });
}

/** Problem files from the picker, a drop or the page URL: verified, findings shown. */
async function openFiles(files) {
  const read = [];
  for (const f of files) {
    if (f.size > 256 * 1024) {
      read.push({ name: f.name, text: '', tooLarge: f.size });
      continue;
    }
    read.push({ name: f.name, text: await f.text() });
  }
  addFiles(read);
}

function addFiles(read) {
  const out = guarded(() => engine.addProblems(JSON.stringify(read.filter((f) => !f.tooLarge))));
  if (out === null) return;
  const r = JSON.parse(out);
  const reports = [...read.filter((f) => f.tooLarge).map((f) => ({ name: f.name, added: false, findings: [{ line: 1, code: 'too-large', message: `the file is ${f.tooLarge} bytes; at most 262144 are read` }] })), ...(r.files ?? [])];
  const kept = savedFiles().filter((f) => !read.some((g) => g.name === f.name));
  for (const f of read) {
    const rep = (r.files ?? []).find((x) => x.name === f.name);
    if (rep && rep.added) kept.push({ name: f.name, text: f.text });
  }
  store(KEY.files, JSON.stringify(kept));
  els.findings.replaceChildren(...reports.map((f) => h('div', { class: `file-report ${f.added ? 'ok' : 'bad'}` },
    h('p', {}, h('span', { class: 'icon', 'aria-hidden': 'true' }, f.added ? '✓' : '✗'), ' ', h('code', {}, f.name), f.added ? ` — added as ${f.problem}` : ' — not added'),
    f.findings.length ? h('ul', { class: 'diagnoses' }, f.findings.map((x) => h('li', { class: 'finding' },
      h('span', { class: 'line' }, `line ${x.line}`), ': ', x.part ? `part ${x.part}: ` : '', h('code', { class: 'code' }, x.code), ' ', x.message))) : null)));
  // Adding files starts a new session over the larger bank: reopen what was open.
  const open = load(KEY.open);
  refresh();
  if (open) send(`:open ${open}`);
}

function exportProgress() {
  const p = guarded(() => engine.progress());
  if (p === null) return;
  const url = URL.createObjectURL(new Blob([p], { type: 'application/json' }));
  const a = h('a', { href: url, download: 'progress.json' });
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 1000);
  els.progressNote.textContent = 'Progress exported as progress.json.';
}

async function importProgress(file) {
  if (!file) return;
  const text = await file.text();
  const r = JSON.parse(guarded(() => engine.importProgress(text)) ?? '{}');
  if (r.ok) {
    save();
    els.progressNote.textContent = `Progress imported from ${file.name}.`;
    const open = load(KEY.open);
    refresh();
    if (open) send(`:open ${open}`);
  } else {
    els.progressNote.textContent = `Not imported: ${r.message ?? 'unreadable'}`;
  }
}

/** `?problems=a.toml,b.toml`: problem files hosted beside the page (same origin only). */
async function fromUrl() {
  const params = new URLSearchParams(location.search);
  const names = (params.get('problems') ?? '').split(',').map((s) => s.trim()).filter(Boolean);
  const read = [];
  for (const n of names) {
    const url = new URL(n, location.href);
    if (url.origin !== location.origin) {
      read.push({ name: n, text: '', tooLarge: 0 });
      continue;
    }
    try {
      const res = await fetch(url);
      read.push({ name: url.pathname.split('/').pop(), text: res.ok ? await res.text() : '' });
    } catch {
      read.push({ name: n, text: '' });
    }
  }
  if (read.length) addFiles(read);
  return params.get('open');
}

/**
 * Registers the service worker (sw.js) that keeps this build's files, so the page opens again
 * with the network off. After the page is ready, so it never delays the first check; a browser
 * without service workers (or a page on plain HTTP away from localhost) still works online.
 */
function offline() {
  if (!('serviceWorker' in navigator)) return;
  navigator.serviceWorker.register(new URL('sw.js', import.meta.url)).catch((e) => {
    console.warn(`lagrange: no offline copy (${e})`);
  });
}

async function main() {
  try {
    module = await WebAssembly.compileStreaming(fetch(new URL('pkg/engine_bg.wasm', import.meta.url)));
  } catch {
    const bytes = await (await fetch(new URL('pkg/engine_bg.wasm', import.meta.url))).arrayBuffer();
    module = await WebAssembly.compile(bytes);
  }
  start();
  $('version').textContent = version();
  try {
    lines = JSON.parse(load(KEY.lines) ?? '[]');
    if (!Array.isArray(lines)) lines = [];
  } catch {
    lines = [];
  }
  bind();
  refresh();
  timings.ready = performance.now();
  document.body.dataset.ready = 'true';
  offline();
  const asked = await fromUrl();
  const open = asked ?? load(KEY.open);
  if (open) send(`:open ${open}`);
}

// The end-to-end tests read the timings and prove a panic is survived through this hook.
globalThis.lagrangePage = { timings, crash: () => guarded(() => panicForTest()) };

main().catch((e) => {
  els.summary.textContent = `The engine could not start: ${e}`;
});
