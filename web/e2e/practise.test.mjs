// End-to-end tests of the page in real headless Chromium (Debian's /usr/bin/chromium driven by
// playwright-core): the page is served from 127.0.0.1 by server.mjs, and a student practises
// as a person would — by clicking and typing. Screenshots of the main states go to
// web/test-artifacts/, with the measured figures (figures.json). Run after scripts/build-web:
//   cd web && node --test e2e/
import { after, before, test } from 'node:test';
import assert from 'node:assert/strict';
import { mkdir, readFile, writeFile } from 'node:fs/promises';
import { existsSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { serve } from './server.mjs';

const here = dirname(fileURLToPath(import.meta.url));
const dist = join(here, '..', 'dist');
const fixtures = join(here, 'fixtures');
const artifacts = join(here, '..', 'test-artifacts');
const CHROMIUM = process.env.CHROMIUM ?? '/usr/bin/chromium';

let server;
let browser;
let context;
let page;
const outside = []; // requests to any other origin (none may happen)
const figures = {};

async function shot(name) {
  await page.screenshot({ path: join(artifacts, `${name}.png`), fullPage: true });
}

/** Types a line in the answer box and presses Enter; resolves when the page has answered. */
async function enter(line) {
  const before = await page.locator('#feedback .echo').count() ? await page.locator('#feedback').innerText() : '';
  await page.fill('#answer', line);
  await page.press('#answer', 'Enter');
  await page.waitForFunction((b) => document.querySelector('#feedback')?.innerText !== b, before);
}

async function openProblem(id) {
  await page.click(`#problem-list button[data-id="${id}"]`);
  await page.waitForFunction((i) => document.querySelector(`#problem-list button[data-id="${i}"]`)?.getAttribute('aria-current') === 'true', id);
}

before(async () => {
  assert.ok(existsSync(join(dist, 'index.html')), 'web/dist is missing: run scripts/build-web first');
  await mkdir(artifacts, { recursive: true });
  server = await serve({ '/': dist, '/sets/': fixtures });
  // Playwright gives the browser a fresh, empty user-data dir of its own.
  browser = await chromium.launch({
    executablePath: CHROMIUM,
    headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  // Every request is seen here: one for another origin is recorded and refused.
  await context.route('**/*', (route) => {
    const url = route.request().url();
    if (url.startsWith(server.origin) || url.startsWith('data:') || url.startsWith('blob:')) return route.continue();
    outside.push(url);
    return route.abort();
  });
  page = await context.newPage();
  page.on('pageerror', (e) => console.log(`page error: ${e.message}`));
});

after(async () => {
  await writeFile(join(artifacts, 'figures.json'), `${JSON.stringify(figures, null, 2)}\n`);
  console.log(`figures: ${JSON.stringify(figures)}`);
  await browser?.close();
  await server?.close();
});

test('the page loads, lists the bank and shows no progress yet', async () => {
  await page.goto(`${server.origin}/`);
  await page.waitForSelector('body[data-ready="true"]');
  const n = await page.locator('#problem-list button').count();
  assert.ok(n >= 16, `the bank's problems are listed (${n})`);
  assert.match(await page.textContent('#summary'), /^0 of \d+ parts solved in \d+ problems\.$/);
  const nav = await page.evaluate(() => performance.getEntriesByType('navigation')[0].startTime);
  figures.ready_ms_first_load = await page.evaluate((s) => globalThis.lagrangePage.timings.ready - s, nav);
  await shot('01-problem-list');
});

test('every bank problem opens with its statement and prompts typeset without a KaTeX error', async () => {
  const ids = await page.locator('#problem-list button[data-id]').evaluateAll((bs) => bs.map((b) => b.dataset.id));
  for (const id of ids) {
    await openProblem(id);
    const parts = await page.textContent(`#problem-list button[data-id="${id}"] .count`);
    assert.equal(`0/${await page.locator('#parts li').count()}`, parts, id);
    assert.equal(await page.locator('.katex-error').count(), 0, `${id}: every formula typesets`);
    assert.match(await page.textContent('#prompt-title'), /^Part 1 of \d+ — /, id);
  }
  await page.evaluate(() => localStorage.removeItem('lagrange.open'));
  await page.reload();
  await page.waitForSelector('body[data-ready="true"]');
});

test('simple-pendulum: a wrong answer gets its diagnosis, the right one moves on', async () => {
  await openProblem('simple-pendulum');
  assert.equal(await page.textContent('#problem-title'), 'Simple pendulum');
  // The statement's mathematics is typeset by KaTeX ($\theta$ in the file).
  assert.ok(await page.locator('#statement .katex').count() >= 3);
  assert.match(await page.textContent('#prompt-title'), /Part 1 of 8 — kinetic/);
  const focused = await page.evaluate(() => document.activeElement.id);
  assert.equal(focused, 'answer', 'opening a problem puts the cursor in the answer box');

  const t0 = await page.evaluate(() => performance.now());
  await enter("1/2*m*l*theta'^2");
  const t1 = await page.evaluate(() => performance.now());
  const ready = await page.evaluate(() => globalThis.lagrangePage.timings.ready);
  figures.first_verdict_ms = await page.evaluate(() => globalThis.lagrangePage.timings.handle.find((h) => h.line.includes('theta')).ms);
  figures.first_verdict_round_trip_ms = t1 - t0;
  figures.first_verdict_after_ready_ms = t1 - ready;
  const verdict = page.locator('#feedback .verdict');
  assert.equal(await verdict.getAttribute('data-status'), 'incorrect');
  assert.match(await verdict.locator('.verdict-head').innerText(), /✗\s*Not correct — part kinetic, attempt 1/);
  const codes = await page.locator('#feedback .diagnoses code.code').allInnerTexts();
  assert.deepEqual(codes, ['dimension', 'wrong-factor']);
  assert.match(await page.locator('#feedback .diagnoses').innerText(), /the factor l is wrong/);
  assert.equal(await page.locator('#feedback .reading .katex').count(), 1, 'the reading is typeset');
  await shot('02-wrong-answer');

  await enter("1/2*m*l^2*theta'^2");
  assert.equal(await page.locator('#feedback .verdict').getAttribute('data-status'), 'correct');
  assert.match(await page.locator('#feedback .verdict-head').innerText(), /✓\s*Correct — part kinetic/);
  assert.match(await page.textContent('#prompt-title'), /Part 2 of 8 — potential/);
  assert.match(await page.textContent('#summary'), /^1 of \d+ parts solved/);
  assert.equal(await page.textContent('#problem-list button[data-id="simple-pendulum"] .count'), '1/8');
  await shot('03-right-answer');
});

test('the live preview typesets the line and points at an error', async () => {
  await page.fill('#answer', '');
  await page.type('#answer', "-m*g*l*cos(theta");
  assert.match(await page.innerText('#preview'), /⚠/);
  assert.equal(await page.locator('#preview mark').count(), 1);
  await page.type('#answer', ')');
  assert.ok(await page.locator('#preview .katex').count() === 1, 'a readable line is typeset');
  assert.match(await page.innerText('#preview'), /dimension M L² T⁻²/);
  await shot('04-preview');
  // Tab completes a parameter name; ↑ recalls the last line entered.
  await page.fill('#answer', 'the');
  await page.press('#answer', 'Tab');
  assert.equal(await page.inputValue('#answer'), 'theta');
  await page.fill('#answer', '');
  await page.press('#answer', 'ArrowUp');
  assert.equal(await page.inputValue('#answer'), "1/2*m*l^2*theta'^2");
  await page.fill('#answer', '');
});

test('a hint, then three steps of the tutor with its verdicts', async () => {
  await page.click('button[data-line="hint"]');
  await page.waitForSelector('#feedback .hint');
  assert.match(await page.innerText('#feedback .hint'), /Hint 1 \(1 more\): Measure the height of the bob from the pivot\./);
  await shot('05-hint');

  await page.click('#tutor-button');
  await page.waitForSelector('#feedback .step-note');
  assert.match(await page.textContent('#prompt-title'), /Step 1 of 13 — position:1/);
  assert.equal(await page.textContent('#answer-label'), 'Your answer to step position:1');
  await enter('l*sin(theta), -l*cos(theta)');
  assert.equal(await page.locator('#feedback .verdict').getAttribute('data-status'), 'correct');
  assert.match(await page.textContent('#prompt-title'), /Step 2 of 13 — speed-squared:1/);
  await enter("l^2*theta'^2");
  assert.equal(await page.locator('#feedback .verdict').getAttribute('data-status'), 'correct');
  assert.match(await page.textContent('#prompt-title'), /Step 3 of 13 — kinetic/);
  await enter("1/2*m*l*theta'^2");
  assert.equal(await page.locator('#feedback .verdict').getAttribute('data-status'), 'incorrect');
  assert.deepEqual(await page.locator('#feedback .diagnoses code.code').allInnerTexts(), ['dimension', 'wrong-factor']);
  await enter("1/2*m*l^2*theta'^2");
  assert.equal(await page.locator('#feedback .verdict').getAttribute('data-status'), 'correct');
  assert.match(await page.textContent('#prompt-title'), /Step 4 of 13 — potential/);
  await shot('06-tutor');
  await page.click('button[data-line=":back"]');
  await page.waitForFunction(() => !document.querySelector('#tutor-button').hidden);
});

test('a reload keeps the progress and the open problem', async () => {
  await page.reload();
  await page.waitForSelector('body[data-ready="true"]');
  await page.waitForFunction(() => document.querySelector('#problem-title').textContent === 'Simple pendulum');
  assert.equal(await page.textContent('#problem-list button[data-id="simple-pendulum"] .count'), '1/8');
  assert.match(await page.textContent('#prompt-title'), /Part 2 of 8 — potential/);
  const saved = await page.evaluate(() => JSON.parse(localStorage.getItem('lagrange.progress')));
  assert.equal(saved.version, 1, 'stored in the REPL progress format');
  assert.equal(saved.problems['simple-pendulum'].parts.kinetic.solved, true);
  const nav = await page.evaluate(() => performance.getEntriesByType('navigation')[0].startTime);
  figures.ready_ms_reload = await page.evaluate((s) => globalThis.lagrangePage.timings.ready - s, nav);
});

test('a simulation is drawn as q(t) and a phase portrait', async () => {
  // The engine's SVG is inserted under the page's strict Content-Security-Policy: nothing in
  // it may be refused (an inline style or script would be).
  await page.evaluate(() => {
    globalThis.cspViolations = [];
    document.addEventListener('securitypolicyviolation', (e) => globalThis.cspViolations.push(`${e.violatedDirective} ${e.blockedURI}`));
  });
  await page.click('#simulate');
  await page.waitForSelector('#simulation:not([hidden]) svg.chart');
  assert.equal(await page.locator('#plots svg.chart').count(), 2);
  const d = await page.getAttribute('#plots svg.chart >> nth=0 >> path.curve', 'd');
  assert.ok(d.split('L').length > 300, 'the curve has the grid\'s points');
  assert.match(await page.textContent('#simulation-summary'), /dop853/i);
  // Names as the REPL shows them: θ and θ̇, never the typed `theta`.
  const summary = await page.textContent('#simulation-summary');
  assert.match(summary, /θ = /);
  assert.doesNotMatch(summary, /theta/);
  const labels = await page.locator('#plots svg.chart text.label').allTextContents();
  assert.deepEqual(labels, ['t / s', 'θ / rad', 'θ / rad', 'θ\u0307 / rad s⁻¹']);
  // Drawn, not just present: the q(t) chart has a size on the page and round ticks.
  const box = await page.locator('#plots svg.chart >> nth=0').boundingBox();
  assert.ok(box.width > 200 && box.height > 100, JSON.stringify(box));
  const ticks = await page.locator('#plots svg.chart >> nth=0 >> text:not(.label)').allTextContents();
  assert.ok(ticks.includes('0') && ticks.includes('−1') && ticks.includes('1'), ticks.join(' '));
  assert.deepEqual(await page.evaluate(() => globalThis.cspViolations), []);
  await page.locator('#simulation').scrollIntoViewIfNeeded();
  await shot('07-simulation');
});

test('problem files: a broken one shows its finding and line, a good one is practised', async () => {
  const files = ['broken.toml', 'wrong-key.toml', 'my-pendulum.toml'];
  await page.setInputFiles('#file-input', await Promise.all(files.map(async (f) => ({ name: f, mimeType: 'text/plain', buffer: await readFile(join(fixtures, f)) }))));
  await page.waitForSelector('#findings .file-report');
  const reports = await page.locator('#findings .file-report').allInnerTexts();
  const broken = reports.find((r) => r.includes('broken.toml'));
  assert.match(broken, /not added/);
  assert.match(broken, /line 6: toml-syntax/);
  const wrong = reports.find((r) => r.includes('wrong-key.toml'));
  assert.match(wrong, /line 74: part eom: wrong-eom/);
  assert.match(reports.find((r) => r.includes('my-pendulum.toml')), /added as my-pendulum/);
  await shot('08-findings');
  await openProblem('my-pendulum');
  await enter("1/2*m*l^2*theta'^2");
  assert.equal(await page.locator('#feedback .verdict').getAttribute('data-status'), 'correct');
  // Follow-through: an EOM that follows from the student's own wrong L says so.
  await page.click('#parts li:nth-child(3) button');
  await enter("1/2*m*l^2*theta'^2 - m*g*l*cos(theta)");
  assert.equal(await page.locator('#feedback .verdict').getAttribute('data-status'), 'incorrect');
  await page.click('#parts li:nth-child(5) button');
  await enter("m*l^2*theta'' - m*g*l*sin(theta) = 0");
  assert.deepEqual(await page.locator('#feedback .diagnoses code.code').allInnerTexts(), ['follows-from-earlier', 'sign-error']);
  assert.match(await page.innerText('#feedback .diagnoses'), /follows correctly from your Lagrangian; the mistake is in L/);
  await shot('08b-follow-through');
  await page.click('button[data-line=":solution"]');
  await page.waitForSelector('#feedback .solution');
  assert.match(await page.innerText('#feedback .solution'), /Solution of eom: m·l²·θ̈ \+ m·g·l·sin\(θ\) = 0/);
  // Bad input is a positioned error, never an attempt.
  await enter("1/2*m*(l*theta'^2");
  assert.equal(await page.locator('#feedback .verdict, #feedback .error').first().getAttribute('class').then((c) => /warn/.test(c)), true);
  assert.equal(await page.locator('#feedback mark').count() >= 1, true, 'the error is marked in the line');
});

test('a page URL names problem files hosted beside the page', async () => {
  await page.goto(`${server.origin}/?problems=sets/my-pendulum.toml&open=my-pendulum`);
  await page.waitForSelector('body[data-ready="true"]');
  await page.waitForFunction(() => document.querySelector('#problem-title').textContent === 'My pendulum (a copy)');
});

test('an untrusted problem file runs nothing (HTML, \\href{javascript:…})', async () => {
  const title = await page.title();
  await page.setInputFiles('#file-input', [{ name: 'xss.toml', mimeType: 'text/plain', buffer: await readFile(join(fixtures, 'xss.toml')) }]);
  await page.waitForFunction(() => /xss\.toml/.test(document.querySelector('#findings').innerText));
  assert.match(await page.innerText('#findings'), /added as xss-check/);
  await openProblem('xss-check');
  await page.click('button[data-line="hint"]');
  await page.waitForSelector('#feedback .hint');
  assert.equal(await page.locator('main img, nav img').count(), 0, 'no <img> was made from the file');
  assert.equal(await page.locator('main a, nav a').count(), 0, 'no link was made from \\href');
  assert.match(await page.innerText('#statement'), /<img src=x onerror=/, 'the markup is shown as text');
  assert.match(await page.innerText('#problem-list'), /<img src=x onerror=/);
  // Click whatever KaTeX made of \href: it is text in the error colour, not a link.
  await page.locator('#statement .katex').last().click();
  await page.waitForTimeout(200);
  assert.equal(await page.title(), title, 'no handler ran');
  assert.equal(await page.evaluate(() => document.querySelectorAll('script:not([src])').length), 0);
  await shot('09-untrusted-file');
});

test('an engine panic is caught, said and survived', async () => {
  await openProblem('simple-pendulum');
  await page.evaluate(() => globalThis.lagrangePage.crash());
  await page.waitForSelector('#engine-alert:not([hidden])');
  assert.match(await page.innerText('#engine-alert'), /stopped on an internal error and was restarted.*panic asked for by the page's test hook/s);
  await enter("-m*g*l*cos(theta)");
  assert.equal(await page.locator('#feedback .verdict').getAttribute('data-status'), 'correct');
  assert.equal(await page.textContent('#problem-list button[data-id="simple-pendulum"] .count'), '2/8', 'progress survived the restart');
  await shot('10-panic-survived');
});

test('with the network off, the page reopens from its service worker and practice goes on', async () => {
  // The server sends every file with no-store, so only the service worker can bring them back.
  const scope = await page.evaluate(async () => (await navigator.serviceWorker.ready).scope);
  assert.equal(scope, `${server.origin}/`);
  await context.setOffline(true);
  const asked = server.requests.length;
  // This page's URL still names sets/my-pendulum.toml: its last copy comes back too.
  assert.match(page.url(), /\?problems=sets\/my-pendulum\.toml/);
  await page.reload();
  await page.waitForSelector('body[data-ready="true"]');
  const nav = await page.evaluate(() => performance.getEntriesByType('navigation')[0].startTime);
  figures.ready_ms_offline_reload = await page.evaluate((s) => globalThis.lagrangePage.timings.ready - s, nav);
  assert.equal(await page.evaluate(() => Boolean(navigator.serviceWorker.controller)), true, 'the page came from its service worker');
  // Only the browser's own update check of the worker's script may get through: Chromium's
  // offline emulation covers the page and the worker's fetches, not that check (which, really
  // offline, just fails).
  assert.deepEqual(server.requests.slice(asked).filter((u) => u !== '/sw.js'), [], 'no page file reached the server');
  await page.waitForFunction(() => document.querySelector('#problem-title').textContent === 'My pendulum (a copy)');
  assert.match(await page.innerText('#findings'), /added as my-pendulum/);
  assert.equal(await page.locator('#problem-list button').count() >= 17, true);
  await page.waitForFunction(() => document.fonts.status === 'loaded');
  await shot('12-offline-reload');
  await openProblem('double-pendulum');
  await page.fill('#answer', '');
  const eom = "(m1+m2)*l1*theta1'' + m2*l2*theta2''*cos(theta1-theta2) + m2*l2*theta2'^2*sin(theta1-theta2) + (m1+m2)*g*sin(theta1) = 0; l2*theta2'' + l1*theta1''*cos(theta1-theta2) - l1*theta1'^2*sin(theta1-theta2) + g*sin(theta2) = 0";
  await page.click('#parts li:nth-child(4) button');
  await page.waitForFunction(() => /— eom/.test(document.querySelector('#prompt-title').textContent));
  const wrong = eom.replace('+ g*sin(theta2)', '- g*sin(theta2)');
  for (let i = 0; i < 6; i++) await enter(i % 2 ? wrong : `${wrong} `);
  const checks = await page.evaluate(() => globalThis.lagrangePage.timings.handle.filter((h) => h.line.includes("theta1''")).map((h) => h.ms));
  figures.double_pendulum_eom_checks_ms = checks.map((x) => Math.round(x * 10) / 10);
  assert.notEqual(await page.locator('#feedback .verdict').getAttribute('data-status'), 'correct');
  assert.ok(await page.locator('#feedback .diagnoses li').count() >= 1, 'the wrong sign is diagnosed');
  await enter(eom);
  assert.equal(await page.locator('#feedback .verdict').getAttribute('data-status'), 'correct');
  await context.setOffline(false);
});

test('the live preview keeps up with typing a 200-character line', async () => {
  await page.fill('#answer', '');
  await page.evaluate(() => { globalThis.lagrangePage.timings.preview.length = 0; });
  const line = "1/2*(m1+m2)*l1^2*theta1'^2 + 1/2*m2*l2^2*theta2'^2 + m2*l1*l2*theta1'*theta2'*cos(theta1-theta2) + (m1+m2)*g*l1*cos(theta1) + m2*g*l2*cos(theta2) - 1/2*m1*l1^2*theta1'^2*sin(theta1)^2 + 1/3*m2*g*l1*theta2^2";
  assert.ok(line.length >= 200, `${line.length}`);
  await page.type('#answer', line);
  const ms = await page.evaluate(() => globalThis.lagrangePage.timings.preview.map((p) => p.ms));
  const sorted = [...ms].sort((a, b) => a - b);
  figures.preview_keystrokes = ms.length;
  figures.preview_ms_median = Math.round(sorted[Math.floor(sorted.length / 2)] * 100) / 100;
  figures.preview_ms_p95 = Math.round(sorted[Math.floor(sorted.length * 0.95)] * 100) / 100;
  figures.preview_ms_max = Math.round(sorted[sorted.length - 1] * 100) / 100;
  figures.preview_ms_last_200_chars = Math.round(ms[ms.length - 1] * 100) / 100;
  assert.equal(await page.locator('#preview .katex').count(), 1);
});

test('progress exports and imports as the REPL\'s progress.json', async () => {
  const [download] = await Promise.all([page.waitForEvent('download'), page.click('#export')]);
  assert.equal(download.suggestedFilename(), 'progress.json');
  const exported = await readFile(await download.path(), 'utf8');
  const json = JSON.parse(exported);
  assert.equal(json.version, 1);
  assert.equal(json.problems['simple-pendulum'].parts.kinetic.solved, true);
  const before = await page.textContent('#summary');
  const file = (name, text) => ({ name, mimeType: 'application/json', buffer: Buffer.from(text) });
  await page.setInputFiles('#import-input', [file('bad.json', '{"version": 1, "problems": 3')]);
  await page.waitForFunction(() => /Not imported/.test(document.querySelector('#progress-note').textContent));
  assert.equal(await page.textContent('#summary'), before, 'a bad file changes nothing');
  await page.setInputFiles('#import-input', [file('empty.json', '{"version": 1, "problems": {}}')]);
  await page.waitForFunction(() => /^0 of /.test(document.querySelector('#summary').textContent));
  await page.setInputFiles('#import-input', [file('progress.json', exported)]);
  await page.waitForFunction((b) => document.querySelector('#summary').textContent === b, before);
});

test('a problem with variants: fresh numbers, judged with them, the seed kept with the progress', async () => {
  // The bank's problem with per-student variants (m, l and g vary; `potential` takes numbers).
  await openProblem('pendulum-numbers');
  assert.equal(await page.isVisible('#variant-button'), true, 'a problem with variants offers fresh numbers');
  assert.match(await page.textContent('#numbers'), /numbers of g, l, m vary/);
  const numbers = async () => Object.fromEntries(
    (await page.textContent('#numbers')).replace(/^Your numbers: |\.$/g, '').split(', ')
      .map((s) => s.split(' = ')).map(([k, v]) => [k, v.split(' ')[0]]));
  // Keyboard: the button is reached and pressed like any other.
  const fresh = async () => {
    const before = await page.textContent('#numbers');
    await page.focus('#variant-button');
    await page.keyboard.press('Enter');
    await page.waitForFunction((b) => document.querySelector('#numbers').textContent !== b, before);
    return numbers();
  };
  const first = await fresh();
  const second = await fresh();
  assert.notDeepEqual(second, first, 'fresh numbers differ from the last ones');
  assert.equal(await page.getAttribute('#variant-button', 'aria-describedby'), 'numbers');
  // The statement shows the numbers practised, typeset without a KaTeX error.
  assert.match(await page.innerText('#statement'), new RegExp(`mass ${second.m} kg`));
  assert.equal(await page.locator('.katex-error').count(), 0);
  // The seed is kept in the browser's progress, in the REPL's progress.json format.
  const saved = await page.evaluate(() => localStorage.getItem('lagrange.progress'));
  assert.match(saved, /"pendulum-numbers": \{\s*"parts": \{\},\s*"variant_seed": \d+/);
  // Judged with these numbers: the last numbers' answer is wrong now, these are right.
  await page.click('#parts li:nth-child(2) button');
  await page.waitForFunction(() => /— potential/.test(document.querySelector('#prompt-title').textContent));
  await enter(`-${first.m}*${first.g}*${first.l}*cos(theta)`);
  assert.equal(await page.locator('#feedback .verdict').getAttribute('data-status'), 'incorrect');
  await enter(`-${second.m}*${second.g}*${second.l}*cos(theta)`);
  assert.equal(await page.locator('#feedback .verdict').getAttribute('data-status'), 'correct');
  await shot('10b-variant');
  // Coming back practises the same numbers (the page's own address: an earlier test left
  // one that asks for another problem).
  await page.goto(`${server.origin}/`);
  await page.waitForSelector('body[data-ready="true"]');
  await page.waitForFunction(() => /^Your numbers: /.test(document.querySelector('#numbers').textContent));
  assert.deepEqual(await numbers(), second);
});

test('one column at 360 px, labelled controls, live verdicts', async () => {
  await page.setViewportSize({ width: 360, height: 780 });
  await openProblem('simple-pendulum');
  await page.fill('#answer', '');
  await enter("m*g*l*cos(theta)");
  const overflow = await page.evaluate(() => document.documentElement.scrollWidth);
  assert.ok(overflow <= 360, `no sideways scrolling at 360 px (${overflow})`);
  assert.equal(await page.getAttribute('#feedback', 'aria-live'), 'polite');
  assert.equal(await page.locator('#answer').count(), 1);
  assert.ok(await page.getByLabel(/Your answer to part/).count() === 1, 'the answer box has its label');
  await page.locator('#work').scrollIntoViewIfNeeded();
  await page.screenshot({ path: join(artifacts, '11-phone.png') });
  await page.setViewportSize({ width: 1280, height: 900 });
});

test('no request left the page\'s origin', async () => {
  assert.deepEqual(outside, []);
  assert.ok(server.requests.some((u) => u.endsWith('engine_bg.wasm')));
  assert.ok(server.requests.some((u) => u.includes('.woff2')), 'fonts came from the page\'s own folder');
});
