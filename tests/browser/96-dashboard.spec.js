// The setting dashboard (issue 22): a head setter opens the dashboard from the gym page, sets a
// wall's grade and style targets with the form, and sees the target-vs-current chart with its
// table and the gaps in words; the floor plan SVG fits a 390 px phone and its walls link to the
// wall pages.
'use strict';

module.exports = async (t) => {
  const { page, base, check, shot, api } = t;
  const n = Date.now() % 100000;
  const head = 'dash' + n;
  const password = 'correct horse battery';

  await page.context().clearCookies();
  await page.goto(base + '/signup');
  await page.fill('#username', head);
  await page.fill('#password', password);
  await Promise.all([page.waitForURL(base + '/'), page.click('#submit')]);
  const gym = (await api('POST', '/api/gyms', { name: 'Dash Gym ' + n })).data.id;
  const gp = '/api/gyms/' + gym;
  const cave = (await api('POST', gp + '/walls', { name: 'Cave', reset_weeks: 4,
                                                   plan: { x: 0, y: 0, w: 8, h: 3 } })).data.id;
  const slab = (await api('POST', gp + '/walls', { name: 'Slab', reset_weeks: 8,
                                                   plan: { x: 9, y: 0, w: 5, h: 6 } })).data.id;
  const today = new Date().toISOString().slice(0, 10);
  for (const [name, grade, wall, date, moves] of [
    ['Old Crimps', 'V3', 'Cave', '2020-01-01', 'R small crimp\nL small crimp\n'],
    ['Heel Fest', 'V5', 'Cave', '2020-02-01', 'R heel hook the arete\nL jug\n'],
    ['Fresh Slab', 'V1', 'Slab', today, 'R small crimp\nL mantle onto the ledge\n']]) {
    const r = await api('POST', '/api/routes', {
      crdl: 'name: ' + name + '\ngrade: ' + grade + '\n---\n' + moves, public: true, gym,
      wall, state: 'set', set_on: date });
    check(r.status === 201, 'route ' + name + ' set (' + r.status + ')');
  }

  await page.goto(base + '/gyms/' + gym);
  await Promise.all([page.waitForURL(/\/dashboard$/), page.click('#gym-dashboard')]);
  check((await page.textContent('#dashboard-title')).includes('Dash Gym'), 'the gym page links its dashboard');
  // Due walls first: the Cave's routes are years old.
  const first = await page.getAttribute('section.dash-wall', 'id');
  check(first === 'wall-' + cave, 'the due wall comes first (' + first + ')');

  await page.click('#wall-' + cave + ' details summary');
  await page.fill('#targets-' + cave + ' input[name="grades"]', 'V3: 3, V5: 1, V6: 1');
  await page.fill('#targets-' + cave + ' input[name="styles"]', 'heel hook: 0.4');
  await Promise.all([page.waitForNavigation(), page.click('#targets-' + cave + ' button[type="submit"]')]);
  const gaps = await page.textContent('#gaps-' + cave);
  check(gaps.includes('wall Cave: 2 × V3 missing, 1 × V6 missing'), 'the gap list in words (' + gaps.trim() + ')');
  check(await page.isVisible('#chart-' + cave), 'the target-vs-current chart is shown');
  const rows = await page.$$eval('#grades-' + cave + ' tbody tr', (trs) => trs.map((tr) => [...tr.cells].map((c) => c.textContent).join('|')));
  check(rows.includes('V3|1|3'), 'the chart table has V3: 1 on the wall, target 3 (' + rows.join(' | ') + ')');
  const d = await api('GET', gp + '/dashboard');
  check(d.status === 200 && d.data.walls[0].targets.V6 === 1, 'the API shows the targets');
  check(!(await page.isVisible('#targets-' + cave + ' .msg.bad')), 'no form error');
  // Targets per discipline: every bouldering wall together.
  await page.click('#discipline-bouldering details summary');
  await page.fill('#targets-bouldering input[name="grades"]', 'V1: 2, V3: 1');
  await Promise.all([page.waitForNavigation(), page.click('#targets-bouldering button[type="submit"]')]);
  const dgaps = await page.textContent('#gaps-bouldering');
  check(dgaps.includes('bouldering: 1 × V1 missing'), 'the discipline gaps in words (' + dgaps.trim() + ')');
  check(await page.isVisible('#chart-bouldering'), 'the discipline chart is shown');
  await shot('96-dashboard');

  await page.setViewportSize({ width: 390, height: 844 });
  await page.reload();
  const box = await page.$eval('#plan', (e) => { const r = e.getBoundingClientRect(); return [r.width, r.height]; });
  const docWidth = await page.evaluate(() => document.documentElement.scrollWidth);
  check(box[0] > 200 && box[0] <= 390, 'the plan fits the phone (' + box.join('x') + ')');
  check(docWidth <= 400, 'the page does not scroll sideways at 390 px (' + docWidth + ')');
  await page.$eval('#plan', (e) => e.scrollIntoView());
  await page.screenshot({ path: require('path').join(t.out, '96-dashboard-plan-phone.png') });
  await page.setViewportSize({ width: 1200, height: 900 });
  await Promise.all([page.waitForURL(/\/walls\/\d+$/), page.click('#plan-wall-' + slab)]);
  check(page.url().endsWith('/walls/' + slab), 'a wall on the plan links to its page');
};
