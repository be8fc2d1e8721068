// The simulation's pictures: SVG documents drawn by the engine (lagrange::chart, the same text
// the command line's --plot and --phase files hold), parsed as XML and imported into the page.
// Nothing is drawn or computed here. The documents carry no script, style or link, so the
// page's Content-Security-Policy stays as strict as it is.

/** The engine's SVG texts as nodes for the page; a text that is not SVG is left out. */
export function plots(charts) {
  const parser = new DOMParser();
  const out = [];
  for (const text of charts ?? []) {
    const doc = parser.parseFromString(text, 'image/svg+xml');
    const root = doc.documentElement;
    if (root.localName !== 'svg' || doc.getElementsByTagName('parsererror').length) continue;
    out.push(document.importNode(root, true));
  }
  return out;
}
