// Responses to DOM: one function per `"kind"` of the REPL's JSON protocol
// (docs/repl-protocol.md). Everything from the engine or a problem file goes in as text nodes
// or through KaTeX; no HTML is ever parsed.
import { inlineMath, mathText, tex } from './math.js';

/** An element with attributes (never event handlers) and children (strings become text). */
export function h(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (v === undefined || v === null || v === false) continue;
    if (k.startsWith('on')) throw new Error('no handlers through h()');
    e.setAttribute(k, v === true ? '' : String(v));
  }
  for (const c of children.flat()) {
    if (c === undefined || c === null || c === false) continue;
    e.append(typeof c === 'string' || typeof c === 'number' ? document.createTextNode(String(c)) : c);
  }
  return e;
}

const STATUS = {
  correct: { icon: '✓', word: 'Correct', cls: 'ok' },
  partial: { icon: '◐', word: 'Partly correct', cls: 'partial' },
  incorrect: { icon: '✗', word: 'Not correct', cls: 'bad' },
  invalid: { icon: '⚠', word: 'Could not be read', cls: 'warn' },
};

/** The line with the error's span marked, for a positioned error. */
export function marked(line, start, end) {
  const s = Math.max(0, Math.min(start, line.length));
  const e = Math.max(s, Math.min(end, line.length));
  const mark = h('mark', {}, line.slice(s, e) || ' ');
  return h('code', { class: 'marked' }, line.slice(0, s), mark, line.slice(e));
}

function diagnoses(list) {
  if (!list || list.length === 0) return null;
  return h('ul', { class: 'diagnoses' }, list.map((d) =>
    h('li', {}, h('code', { class: 'code' }, d.code), ' ', d.message)));
}

function verdict(r, line) {
  const s = STATUS[r.status] ?? { icon: '?', word: r.status, cls: 'warn' };
  const where = r.step ? `step ${r.number} of ${r.total}` : `part ${r.part}`;
  const box = h('div', { class: `verdict ${s.cls}`, 'data-status': r.status },
    h('p', { class: 'verdict-head' },
      h('span', { class: 'icon', 'aria-hidden': 'true' }, s.icon), ' ',
      h('strong', {}, s.word), ` — ${where}`,
      r.score > 0 && r.score < 1 ? ` (score ${Math.round(r.score * 100)}%)` : '',
      r.attempts ? `, attempt ${r.attempts}` : ''));
  if (r.reading_tex) {
    const m = h('span', { class: 'math' });
    tex(m, r.reading_tex);
    box.append(h('p', { class: 'reading' }, 'Read as: ', m));
  } else if (r.reading && r.reading.unicode) {
    box.append(h('p', { class: 'reading' }, 'Read as: ', h('span', { class: 'unicode' }, r.reading.unicode)));
  }
  if (r.error_span && line) box.append(h('p', {}, marked(line, r.error_span[0], r.error_span[1])));
  const d = diagnoses(r.diagnoses);
  if (d) box.append(d);
  return box;
}

function stepPrompt(s) {
  const p = h('div', { class: 'step' }, h('p', { class: 'step-head' }, `Step ${s.number} of ${s.total}: `, h('code', {}, s.step)));
  const q = h('p', {});
  inlineMath(q, s.prompt);
  p.append(q);
  if (s.note) p.append(h('p', { class: 'note' }, s.note));
  return p;
}

function simple(cls, ...children) {
  return h('div', { class: `response ${cls}` }, ...children);
}

/**
 * One response as DOM for the feedback area. `ui` gives the page's hooks: statement(r),
 * part(r), step(r), problems(r), simulation(r), done(r), suggestion(line).
 */
export function response(r, line, ui) {
  switch (r.kind) {
    case 'verdict': {
      const box = verdict(r, line);
      if (r.next) {
        ui.step(r.next);
        box.append(h('div', { class: 'next' }, h('p', {}, 'Next:'), stepPrompt(r.next)));
      } else if (r.step && r.next === null) {
        ui.step(null);
        box.append(h('p', { class: 'next' }, 'That was the last step: the derivation is complete.'));
      }
      return box;
    }
    case 'statement':
      ui.statement(r);
      return null;
    case 'part':
      ui.part(r);
      return simple('part-note', `Now part ${r.number}: `, h('code', {}, r.part), r.solved ? ' (already solved)' : '');
    case 'done':
      ui.done(r);
      return simple('done ok', h('span', { class: 'icon', 'aria-hidden': 'true' }, '★'), ' ', `Every part of ${r.problem} is solved.`);
    case 'hint': {
      if (r.hint === null || r.hint === undefined) {
        return simple('hint', `No more hints for ${r.part}: `, h('code', {}, r.reveal), ' shows the answer.');
      }
      const p = h('p', {}, h('strong', {}, `Hint ${r.number}`), r.remaining ? ` (${r.remaining} more): ` : ': ');
      inlineMath(p, r.hint_tex ?? r.hint);
      return simple('hint', p);
    }
    case 'solution': {
      const box = simple('solution', h('p', {}, h('strong', {}, `Solution of ${r.part}: `), h('span', { class: 'unicode' }, r.unicode || r.answer)));
      if (r.derivation && r.derivation.length) {
        box.append(h('ol', { class: 'derivation' }, r.derivation.map((s) => {
          const li = h('li', {});
          inlineMath(li, s.prompt);
          li.append(h('br'), h('span', { class: 'unicode' }, s.unicode || s.answer));
          return li;
        })));
      }
      return box;
    }
    case 'step':
      ui.step(r);
      return simple('step-note', stepPrompt(r));
    case 'step-solution': {
      ui.step(r.next);
      const box = simple('solution', h('p', {}, h('strong', {}, `Step ${r.number} (${r.step}): `), h('span', { class: 'unicode' }, r.unicode || r.answer)));
      box.append(r.next ? h('div', { class: 'next' }, h('p', {}, 'Next:'), stepPrompt(r.next)) : h('p', {}, 'That was the last step.'));
      return box;
    }
    case 'problems':
      ui.problems(r);
      return null;
    case 'progress':
      ui.problems(r);
      return simple('progress', `Solved ${r.solved} of ${r.parts} parts.`);
    case 'parts':
      return simple('parts', h('ul', {}, r.parts.map((p) => h('li', {}, p.solved ? '✓ ' : '○ ', `${p.number}. `, h('code', {}, p.id), p.current ? ' (current)' : ''))));
    case 'help':
      return simple('help', h('dl', {}, r.commands.flatMap((c) => [h('dt', {}, h('code', {}, c.usage)), h('dd', {}, c.summary)])));
    case 'analysis': {
      if (r.of === 'simulate') {
        ui.simulation(r);
        return simple('analysis', 'The simulation is drawn below.');
      }
      const box = simple('analysis');
      if (r.latex) {
        const m = h('div', { class: 'display-math' });
        tex(m, r.latex, true); // a reading, or the derivation's align* block
        box.append(m);
      }
      box.append(h('pre', { class: 'summary-text' }, r.text ?? ''));
      if (r.note) box.append(h('p', { class: 'note' }, r.note));
      return box;
    }
    case 'error': {
      const box = simple('error warn', h('p', {}, h('span', { class: 'icon', 'aria-hidden': 'true' }, '⚠'), ' ', h('code', { class: 'code' }, r.code), ' ', r.message));
      if (r.suggestion) {
        const b = h('button', { type: 'button', class: 'link' }, `Did you mean ${r.suggestion}?`);
        b.addEventListener('click', () => ui.suggestion(r.suggestion));
        box.append(b);
      }
      return box;
    }
    case 'quit':
      return simple('note', 'This page has no session to quit: just close it. Your progress is kept.');
    case 'none':
      return null;
    default:
      return null; // new kinds may be added; the protocol says to ignore unknown ones
  }
}

/** The problem's statement, symbols and parts. */
export function statement(r, els) {
  els.title.textContent = r.title;
  els.source.textContent = r.source ? `Source: ${r.source}` : '';
  els.statement.replaceChildren();
  mathText(els.statement, r.statement_tex ?? r.statement);
  els.symbols.replaceChildren(
    h('dt', {}, 'Coordinates'), h('dd', {}, (r.coordinates ?? []).join(', ')),
    h('dt', {}, 'Parameters'), h('dd', {}, (r.parameters ?? []).join(', ') || '—'),
    ...(r.assumptions && r.assumptions.length ? [h('dt', {}, 'Assumptions'), h('dd', {}, r.assumptions.join('; '))] : []),
  );
  // A problem whose numbers vary: the numbers being practised (`:variant` picks fresh ones).
  const varies = r.varies ?? [];
  els.variantBox.hidden = varies.length === 0;
  els.numbers.textContent = r.numbers && r.numbers.length
    ? `Your numbers: ${r.numbers.join(', ')}.`
    : `The numbers of ${varies.join(', ')} vary: practise with fresh numbers to get your own.`;
}
