// Issue 31, cycle part 6, by hand as a head setter of two gyms, a setter and a climber: the head
// setter renames the gym, moves a wall on the floor plan and clears its reset weeks and plan from
// the form, removes a wall (refused while routes are on it) and a circuit; a setter made a
// climber loses "Edit" at once and a removed member gets nothing of the gym on the next request;
// a route planned for a day is set from the day's sheet and stripped from its page; a CRDL import names its gym and links its routes; the CSV export holds a
// gym's routes for its setters only; a logged-out visitor of a gym page logs in and is back.
'use strict';
const { gymPeople, makeGym } = require('./gym_people');

module.exports = async (t) => {
  const { page, base, check, shot, api } = t;
  const n = Date.now() % 100000;
  const day = new Date(Date.now() + 20 * 864e5).toISOString().slice(0, 10);
  const { head, setter, climber, as, submit, done } = await gymPeople(t, 'c6', n);

  await as(head);
  await makeGym(api, 'C6 Home ' + n, { walls: ['Home Wall'] });
  const g = await makeGym(api, 'C6 Away ' + n, {
    members: { [setter]: 'setter', [climber]: 'climber' },
    walls: ['North', 'Roof'], circuits: [{ colour: 'red' }, { colour: 'blue' }] });
  const [north, roof] = g.walls;
  const route = (name, extra) => api('POST', '/api/routes', {
    crdl: 'name: ' + name + '\n---\nR jug\nL crimp\n', gym: g.id, wall: north, ...extra }).then((r) => r.data.id);
  const onWall = await route('C6 On ' + n, { state: 'set', set_on: '2026-01-05' });
  const planned = await route('C6 Plan ' + n, { state: 'planned', set_on: day });

  // A field the API does not know is refused, naming it (it was dropped without a word).
  const extra = await api('POST', '/api/routes', { crdl: 'name: X\n---\nR jug\n', gym: g.id, grade: 'V99' });
  check(extra.status === 400 && /^grade: unknown field \(accepted: crdl/.test(extra.data.error),
        'a route write with an unknown field is refused naming it (' + extra.data.error + ')');

  // The gym page: rename, the wall moved on the floor plan, then its reset weeks and plan cleared.
  await page.goto(base + '/gyms/' + g.id);
  await page.fill('#gym-rename-name', 'C6 Away Renamed ' + n);
  await submit('#gym-rename');
  check((await page.textContent('#gym-title')).includes('Renamed'), 'the gym is renamed from its page');
  check(await page.isVisible('#new-wall-title') && await page.isVisible('#new-circuit-title'),
        'the forms that add a wall and a circuit have headings of their own');
  const form = '#wall-form-' + north;
  await page.click('#wall-edit-' + north + ' summary');
  await page.fill(form + ' input[name="reset_weeks"]', '6');
  for (const [k, v] of [['x', '2'], ['y', '1'], ['w', '4'], ['h', '3']]) await page.fill(form + ' input[name="plan.' + k + '"]', v);
  await submit(form);
  let w = (await api('GET', '/api/gyms/' + g.id + '/walls')).data.walls.find((x) => x.id === north);
  check(w.reset_weeks === 6 && w.plan && w.plan.x === 2 && w.plan.h === 3, 'the wall is put on the floor plan from the form');
  await shot('96c-gym-page');
  await page.click('#wall-edit-' + north + ' summary');
  await page.fill(form + ' input[name="reset_weeks"]', '');
  for (const k of ['x', 'y', 'w', 'h']) await page.fill(form + ' input[name="plan.' + k + '"]', '');
  await submit(form);
  w = (await api('GET', '/api/gyms/' + g.id + '/walls')).data.walls.find((x) => x.id === north);
  check(w.reset_weeks === null && w.plan === null, 'emptying reset weeks and the floor plan in the form clears them');

  // Remove a wall with routes on it: refused with the count; the empty one goes; a circuit goes.
  await page.click('#wall-edit-' + north + ' summary');
  await page.click('#wall-remove-' + north + ' button[type="submit"]');
  await page.waitForFunction((s) => document.querySelector(s).textContent.length > 0, '#wall-remove-' + north + ' .msg');
  const refusal = await page.textContent('#wall-remove-' + north + ' .msg');
  check(/2 routes/.test(refusal), 'removing a wall with routes on it is refused with their count (' + refusal + ')');
  await page.click('#wall-edit-' + roof + ' summary');
  await submit('#wall-remove-' + roof);
  await page.click('#circuit-edit-' + g.circuits[1] + ' summary');
  await submit('#circuit-remove-' + g.circuits[1]);
  const gym = (await api('GET', '/api/gyms/' + g.id)).data;
  check(gym.walls.length === 1 && gym.circuits.length === 1, 'the empty wall and a circuit are removed');

  // The setting day's sheet: the planned route set, then stripped, with its buttons.
  await page.goto(base + '/gyms/' + g.id + '/setting-day/sheet?date=' + day);
  await submit('#sheet-set-' + planned);
  check((await api('GET', '/api/routes/' + planned)).data.state === 'set', 'the sheet sets the planned route');
  // Its page's buttons are inside their block (a <p> around forms lost them), and strip it.
  await page.goto(base + '/routes/' + planned);
  check((await page.$$('#route-state-buttons form')).length === 1, 'the route page\'s state buttons are in their block');
  await submit('#route-strip');
  check((await api('GET', '/api/routes/' + planned)).data.state === 'stripped', 'the route page strips it');
  await page.goto(base + '/gyms/' + g.id + '/setting-day/sheet?date=' + day);
  check((await page.textContent('main')).includes('C6 Plan'), 'the sheet keeps the stripped route');
  await page.goto(base + '/walls/' + north);
  check((await page.$$('.wall-actions form')).length === 2, 'the wall\'s buttons are in their block');

  // The setter made a climber: no "Edit" on their next page, the API refuses.
  await page.goto(base + '/gyms/' + g.id);
  await page.selectOption('#member-role-' + setter + ' select', 'climber');
  await submit('#member-role-' + setter);
  await as(setter);
  await page.goto(base + '/routes/' + onWall);
  check(!(await page.$('a[href="/routes/' + onWall + '/edit"]')), 'a setter made a climber sees no Edit');
  const put = await api('PUT', '/api/routes/' + onWall, { setters: [setter] });
  check(put.status === 403, 'and may not change the route (' + put.status + ')');
  // Removed: nothing of the gym on the next request.
  await as(head);
  await page.goto(base + '/gyms/' + g.id);
  await submit('#member-remove-' + climber);
  await as(climber);
  const gone = await page.goto(base + '/gyms/' + g.id);
  check(gone.status() === 404, 'a removed member gets nothing of the gym (' + gone.status() + ')');

  // The CSV export: the gym's route for its head setter, not for a removed member or a visitor.
  const csv = async () => page.evaluate(async () => (await fetch('/api/export/routes.csv')).text());
  check(!(await csv()).includes('C6 On ' + n), 'a removed member\'s export has none of the gym\'s routes');
  await as(head);
  check((await csv()).includes('C6 On ' + n), 'the head setter\'s export has them');

  // A CRDL import names the gym its routes went into and links them (it said only "1 imported").
  await page.goto(base + '/gyms/' + g.id);
  await page.evaluate((id) => { document.cookie = 'sb_gym=' + id + '; path=/'; }, g.id);
  await page.goto(base + '/import');
  await page.setInputFiles('#crdl-files', { name: 'c6.crdl', mimeType: 'text/plain',
                                            buffer: Buffer.from('name: C6 Imported ' + n + '\n---\nR jug\n') });
  await page.click('#import-crdl');
  await page.waitForSelector('#crdl-imported:not([hidden]) a');
  const msg = await page.textContent('#crdl-msg');
  check(msg.includes('1') && msg.includes('C6 Away Renamed ' + n), 'the import says the gym it went into (' + msg + ')');
  check((await page.getAttribute('#crdl-gym', 'href')) === '/gyms/' + g.id, 'and links the gym');
  const link = page.locator('#crdl-imported li a', { hasText: 'C6 Imported ' + n });
  check(/^\/routes\/\d+$/.test(await link.getAttribute('href') || ''), 'and links the imported route');
  await shot('96c-crdl-imported');

  // A logged-out visitor of a gym page: the log-in page, then back.
  await as(null);
  await page.goto(base + '/gyms/' + g.id);
  check(page.url().includes('/login?next='), 'a logged-out visitor of a gym page gets the log-in page');
  await page.fill('#username', head);
  await page.fill('#password', 'correct horse battery');
  await Promise.all([page.waitForURL(base + '/gyms/' + g.id), page.click('#submit')]);
  check((await page.textContent('#gym-title')).includes('Renamed'), 'and is back on it after logging in');
  await shot('96c-back-on-gym');
  done();
};
