// Issue 31, cycle part 5, as a head setter of two gyms meets it: a page of a gym (its wall, a
// route of it, its setting-day sheet) shows that gym in the header's switcher and writes to it
// whatever the switcher was on elsewhere; switching there goes to the other gym's page (the
// sheet keeps its date); the wall's "Strip this wall" changes exactly the routes the page showed
// and says how many it left (a route set meanwhile by a teammate stays on the wall).
'use strict';
const { gymPeople, makeGym } = require('./gym_people');

module.exports = async (t) => {
  const { page, base, check, shot, api } = t;
  const n = Date.now() % 100000;
  const day = '2027-05-1' + (n % 9);
  const { head, setter, as, done } = await gymPeople(t, 'c5', n);

  await as(head);
  const a = await makeGym(api, 'C5 North ' + n, { members: { [setter]: 'setter' }, walls: ['North Wall'] });
  const b = await makeGym(api, 'C5 South ' + n, { members: { [setter]: 'setter' }, walls: ['South Cave'] });
  const wallB = b.walls[0];
  const route = (gym, wall, name, extra) => api('POST', '/api/routes', {
    crdl: 'name: ' + name + '\n---\nR jug\nL crimp\n', gym, wall, ...extra }).then((r) => r.data.id);
  const plannedB = await route(b.id, wallB, 'C5 Planned ' + n, { state: 'planned', set_on: day });
  const setB = await route(b.id, wallB, 'C5 Set ' + n, { state: 'set' });

  // The switcher on the first gym (its page), then the second gym's wall: the header says the
  // second, and "New route on this wall" is the second gym's form with the wall chosen.
  await page.goto(base + '/gyms/' + a.id);
  check((await page.inputValue('#gym-switch')) === String(a.id), 'the first gym\'s page shows it in the switcher');
  await page.goto(base + '/walls/' + wallB);
  check((await page.inputValue('#gym-switch')) === String(b.id) &&
        (await page.getAttribute('meta[name="sb-gym"]', 'content')) === String(b.id),
        'another gym\'s wall page shows that gym as the one written to');
  await shot('96b-wall-of-second-gym');
  await Promise.all([page.waitForNavigation(), page.click('#plan-here')]);
  check((await page.inputValue('#f-wall')) === String(wallB) && (await page.textContent('main')).includes('C5 South'),
        '"New route on this wall" is the wall\'s gym\'s form');
  for (const p of ['/routes/' + plannedB, '/gyms/' + b.id + '/dashboard',
                   '/gyms/' + b.id + '/setting-day/sheet?date=' + day]) {
    await page.goto(base + p);
    check((await page.inputValue('#gym-switch')) === String(b.id), p.split('?')[0] + ' shows the second gym in the header');
  }
  // Switching on the sheet goes to the first gym's sheet of that day; on a wall, to the gym page.
  await Promise.all([page.waitForNavigation(), page.selectOption('#gym-switch', String(a.id))]);
  check(page.url() === base + '/gyms/' + a.id + '/setting-day/sheet?date=' + day,
        'switching on a setting-day sheet goes to the other gym\'s sheet of that day');
  await page.goto(base + '/walls/' + wallB);
  await Promise.all([page.waitForNavigation(), page.selectOption('#gym-switch', String(a.id))]);
  check(page.url() === base + '/gyms/' + a.id, 'switching on a wall page goes to the other gym\'s page');
  // The next page outside a gym stays with the gym chosen last.
  await page.goto(base + '/routes/new');
  check((await page.textContent('main')).includes('C5 North'), 'the new-route form then is the chosen gym\'s');

  // "Strip this wall" from a page read before another route was set (another tab): the routes
  // shown are stripped, the new one stays on the wall, and the page says it left one.
  await page.goto(base + '/walls/' + wallB);
  const late = await route(b.id, wallB, 'C5 Late ' + n, { state: 'set' });
  await Promise.all([page.waitForNavigation(), page.click('#wall-strip button[type="submit"]')]);
  await page.waitForSelector('#bulk-note');
  const note = await page.textContent('#bulk-note');
  const [s1, s2] = await Promise.all([setB, late].map(async (id) => (await api('GET', '/api/routes/' + id)).data.state));
  check(s1 === 'stripped' && s2 === 'set' && note.includes('did not show') && note.includes('1'),
        'the wall strips only the routes its page showed and says it left one (' + note + ')');
  await shot('96b-strip-note');
  done();
};
