// Issue 31's last gaps, as the gym's people would meet them: a setter picks a circuit in the route
// form (the route keeps it, its page says so, the edit form shows it); the head setter removes the
// circuit (the route keeps its colour, its history says so); two tabs of the dashboard save the
// discipline targets (the second is refused showing the first's); the setting day's sheet sets
// every planned route of the day with one button, refusing a sheet gone stale; a climber member,
// another gym's head setter and a logged-out visitor see nothing of the drafts and plans (route
// page, JSON, history, search, CSV, /tags.pdf?ids=, the day's sheet, the wall page) while the
// routes on the wall stay at /r/{id}. 93-cycle-story walks the rest of the cycle.
'use strict';
const { gymPeople, makeGym } = require('./gym_people');

module.exports = async (t) => {
  const { page, base, check, shot, api, context } = t;
  const n = Date.now() % 100000;
  const day = '2027-04-1' + (n % 9);
  const { head, setter, climber, rival, as, submit, done } = await gymPeople(t, 'gp', n);

  await as(head);
  const made = await makeGym(api, 'Gaps ' + n, {
    members: { [setter]: 'setter', [climber]: 'climber' },
    walls: ['Slab'],
    circuits: [{ colour: 'Red', grade_from: 'V2', grade_to: 'V4' }, { colour: 'Blue' }],
  });
  const gym = made.id, wall = made.walls[0];
  const [red, blue] = made.circuits;

  // The setter: a new route with a circuit chosen in the form.
  await as(setter);
  await page.goto(base + '/routes/new');
  await page.fill('#f-name', 'Gap Red ' + n);
  await page.selectOption('#f-wall', String(wall));
  await page.selectOption('#f-circuit', String(red));
  check((await page.inputValue('#f-colour')) === 'Red', 'choosing a circuit fills the colour');
  await page.fill('#f-grade', 'V3');
  await page.selectOption('#f-state', 'planned');
  await page.fill('#f-date', day);
  await page.fill('#f-moves', 'R small crimp\nL jug finish');
  await Promise.all([page.waitForURL(/\/routes\/\d+$/), page.click('#save')]);
  const first = Number(page.url().match(/(\d+)$/)[1]);
  let got = (await api('GET', '/api/routes/' + first)).data;
  check(got.circuit === red && got.colour === 'Red', 'the route keeps the circuit chosen (its id in the JSON)');
  check((await page.textContent('#route-circuit')).includes('Red'), 'the route page shows its circuit');
  await page.goto(base + '/routes/' + first + '/edit');
  check((await page.inputValue('#f-circuit')) === String(red), 'the edit form shows the route\'s circuit');
  await page.selectOption('#f-circuit', String(blue));
  await Promise.all([page.waitForURL(/\/routes\/\d+$/), page.click('#save')]);
  got = (await api('GET', '/api/routes/' + first)).data;
  check(got.circuit === blue && got.colour === 'Blue' && got.crdl.includes('colour: Blue'),
        'the form moves it to another circuit (colour and text follow)');
  const second = (await api('POST', '/api/routes', { crdl: 'name: Gap Two ' + n + '\n---\nR jug\nL crimp\n', gym,
    wall, state: 'planned', set_on: day })).data.id;
  const draft = (await api('POST', '/api/routes', { crdl: 'name: Gap Draft ' + n + '\n---\nR jug\nL pinch-' + n + '\n',
    gym, wall })).data.id;
  const onWall = (await api('POST', '/api/routes', { crdl: 'name: Gap Wall ' + n + '\n---\nR jug\nL sloper\n', gym,
    wall, state: 'set' })).data.id;

  // The head setter: the dashboard's discipline targets in two tabs.
  await as(head);
  const dash = base + '/gyms/' + gym + '/dashboard';
  await page.goto(dash);
  const tab2 = await context.newPage();
  await tab2.goto(dash);
  await page.click('#discipline-bouldering details summary');
  await page.fill('#targets-bouldering input[name="grades"]', 'V3: 2');
  await submit('#targets-bouldering');
  await tab2.click('#discipline-bouldering details summary');
  await tab2.fill('#targets-bouldering input[name="grades"]', 'V5: 1');
  await tab2.click('#targets-bouldering button[type="submit"]');
  await tab2.waitForFunction(() => document.querySelector('#targets-bouldering .msg').textContent !== '');
  const said = await tab2.textContent('#targets-bouldering .msg');
  check(said.includes('V3: 2') && (await tab2.inputValue('#targets-bouldering input[name="grades"]')) === 'V5: 1',
        'a stale targets form is refused showing the targets saved meanwhile, the typing kept');
  await tab2.screenshot({ path: require('path').join(t.out, '95-gaps-targets-conflict.png'), fullPage: true });
  await submit('#targets-bouldering', tab2);
  const d = (await api('GET', '/api/gyms/' + gym + '/dashboard')).data.disciplines.find((x) => x.discipline === 'bouldering');
  check(JSON.stringify(d.targets) === '{"V5":1}', 'saving again applies the second tab\'s targets');
  await tab2.close();

  // The day's sheet: one button sets every planned route of the day; a stale sheet is refused.
  const sheet = base + '/gyms/' + gym + '/setting-day/sheet?date=' + day;
  await page.goto(sheet);
  check(await page.isVisible('#sheet-set-day'), 'the sheet offers "Set all planned routes of this day"');
  await api('PUT', '/api/routes/' + second, { setters: [setter] });  // someone else, meanwhile
  await page.click('#sheet-set-day button[type="submit"]');
  await page.waitForFunction(() => document.querySelector('#sheet-set-day .msg').textContent !== '');
  check((await page.textContent('#sheet-set-day .msg')).includes('Gap Two') &&
        (await api('GET', '/api/routes/' + first)).data.state === 'planned',
        'a sheet gone stale sets nothing and says what the day holds now');
  await shot('95-gaps-sheet-stale');
  await page.goto(sheet);
  await submit('#sheet-set-day');
  const both = await Promise.all([first, second].map(async (id) => (await api('GET', '/api/routes/' + id)).data));
  const hist = (await api('GET', '/api/routes/' + second + '/history')).data.history.map((h) => h.what).join('; ');
  check(both.every((r) => r.state === 'set' && r.set_on === day) && hist.includes('planned -> set'),
        'the day\'s planned routes are set on their day, each in its history');
  check(!(await page.$('#sheet-set-day')) && (await page.textContent('table.day-sheet')).includes('on the wall'),
        'the sheet shows them on the wall, with nothing left to set');
  await shot('95-gaps-sheet-set');

  // Two tabs of the route form: the second save is refused; the fields its user did not
  // change take the first's values, so saving again keeps both edits (nothing lost).
  const editUrl = base + '/routes/' + second + '/edit';
  await page.goto(editUrl);
  const tab3 = await context.newPage();
  await tab3.goto(editUrl);
  await page.fill('#f-grade', 'V5');
  await Promise.all([page.waitForURL(/\/routes\/\d+$/), page.click('#save')]);
  await tab3.fill('#f-name', 'Gap Two Renamed ' + n);
  await tab3.click('#save');
  await tab3.waitForSelector('#conflict-merge');
  check((await tab3.textContent('#conflict-merge')).includes('now in the form: grade') &&
        (await tab3.inputValue('#f-grade')) === 'V5' && (await tab3.inputValue('#f-name')) === 'Gap Two Renamed ' + n,
        'a stale route form takes the other save\'s change and keeps its own');
  await Promise.all([tab3.waitForURL(/\/routes\/\d+$/), tab3.click('#save')]);
  await tab3.close();
  got = (await api('GET', '/api/routes/' + second)).data;
  check(got.grade === 'V5' && got.name === 'Gap Two Renamed ' + n, 'saving again loses neither edit');

  // The wall page's "Strip this wall" carries the routes it shows: stale, it strips nothing.
  await page.goto(base + '/walls/' + wall);
  await api('PUT', '/api/routes/' + first, { setters: [setter] });  // someone else, meanwhile
  await page.click('#wall-strip button[type="submit"]');
  await page.waitForFunction(() => document.querySelector('#wall-strip .msg').textContent !== '');
  check((await page.textContent('#wall-strip .msg')).includes('Gap Red') &&
        (await api('GET', '/api/routes/' + first)).data.state === 'set',
        'a stale wall page strips nothing and says what the wall holds now');

  // Removing the circuit: the route keeps its colour, its history and the gym's say so.
  await page.goto(base + '/gyms/' + gym);
  await page.click('#circuit-edit-' + blue + ' summary');
  await submit('#circuit-remove-' + blue);
  got = (await api('GET', '/api/routes/' + first)).data;
  const rh = (await api('GET', '/api/routes/' + first + '/history')).data.history.map((h) => h.what).join('; ');
  check(got.circuit === null && got.colour === 'Blue' && rh.includes('circuit Blue removed'),
        'a removed circuit leaves its routes their colour, said in their history');
  await page.goto(base + '/routes/' + first);
  check(!(await page.$('#route-circuit')) && (await page.textContent('#route-history')).includes('Blue'),
        'the route page no longer names a circuit');
  const planned = (await api('POST', '/api/routes', { crdl: 'name: Gap Plan ' + n + '\n---\nR jug\nL crimp-' + n + '\n',
    gym, wall, state: 'planned', set_on: day })).data.id;

  // Who is not a setter of the gym sees nothing of its draft and plan; the routes on the wall
  // are at /r/{id} for anyone and in the gym's pages for its members.
  async function hidden(who, member) {
    const seen = [];
    for (const id of [draft, planned]) {
      for (const p of ['/api/routes/' + id, '/api/routes/' + id + '/history', '/tags.pdf?ids=' + id,
                       '/routes/' + id + '/tag']) {
        const r = await api('GET', p);
        if (r.status !== 404 && r.status !== 401) seen.push(p + ' ' + r.status);
      }
      const resp = await api('GET', '/routes/' + id);
      if (resp.status === 200 && String(resp.data).includes('Gap ')) seen.push('/routes/' + id);
    }
    const search = await api('GET', '/api/routes?limit=500&q=' + encodeURIComponent('Gap'));
    const listed = JSON.stringify(search.data);
    if (listed.includes('Gap Draft') || listed.includes('Gap Plan')) seen.push('search');
    if (String((await api('GET', '/?q=Gap')).data).match(/Gap (Draft|Plan)/)) seen.push('list page');
    for (const f of ['routes', 'moves']) {
      const csv = String((await api('GET', '/api/export/' + f + '.csv')).data);
      if (csv.includes('Gap Draft') || csv.includes('Gap Plan') || csv.includes('crimp-' + n)) seen.push(f + '.csv');
    }
    // The gym's own pages (a member's; 93 and 92 check that outsiders get none).
    for (const p of member ? [sheet, base + '/walls/' + wall] : []) {
      await page.goto(p);
      if ((await page.content()).match(/Gap (Draft|Plan)/)) seen.push(p.replace(base, ''));
    }
    const qr = await api('GET', '/r/' + onWall);
    if (qr.status !== 200) seen.push('missing /r/' + onWall + ' ' + qr.status);
    console.log('     ' + who + ': ' + (seen.join(', ') || 'nothing'));
    return seen;
  }
  await as(climber);
  let seen = await hidden('climber', true);
  check(seen.length === 0, 'a climber member sees no draft or plan (' + seen.join(', ') + ')');
  const climbed = await api('GET', '/api/routes/' + onWall);
  check(climbed.status === 200, 'and sees the route on the wall');
  await shot('95-gaps-climber-wall');
  await as(rival);
  await api('POST', '/api/gyms', { name: 'Rival Gaps ' + n });
  seen = await hidden('rival');
  check(seen.length === 0, 'another gym\'s head setter sees no draft or plan (' + seen.join(', ') + ')');
  await as(null);
  seen = await hidden('visitor');
  check(seen.length === 0, 'a logged-out visitor sees no draft or plan (' + seen.join(', ') + ')');
  done();
};
