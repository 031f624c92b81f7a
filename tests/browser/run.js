// Browser tests of the web app: drives Debian's chromium through Playwright.
// Usage: node run.js BASE_URL OUT_DIR [FILTER]   (tests/browser.sh starts the server)
//
// Runs every tests/browser/*.spec.js in file-name order in one browser
// context. A spec exports `async function (t)`; `t` holds the page, check(),
// shot(), api() and `t.state`, which specs share (the signed-up user, route
// ids). Add a spec by adding a file: nothing here lists them. A spec that
// throws counts as one failure; the next spec still runs.
'use strict';
const fs = require('fs');
const os = require('os');
const path = require('path');
const { chromium } = require('playwright-core');

const base = process.argv[2];
const out = process.argv[3];
const filter = process.argv[4] || '';
const chromiumPath = process.env.SB_CHROMIUM || '/usr/bin/chromium';
let failures = 0, passes = 0;

function check(cond, what) {
  if (cond) { passes++; console.log('ok   ' + what); }
  else { failures++; console.log('FAIL ' + what); }
}

(async () => {
  fs.mkdirSync(out, { recursive: true });
  const userDir = fs.mkdtempSync(path.join(os.tmpdir(), 'sb-chromium-'));
  const context = await chromium.launchPersistentContext(userDir, {
    executablePath: chromiumPath,
    headless: true,
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
           '--disable-background-networking', '--disable-component-update', '--disable-sync'],
    viewport: { width: 1200, height: 900 },
  });
  context.setDefaultTimeout(30000);
  const page = context.pages()[0] || await context.newPage();
  const consoleErrors = [];
  page.on('pageerror', (e) => consoleErrors.push(String(e)));
  const t = {
    base, out, page, context, check, state: {},
    shot: async (name) => page.screenshot({ path: path.join(out, name + '.png'), fullPage: true }),
    // Calls the JSON API from the page (its session and CSRF token).
    api: async (method, url, body) => page.evaluate(async ([method, url, body]) => {
      const m = document.querySelector('meta[name="csrf-token"]');
      const headers = { 'Accept': 'application/json' };
      if (body !== undefined && body !== null) headers['Content-Type'] = 'application/json';
      if (m) headers['X-CSRF-Token'] = m.content;
      const r = await fetch(url, { method, headers, body: body == null ? undefined : JSON.stringify(body) });
      const text = await r.text();
      let data = null;
      try { data = JSON.parse(text); } catch (e) { data = text; }
      return { status: r.status, data };
    }, [method, url, body === undefined ? null : body]),
    pdfPages: (buf) => (buf.toString('latin1').match(/\/Type\s*\/Page[^s]/g) || []).length,
  };
  const specs = fs.readdirSync(__dirname).filter((f) => f.endsWith('.spec.js') && f.includes(filter)).sort();
  const started = Date.now();
  for (const f of specs) {
    console.log('---- ' + f);
    const specStarted = Date.now();
    try {
      await require(path.join(__dirname, f))(t);
    } catch (e) {
      failures++;
      console.log('FAIL ' + f + ': ' + (e && e.stack || e));
      try { await t.shot('failure-' + f.replace(/\.spec\.js$/, '')); } catch (_) { /* ignore */ }
    }
    console.log(`---- ${f}: ${((Date.now() - specStarted) / 1000).toFixed(1)} s`);
  }
  check(consoleErrors.length === 0, 'no script errors (' + consoleErrors.join('; ') + ')');
  await context.close();
  fs.rmSync(userDir, { recursive: true, force: true });
  console.log(`browser: ${passes} passed, ${failures} failed (${specs.length} spec files, ` +
              `${((Date.now() - started) / 1000).toFixed(1)} s)`);
  process.exit(failures ? 1 : 0);
})();
