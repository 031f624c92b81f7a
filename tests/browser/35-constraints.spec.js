// The vary page's constraints (issue 13): keep_start and alternate_hands set
// in the advanced panel are part of the form's URL, are sent to the API, and
// the card shows the constraints held (and its difficulty column and
// warnings); Back restores them; a bad crux window is refused in words next
// to the form.
'use strict';
const route = (name, moves) => ['name: ' + name, 'grade: V3', '---'].concat(moves).join('\n');
module.exports = async (t) => {
  const { page, base, check, shot, api } = t;
  await page.goto(base + '/');
  const ids = [];
  for (const [name, moves] of [
    ['Constraint Delta', ['R delta jug start', 'R delta crimp', 'L delta sloper (crux)', 'L delta pinch', 'R delta edge', 'R delta finish jug']],
    ['Constraint Echo', ['L echo pocket', 'L echo gaston', 'R echo undercling', 'R echo crimp', 'L echo side pull', 'R echo top']]]) {
    const r = await api('POST', '/api/routes', { crdl: route(name, moves), public: true });
    ids.push(r.data.id);
  }
  await page.goto(base + '/vary?routes=' + ids.join(','));
  await page.selectOption('#preset', 'default');  // the paper's preset, by name (issue 22)
  await page.click('#advanced summary');
  await page.check('#keep_start');
  await page.check('#alternate_hands');
  await page.fill('#name', 'Constrained card');
  check(/keep_start=1/.test(page.url()) && /alternate_hands=1/.test(page.url()), 'the constraints are in the form URL (' + page.url() + ')');
  await shot('35-vary-constraints');
  const formUrl = page.url();
  await Promise.all([page.waitForURL(/\/variations\/\d+/), page.click('#generate')]);
  const search = await page.textContent('#card-search');
  check(/held: keep-start, alternate-hands/.test(search) && !/NOT held/.test(search),
        'the card shows the constraints held (' + search + ')');
  check(await page.isVisible('th.diff') && (await page.$$('td.diff .bar')).length > 0, 'the card has a difficulty column');
  check(/Estimated grade/.test(await page.textContent('#card-grades')), 'the card shows the estimated grade');
  await shot('36-card-constraints');
  await page.emulateMedia({ media: 'print' });
  await shot('37-card-constraints-print');
  const buf = await page.pdf({ format: 'A4', printBackground: true });
  check(t.pdfPages(buf) === 1, 'the constrained card prints on one A4 page');
  await page.emulateMedia({ media: 'screen' });
  // Back: the same constraints, ticked.
  await page.goBack();
  await page.waitForSelector('#keep_start');
  check(await page.isChecked('#keep_start') && await page.isChecked('#alternate_hands') &&
        !(await page.isChecked('#keep_finish')) && await page.evaluate(() => document.querySelector('#advanced').open),
        'Back restores the constraints in the open advanced panel');
  check(page.url() === formUrl, 'the form URL is the same after Back');
  // A bad crux window: refused, in words, next to the form.
  await page.fill('#crux_window', '0.9,0.1');
  await page.click('#generate');
  await page.waitForFunction(() => /Crux window/.test(document.querySelector('#vary-msg').textContent));
  const msg = await page.textContent('#vary-msg');
  check(/^Crux window: /.test(msg) && page.url().includes('/vary'), 'a bad crux window is refused by its label (' + msg + ')');
  await shot('38-vary-constraint-error');
};
