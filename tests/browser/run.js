// Browser test of the web app: drives Debian's chromium through Playwright.
// Usage: node run.js BASE_URL OUT_DIR   (tests/browser.sh starts the server)
'use strict';
const fs = require('fs');
const os = require('os');
const path = require('path');
const { chromium } = require('playwright-core');

const base = process.argv[2];
const out = process.argv[3];
const chromiumPath = process.env.SB_CHROMIUM || '/usr/bin/chromium';
let failures = 0, passes = 0;

function check(cond, what) {
  if (cond) { passes++; console.log('ok   ' + what); }
  else { failures++; console.log('FAIL ' + what); }
}

const ROUTE = [
  'name: Browser Test Arete',
  'grade: V3',
  'setter: playwright',
  'Set by the browser test.',
  '---',
  'R big jug at the start',
  'L small crimp',
  'R match',
  'L sloper on the arete',
  'R high step to the rail',
  'L dyno to the finish jug',
  'Q this line is wrong',
].join('\n');

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
  const shot = async (name) => page.screenshot({ path: path.join(out, name + '.png'), fullPage: true });
  const user = 'setter' + Date.now() % 100000;
  try {
    // Sign up (logs in and lands on the route list).
    await page.goto(base + '/signup');
    await page.fill('#username', user);
    await page.fill('#password', 'correct horse battery');
    await Promise.all([page.waitForURL(base + '/'), page.click('#submit')]);
    check((await page.textContent('#whoami')) === user, 'sign up logs the new user in');
    await shot('01-routes');

    // Log out, then log in again (a wrong password first).
    await page.click('#logout');
    await page.waitForSelector('#nav-login');  // the page reloads logged out
    check(await page.isVisible('#nav-login') && !(await page.$('#whoami')), 'log out');
    await page.goto(base + '/login');
    await page.fill('#username', user);
    await page.fill('#password', 'wrong password!');
    await page.click('#submit');
    await page.waitForFunction(() => document.querySelector('#form-msg').textContent.length > 0);
    check((await page.textContent('#form-msg')).includes('wrong'), 'wrong password is refused');
    await shot('02-login');
    await page.fill('#password', 'correct horse battery');
    await Promise.all([page.waitForURL(base + '/'), page.click('#submit')]);
    check((await page.textContent('#whoami')) === user, 'log in');

    // Add a route in the editor; live feedback marks the bad line.
    await page.goto(base + '/routes/new');
    await page.fill('#crdl', ROUTE);
    await page.waitForSelector('#feedback li.fb-error');
    const errLine = await page.textContent('#feedback li.fb-error');
    check(errLine.includes('Q this line is wrong'), 'editor highlights the unparsed line');
    const moves = await page.$$('#feedback li.fb-move');
    check(moves.length === 6, 'editor shows each move line (' + moves.length + ')');
    await shot('03-editor-error');
    await page.fill('#crdl', ROUTE.split('\n').slice(0, -1).join('\n'));
    await page.waitForFunction(() => !document.querySelector('#feedback li.fb-error'));
    await shot('04-editor');
    await Promise.all([page.waitForURL(/\/routes\/\d+$/), page.click('#save')]);
    const routeId = page.url().match(/\/routes\/(\d+)$/)[1];
    check((await page.textContent('h1')).includes('Browser Test Arete'), 'route saved and shown');
    await shot('05-route');

    // Vary it: the IC map loads; a click sets the variation IC.
    await page.goto(base + '/vary?routes=' + routeId);
    await page.waitForSelector('#icmap[data-ready="1"]');
    await page.fill('#pick-effect', '3');
    await page.click('#pick');
    await page.waitForSelector('#candidates li button');
    await page.click('#candidates li button');
    const suggested = await page.inputValue('#var_ic');
    check(/^-?[\d.]+,-?[\d.]+,-?[\d.]+$/.test(suggested), 'a suggested IC can be chosen (' + suggested + ')');
    const box = await (await page.$('#icmap')).boundingBox();
    // Left of the centre: x = ref x - 0.3 * grid * spacing, y = ref y.
    await page.click('#icmap', { position: { x: box.width * 0.2, y: box.height * 0.5 } });
    const ic = await page.inputValue('#var_ic');
    const parts = ic.split(',').map(Number);
    check(parts.length === 3 && ic !== suggested && parts[0] < -13 && Math.abs(parts[1] + 12) < 0.3 && parts[2] === 52,
          'clicking the IC map sets the variation IC (' + ic + ')');
    await page.check('#smooth');
    await shot('06-vary');
    await Promise.all([page.waitForURL(/\/variations\/\d+$/), page.click('#generate')]);
    const varId = page.url().match(/\/variations\/(\d+)$/)[1];

    // The plan page.
    check((await page.textContent('h1')).includes('Chaotic route plan'), 'plan page opens');
    check((await page.$$('table.plan-moves tbody tr:not(.suggested)')).length === 6, 'plan lists every move');
    check(await page.isVisible('figure.trajectory svg'), 'plan shows the trajectory picture');
    check((await page.textContent('.params')).includes(ic.split(',')[0]), 'plan shows the chosen IC');
    const smoothing = await page.textContent('.params');
    check(!smoothing.includes('Not requested'), 'plan reports the requested smoothing');
    const suggestionRows = (await page.$$('table.plan-moves tr.suggested')).length;
    console.log('     (' + suggestionRows + ' smoothing suggestion rows)');
    await shot('07-plan');
    await page.emulateMedia({ media: 'print' });
    await shot('08-plan-print');

    // Print to PDF: one A4 sheet.
    const pdfPath = path.join(out, 'plan-print.pdf');
    const pdf = await page.pdf({ path: pdfPath, format: 'A4', printBackground: true });
    const pages = (pdf.toString('latin1').match(/\/Type\s*\/Page[^s]/g) || []).length;
    check(pages === 1, 'the plan prints on one A4 sheet (' + pages + ' page(s))');
    const letter = await page.pdf({ format: 'Letter', printBackground: true });
    const lpages = (letter.toString('latin1').match(/\/Type\s*\/Page[^s]/g) || []).length;
    check(lpages === 1, 'the plan prints on one Letter sheet (' + lpages + ' page(s))');

    // The server-side PDF and SVG.
    const r = await page.request.get(base + '/variations/' + varId + '.pdf');
    const body = await r.body();
    fs.writeFileSync(path.join(out, 'plan-server.pdf'), body);
    check(r.status() === 200 && body.slice(0, 5).toString() === '%PDF-', 'server PDF download');
    const s = await page.request.get(base + '/variations/' + varId + '.svg');
    check(s.status() === 200 && (await s.text()).includes('<svg'), 'server SVG download');

    // A long plan (every route, ~80 moves) still prints on one sheet.
    const longId = await page.evaluate(async () => {
      const csrf = document.querySelector('meta[name="csrf-token"]').content;
      const list = await (await fetch('/api/routes?variations=0')).json();
      const ids = list.routes.map((r) => r.id).slice(0, 8);
      if (ids.length < 4) return null;
      const r = await fetch('/api/variations', {
        method: 'POST', headers: { 'Content-Type': 'application/json', 'X-CSRF-Token': csrf },
        body: JSON.stringify({ routes: ids, smooth: true }),
      });
      return r.status === 201 ? (await r.json()).id : -r.status;
    });
    if (longId === null) {
      console.log('skip long plan: fewer than 4 routes (no bundled examples)');
    } else {
      check(longId > 0, 'a variation of many routes is generated (' + longId + ')');
      await page.goto(base + '/variations/' + longId);
      const rows = await page.getAttribute('#plan', 'data-rows');
      for (const format of ['A4', 'Letter']) {
        const buf = await page.pdf({ path: path.join(out, 'long-plan-' + format + '.pdf'), format, printBackground: true });
        const n = (buf.toString('latin1').match(/\/Type\s*\/Page[^s]/g) || []).length;
        check(n === 1, 'a ' + rows + '-row plan prints on one ' + format + ' sheet (' + n + ' page(s))');
      }
      await page.emulateMedia({ media: 'print' });
      await shot('10-long-plan-print');
      await page.emulateMedia({ media: 'screen' });
    }

    // Search finds the new route.
    await page.goto(base + '/?q=arete');
    check((await page.textContent('#route-list')).includes('Browser Test Arete'), 'search finds the route');
    await page.goto(base + '/import');
    await shot('09-import');
    check(consoleErrors.length === 0, 'no script errors (' + consoleErrors.join('; ') + ')');
  } catch (e) {
    failures++;
    console.log('FAIL ' + (e && e.stack || e));
    try { await shot('failure'); } catch (_) { /* ignore */ }
  } finally {
    await context.close();
    fs.rmSync(userDir, { recursive: true, force: true });
  }
  console.log(`browser: ${passes} passed, ${failures} failed`);
  process.exit(failures ? 1 : 0);
})();
