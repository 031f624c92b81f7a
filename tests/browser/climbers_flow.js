// Browser test of the climbers' side (issues 14 and 15): the feedback page
// behind the route card's QR code, consensus and drift, studies, and the
// worked example of docs/studies.md: a survey shaped like the paper's BRC
// study (4 routes, 44 participants, 14 items, from `strangebeta study
// simulate`) entered through the study page by 44 anonymous browsers, then
// analysed on the results page and by `strangebeta study analyze` on the
// exported CSV, asserting the same numbers. Also the abuse cases.
// Usage: node climbers_flow.js BASE_URL OUT_DIR BUILD_DIR   (tests/browser.sh)
'use strict';
const fs = require('fs');
const path = require('path');
const { execFileSync } = require('child_process');
const { chromium } = require('playwright-core');

const base = process.argv[2];
const out = path.join(process.argv[3], 'climbers');
const cli = path.join(process.argv[4], 'strangebeta');
const chromiumPath = process.env.SB_CHROMIUM || '/usr/bin/chromium';
let failures = 0, passes = 0;

function check(cond, what) {
  if (cond) { passes++; console.log('ok   ' + what); }
  else { failures++; console.log('FAIL ' + what); }
}

const PHONE = { width: 390, height: 844 };

function route(name, grade, type) {
  return [`name: ${name}`, `grade: ${grade}`, `type: ${type}`, 'setter: climbers test', '---',
          'R big jug at the start', 'L small crimp', 'R match', 'L sloper on the arete',
          'R high step to the rail', 'L dyno to the finish jug'].join('\n');
}

// The ability column of `study simulate` (10 .. 12.75 in quarters) as the
// YDS grade a climber types.
function ydsOf(ability) {
  const whole = Math.floor(ability);
  const letter = 'abcd'[Math.round((ability - whole) * 4)];
  return `5.${whole}${letter}`;
}

function csvRows(text) {
  const lines = text.trim().split('\n');
  const head = lines[0].split(',');
  return lines.slice(1).map((l) => {
    const cells = l.split(',');
    const o = {};
    head.forEach((h, i) => { o[h] = cells[i]; });
    return o;
  });
}

// A value of `json` by JSON pointer ("/items/3/alpha_if_deleted").
function at(json, pointer) {
  return pointer.split('/').slice(1).reduce((o, k) => (o == null ? undefined : o[k]), json);
}

async function noHorizontalScroll(page) {
  return page.evaluate(() => document.documentElement.scrollWidth <= window.innerWidth);
}

async function api(page, method, url, body) {
  return page.evaluate(async ([method, url, body]) => {
    const m = document.querySelector('meta[name="csrf-token"]');
    const headers = { 'Content-Type': 'application/json' };
    if (m) headers['X-CSRF-Token'] = m.content;
    const res = await fetch(url, { method, headers, body: JSON.stringify(body) });
    let data = {};
    try { data = await res.json(); } catch (e) { /* none */ }
    return { status: res.status, data, retry: res.headers.get('retry-after') };
  }, [method, url, body]);
}

async function signUp(ctx, name) {
  const page = await ctx.newPage();
  await page.goto(base + '/signup');
  await page.fill('#username', name);
  await page.fill('#password', 'correct horse battery');
  await Promise.all([page.waitForURL(base + '/'), page.click('#submit')]);
  return page;
}

(async () => {
  fs.mkdirSync(out, { recursive: true });
  const browser = await chromium.launch({
    executablePath: chromiumPath,
    headless: true,
    args: ['--headless', '--no-sandbox', '--disable-gpu', '--no-first-run',
           '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  const shot = async (page, name) =>
    page.screenshot({ path: path.join(out, name + '.png'), fullPage: true });
  const errors = [];
  const phone = async () => {
    const ctx = await browser.newContext({ viewport: PHONE, isMobile: true, hasTouch: true });
    ctx.setDefaultTimeout(30000);
    const page = await ctx.newPage();
    page.on('pageerror', (e) => errors.push(String(e)));
    return { ctx, page };
  };
  try {
    // ---- a setter with four routes -------------------------------------------------
    const setterCtx = await browser.newContext({ viewport: { width: 1200, height: 900 } });
    setterCtx.setDefaultTimeout(30000);
    const user = 'climbset' + (Date.now() % 100000);
    const setter = await signUp(setterCtx, user);
    const ids = [];
    const grades = [['V3', 'boulder'], ['V5', 'boulder'], ['5.10a', 'route'], ['5.11c', 'route']];
    for (let i = 0; i < 4; i++) {
      const r = await api(setter, 'POST', '/api/routes',
                          { crdl: route(`Study route ${i + 1}`, grades[i][0], grades[i][1]) });
      check(r.status === 201, `create route ${i + 1}`);
      ids.push(r.data.id);
    }

    // ---- /r/{id}: a climber without an account, at 390 px ----------------------------
    const a = await phone();
    await a.page.goto(base + '/r/' + ids[0]);
    check(await noHorizontalScroll(a.page), '/r/{id} has no horizontal scroll at 390 px');
    const items = await a.page.$$eval('#feedback-form fieldset.likert', (f) => f.length);
    check(items === 14, 'the feedback page asks the 14-item instrument by default');
    await a.page.check('input[name="q0"][value="2"]');
    await a.page.check('input[name="q3"][value="-1"]');
    await a.page.fill('#felt-grade', 'V6');
    await a.page.fill('#comment', 'Secret beta from climber A');
    await a.page.click('#feedback-submit');
    await a.page.waitForFunction(() => document.querySelector('#feedback-msg').textContent !== '');
    check((await a.page.textContent('#feedback-msg')).includes('Saved'), 'a climber saves feedback');
    const cookies = await a.ctx.cookies();
    const pc = cookies.find((c) => c.name === 'sb_climber');
    check(pc && pc.httpOnly && pc.expires > Date.now() / 1000 + 365 * 86400,
          'the participant token is a long-lived HttpOnly cookie');
    await a.page.reload();
    check(await a.page.isChecked('input[name="q0"][value="2"]') &&
          (await a.page.inputValue('#felt-grade')) === 'V6',
          'their answers come back to be edited');
    await a.page.check('input[name="q0"][value="1"]');
    await a.page.fill('#comment', 'Secret beta from climber A, edited');
    await a.page.click('#feedback-submit');
    await a.page.waitForFunction(() => document.querySelector('#feedback-msg').textContent !== '');
    await shot(a.page, '01-feedback-390');
    // A bad felt grade is refused with a clear message.
    await a.page.fill('#felt-grade', '5.10a');
    await a.page.click('#feedback-submit');
    await a.page.waitForFunction(
      () => document.querySelector('#feedback-msg').className.includes('bad'));
    check((await a.page.textContent('#feedback-msg')).includes('bouldering'),
          'a felt grade of the other discipline is refused naming it');

    // Six more climbers feel V6 on the V3: consensus and drift.
    for (let c = 0; c < 6; c++) {
      const b = await phone();
      await b.page.goto(base + '/r/' + ids[0]);
      const body = await b.page.content();
      if (c === 0) check(!body.includes('Secret beta'), "another climber never sees A's answers");
      await b.page.fill('#felt-grade', c % 2 ? 'V6' : '7A');  // Font 7A = V6
      await b.page.click('#feedback-submit');
      await b.page.waitForFunction(
        () => document.querySelector('#feedback-msg').textContent !== '');
      await b.ctx.close();
    }
    await a.page.reload();
    check((await a.page.textContent('#consensus-grade')).includes('V6'),
          'climbers see the consensus once enough felt grades are in');
    const d = await phone();
    await d.page.goto(base + '/r/' + ids[0]);
    check(!(await d.page.content()).includes('Secret beta'),
          "with the consensus shown, other climbers' comments stay hidden");
    await d.ctx.close();

    // The setter's views.
    await setter.goto(base + '/routes/' + ids[0]);
    check((await setter.textContent('#consensus-grade')).includes('V6') &&
          (await setter.getAttribute('#drift', 'class')).includes('flagged'),
          'the route page shows the consensus and flags the drift');
    await setter.goto(base + '/r/' + ids[0] + '/responses');
    check((await setter.textContent('#responses')).trim() === '7',
          'the setter sees 7 responses (the edit replaced, not added)');
    const comments = await setter.textContent('#comments');
    check(comments.includes('edited') && !comments.includes('climber A\n'),
          'the setter sees the edited comment once');
    check((await setter.$$('#felt-distribution tr.setter')).length === 1,
          "the felt-grade distribution marks the setter's band");
    await shot(setter, '02-setter-view');
    await setter.goto(base + '/drift');
    check((await setter.textContent('#drift-summary')).includes('1 flagged'),
          'the drift report counts the flagged route');

    // Abuse: one participant over the rate limit gets 429 with Retry-After.
    let limited = null;
    for (let i = 0; i < 70 && !limited; i++) {
      const r = await api(a.page, 'POST', `/api/r/${ids[1]}/feedback`, { felt_grade: 'V5' });
      if (r.status === 429) limited = r;
    }
    check(limited && limited.retry, 'feedback is rate-limited per participant (429, Retry-After)');

    // ---- a study ----------------------------------------------------------------
    await setter.goto(base + '/studies/new');
    // Malformed instrument upload: a clear error with file:line:col.
    await setter.fill('#study-name', 'BRC-shaped survey');
    for (const id of ids) await setter.check(`input.study-route[value="${id}"]`);
    await setter.check('input[name="instrument"][value="file"]');
    await setter.setInputFiles('#instrument-file', {
      name: 'bad.json', mimeType: 'application/json',
      buffer: Buffer.from('{"name": "x",\n "scale": [1, 5],\n "items": [,]}\n'),
    });
    await setter.click('#study-save');
    await setter.waitForFunction(() => document.querySelector('#study-msg').textContent !== '');
    const bad = await setter.textContent('#study-msg');
    check(/^bad\.json:3:\d+: /.test(bad), 'a malformed instrument upload names file:line:col');
    await setter.setInputFiles('#instrument-file', {
      name: 'dup.json', mimeType: 'application/json',
      buffer: Buffer.from(JSON.stringify({ name: 'x', scale: [1, 5], items: [
        { id: 'a', text: 'A' }, { id: 'a', text: 'B' }] })),
    });
    await setter.click('#study-save');
    await setter.waitForFunction(
      (before) => document.querySelector('#study-msg').textContent !== before, bad);
    check((await setter.textContent('#study-msg')).startsWith('dup.json: items[1].id'),
          'an invalid instrument names the file and field');
    await setter.check('input[name="instrument"][value="brc"]');
    await Promise.all([setter.waitForURL(/\/studies\/\d+$/), setter.click('#study-save')]);
    const studyId = setter.url().match(/\/studies\/(\d+)$/)[1];
    check(!!studyId, 'the setter creates a study');

    // The worked example: 44 simulated participants answer through /s/{id}.
    const csvPath = path.join(out, 'brc-survey.csv');
    execFileSync(cli, ['study', 'simulate', '--routes', '4', '--participants', '44',
                       '--instrument', 'brc', '--seed', '2011', '--quality', '0.2,0.1,0.9,-0.1',
                       '-o', csvPath]);
    const rows = csvRows(fs.readFileSync(csvPath, 'utf8'));
    const byParticipant = new Map();
    for (const r of rows) {
      if (!byParticipant.has(r.participant)) byParticipant.set(r.participant, []);
      byParticipant.get(r.participant).push(r);
    }
    let first = true, answered = 0;
    for (const [, prow] of byParticipant) {
      const c = await phone();
      await c.page.goto(base + '/s/' + studyId);
      const labels = await c.page.$$eval('section.study-route h2', (h) => h.map((x) => x.textContent));
      if (first) {
        const html = await c.page.content();
        check(labels.join('|') === 'Route 1|Route 2|Route 3|Route 4' &&
              !html.includes('Study route'), 'climbers see neutral labels only');
        check(await noHorizontalScroll(c.page), '/s/{id} has no horizontal scroll at 390 px');
      }
      for (const r of prow) {
        for (let i = 0; i < 14; i++) {
          const v = r['q' + (i + 1)];
          if (v !== '') await c.page.check(`input[name="r${r.route}q${i}"][value="${v}"]`);
        }
        const sec = `section.study-route[data-label="${r.route}"]`;
        await c.page.selectOption(`${sec} select.rank`, r.rank);
        await c.page.selectOption(`${sec} select.order`, r.order);
      }
      await c.page.fill('input.demo[data-key="outdoor_range.high"]', ydsOf(Number(prow[0].ability)));
      await c.page.fill('input.demo[data-key="years_climbing"]', '3');
      if (first) await shot(c.page, '03-study-form-390');
      await c.page.click('#study-submit');
      await c.page.waitForFunction(() => document.querySelector('#study-msg').textContent !== '');
      const ok = (await c.page.textContent('#study-msg')).includes('saved');
      answered += ok;
      if (first) {
        // Ballot stuffing: the same participant again, by page and by API.
        await c.page.reload();
        check(await c.page.isVisible('#study-answered'), 'the study page says it is answered');
        const full = { answers: Array(14).fill(0) };
        const again = await api(c.page, 'POST', `/api/s/${studyId}/responses`, {
          routes: [full, full, full, full] });
        check(again.status === 409 && again.data.error.includes('already'),
              'a second response of one participant is refused (409)');
      }
      first = false;
      await c.ctx.close();
    }
    check(answered === 44, `44 participants answered through the page (${answered})`);

    // The burst rule (issue 23): 44 new phones answering from one address
    // within minutes are a burst, so from the sixth on the responses are
    // held out of the numbers and shown to the owner, who accepts them here
    // (they were real) before reading the results.
    await setter.goto(base + '/studies/' + studyId);
    const heldN = await setter.$$eval('#held-responses li.held-response', (l) => l.length);
    check(heldN >= 1 && heldN <= 39, `the burst is held for the study's owner (${heldN} held)`);
    await setter.click('#accept-all-held');
    await setter.waitForFunction(
        () => document.querySelectorAll('#held-responses li.held-response').length === 0);

    // The results page and the CLI on the exported CSV agree.
    await setter.goto(base + '/studies/' + studyId);
    await shot(setter, '04-results');
    const shown = await setter.$$eval('[data-k]', (els) =>
      els.map((e) => [e.dataset.k, e.dataset.v]));
    const csv = await (await setterCtx.request.get(`${base}/studies/${studyId}/responses.csv`)).text();
    const inst = await (await setterCtx.request.get(`${base}/studies/${studyId}/instrument.json`)).text();
    fs.writeFileSync(path.join(out, 'exported.csv'), csv);
    fs.writeFileSync(path.join(out, 'instrument.json'), inst);
    const analyze = (responses) => JSON.parse(execFileSync(cli, ['study', 'analyze',
      '--instrument', path.join(out, 'instrument.json'), '--responses', responses,
      '--format', 'json']).toString());
    const fromExport = analyze(path.join(out, 'exported.csv'));
    const fromSimulation = analyze(csvPath);
    let same = 0, differ = [];
    for (const [k, v] of shown) {
      const want = at(fromExport, k);
      const got = v === 'nan' ? null : Number(v);
      if (want === got) same++; else differ.push(`${k}: page ${v}, cli ${want}`);
    }
    check(shown.length > 100 && differ.length === 0,
          `the results page shows the CLI's numbers exactly (${same} values; ${differ.slice(0, 3)})`);
    check(fromExport.rows === 176 && fromExport.participants === 44,
          'the export holds 176 rows of 44 participants');
    const keys = ['/alpha', '/kendall_w/w', '/kendall_w/p', '/routes/2/median_sum',
                  '/pairs/0/wilcoxon_p', '/pairs/1/welch_t', '/correlations/0/tau',
                  '/correlations/1/r_p'];
    const far = keys.filter((k) => !(Math.abs(at(fromExport, k) - at(fromSimulation, k)) <= 1e-9));
    check(far.length === 0, `the web survey equals the simulated CSV's analysis (${far})`);
    const censored = await setterCtx.request.get(`${base}/studies/${studyId}?censor=1`);
    check(censored.ok() && (await censored.text()).includes('rule'), 'the paper\'s censoring rule');
    const svg = await setterCtx.request.get(`${base}/studies/${studyId}/boxplot.svg`);
    check(svg.ok() && (await svg.text()).includes('<svg'), 'box plots as SVG');

    // Owner-only: another user and a stranger see nothing.
    const otherCtx = await browser.newContext();
    const other = await signUp(otherCtx, 'other' + (Date.now() % 100000));
    for (const p of ['', '/responses.csv', '/analysis.json', '/instrument.json', '/boxplot.svg']) {
      const r = await otherCtx.request.get(`${base}/studies/${studyId}${p}`);
      check(r.status() === 404, `another user gets 404 for /studies/{id}${p}`);
    }
    const anon = await browser.newContext();
    const r401 = await anon.request.get(`${base}/studies/${studyId}/responses.csv`);
    check(r401.status() === 401, 'a stranger gets 401 for the export');
    const other403 = await otherCtx.request.get(`${base}/r/${ids[0]}/responses`);
    check(other403.status() === 403, "another user cannot read a route's answers");
    const put = await api(other, 'PUT', `/api/studies/${studyId}`, { open: false });
    check(put.status === 404, 'another user cannot close the study');

    // Close it: the page says so and responses are refused.
    await setter.goto(base + `/studies/${studyId}/edit`);
    await setter.uncheck('#study-open');
    await Promise.all([setter.waitForURL(/\/studies\/\d+$/), setter.click('#study-save')]);
    const late = await phone();
    await late.page.goto(base + '/s/' + studyId);
    check(await late.page.isVisible('#study-closed'), 'a closed study says so');
    const full = { answers: Array(14).fill(0) };
    const refused = await api(late.page, 'POST', `/api/s/${studyId}/responses`, {
      routes: [full, full, full, full] });
    check(refused.status === 409 && refused.data.error.includes('closed'),
          'a closed study refuses responses (409)');
    check(errors.length === 0, 'no script errors' + (errors.length ? ': ' + errors[0] : ''));
  } catch (e) {
    failures++;
    console.log('FAIL exception: ' + (e.stack || e));
  } finally {
    await browser.close();
  }
  console.log(`climbers_flow.js: ${passes} passed, ${failures} failed`);
  process.exit(failures ? 1 : 0);
})();
