// Typesetting for the page: KaTeX (bundled, `trust: false`) for mathematics, text nodes for
// everything else. A problem file is untrusted input, so nothing here ever parses HTML:
// statements and hints are split into text and `$…$` mathematics, and KaTeX builds its own
// DOM (katex.render, not renderToString, so its sizes go through CSSOM and the page's CSP
// needs no inline styles).
import katex from './katex/katex.mjs';

const OPTIONS = {
  throwOnError: false, // a bad formula is shown in red, not thrown
  trust: false, // no \href, \url, \includegraphics, \htmlClass … from a problem file
  strict: 'ignore',
  maxSize: 20,
  maxExpand: 500,
  output: 'htmlAndMathml', // MathML for screen readers
};

/** Typesets `source` into `el` (replacing its content); on any failure shows the source. */
export function tex(el, source, display = false) {
  try {
    katex.render(source, el, { ...OPTIONS, displayMode: display });
  } catch {
    el.textContent = source;
  }
}

/** Splits text into segments: `{math, display}` for `$…$`/`$$…$$`, `{text}` otherwise. */
export function segments(text) {
  const out = [];
  let buf = '';
  let i = 0;
  while (i < text.length) {
    const c = text[i];
    if (c === '\\' && text[i + 1] === '$') {
      buf += '$';
      i += 2;
      continue;
    }
    if (c === '$') {
      const display = text[i + 1] === '$';
      const open = display ? 2 : 1;
      const close = text.indexOf(display ? '$$' : '$', i + open);
      if (close !== -1) {
        if (buf) out.push({ text: buf });
        buf = '';
        out.push({ math: text.slice(i + open, close), display });
        i = close + open;
        continue;
      }
    }
    buf += c;
    i += 1;
  }
  if (buf) out.push({ text: buf });
  return out;
}

/** Appends `text` to `parent` as paragraphs (blank lines part them) of text and mathematics. */
export function mathText(parent, text) {
  const paragraphs = String(text ?? '').split(/\n\s*\n/).filter((p) => p.trim() !== '');
  for (const para of paragraphs) {
    const p = document.createElement('p');
    inlineMath(p, para.replace(/\s*\n\s*/g, ' ').trim());
    parent.append(p);
  }
}

/** Appends one line of text with `$…$` mathematics to `parent`. */
export function inlineMath(parent, text) {
  for (const s of segments(String(text ?? ''))) {
    if (s.text !== undefined) {
      parent.append(document.createTextNode(s.text));
    } else {
      const span = document.createElement('span');
      span.className = 'math';
      tex(span, s.math, s.display);
      parent.append(span);
    }
  }
}
