// The whole setting cycle by four people (issue 31, "Must show"): a head setter of two gyms picks
// the second in the header's switcher, sets it up (walls, a circuit, members), plans a setting
// day and accepts two candidates, sets them and strips them with the day sheet's buttons (the
// sheet keeps them), prints the wall's tag sheet from the wall page, edits and removes a wall and
// the circuit, and removes a member who is refused at once; a setter creates a route with the
// form (a grade outside the wall's scale is refused at the field, the text view carries the
// values) and edits a teammate's route with the same form; two tabs of the form on one route:
// the second save is refused showing the first's change; a climber member ticks and sees no
// setters' navigation; another gym's head setter and a logged-out visitor see nothing of the
// gym's plans. 91-cycle and 92-visibility check the single pieces in depth.
'use strict';
const { gymPeople, makeGym } = require('./gym_people');

module.exports = async (t) => {
  const { page, base, check, shot, api, context, pdfPages } = t;
  const n = Date.now() % 100000;
  const day = '2027-03-0' + (1 + (n % 8));
  // The four people's sessions, made once outside the page; `as(user)` switches the browser to
  // one of them.
  const { head, setter, climber, rival, as, submit, done } = await gymPeople(t, 'st', n);

  await as(head);
  const gymA = (await makeGym(api, 'Story A ' + n)).id;
  const gymB = (await makeGym(api, 'Story B ' + n)).id;

  // The header's switcher: the head setter's pages write to the gym chosen there.
  await page.goto(base + '/routes/new');
  check((await page.$$('#gym-switch option')).length >= 2, 'a member of two gyms has the gym switcher');
  await Promise.all([page.waitForNavigation(), page.selectOption('#gym-switch', String(gymB))]);
  check(page.url().includes('gym=' + gymB) && (await page.textContent('#form-gym')).includes('Story B'),
        'switched to the second gym: the new-route form writes there');

  // The second gym from its page: two walls, a circuit, three members.
  await page.goto(base + '/gyms/' + gymB);
  for (const name of ['North', 'South']) {
    await page.fill('#wall-name', name);
    await submit('#new-wall');
  }
  await page.fill('#circuit-colour', 'orange');
  await submit('#new-circuit');
  await api('POST', '/api/gyms/' + gymB + '/members', { username: setter, role: 'setter' });
  await page.fill('#member-name', climber);
  await page.selectOption('#member-role', 'climber');
  await submit('#new-member');
  const walls = (await api('GET', '/api/gyms/' + gymB + '/walls')).data.walls;
  const north = walls.find((w) => w.name === 'North').id, south = walls.find((w) => w.name === 'South').id;
  check(north && south && (await page.textContent('#member-list')).includes(climber), 'walls, circuit, members made');
  await api('PUT', '/api/gyms/' + gymB + '/walls/' + north, { scale: 'V' });
  const moves = ['R small crimp\nL small crimp\nR sidepull\nL gaston\nR crimp\nL jug finish\n',
                 'L sloper\nR small crimp\nL heel hook\nR pinch\nL crimp\nR top out\n',
                 'R jug\nL crimp\nR crimp\nL undercling\nR sloper\nL jug finish\n'];
  const onWall = [];
  for (const [i, m] of moves.entries()) {
    onWall.push((await api('POST', '/api/routes', { crdl: 'name: Story ' + n + '-' + i + '\ngrade: V' + (3 + i) +
      '\n---\n' + m, gym: gymB, wall: north, state: 'set' })).data.id);
  }

  // A setting day for both walls: accept the best candidate of each slot.
  await page.goto(base + '/gyms/' + gymB + '/setting-day?date=' + day + '&walls=' + north + ',' + south + '&k=2');
  const accepted = [];
  for (const slot of ['#slot-1', '#slot-2']) {
    await page.click(slot + ' .day-candidate form.day-accept button[type="submit"]');
    await page.waitForSelector(slot + ' .day-candidate .accepted-tag');
    accepted.push(Number((await page.getAttribute(slot + ' .day-candidate .accepted-tag', 'href'))
      .match(/\/routes\/(\d+)\//)[1]));
  }
  check(accepted.length === 2 && accepted[0] !== accepted[1], 'the head setter accepts two candidates');

  // The day's sheet: set both with its buttons, then strip both; the sheet keeps them.
  const sheet = base + '/gyms/' + gymB + '/setting-day/sheet?date=' + day;
  await page.goto(sheet);
  for (const id of accepted) await submit('#sheet-set-' + id);
  let states = await Promise.all(accepted.map(async (id) => (await api('GET', '/api/routes/' + id)).data));
  check(states.every((r) => r.state === 'set' && r.set_on === day),
        'the sheet\'s buttons set the day\'s routes on the wall, on the day planned');
  await shot('93-story-sheet');
  // The wall page links the wall's tag sheet.
  await page.goto(base + '/walls/' + north);
  const tagsHref = await page.getAttribute('#wall-tags', 'href');
  const tags = await page.request.get(base + tagsHref);
  check(tags.status() === 200 && pdfPages(await tags.body()) >= 1, 'the wall page prints the wall\'s tags');
  await page.goto(sheet);
  for (const id of accepted) await submit('#sheet-stripped-' + id);
  states = await Promise.all(accepted.map(async (id) => (await api('GET', '/api/routes/' + id)).data));
  check(states.every((r) => r.state === 'stripped'), 'the sheet strips two routes');
  check((await page.$$('table.day-sheet tbody tr')).length >= 2 &&
        (await page.textContent('table.day-sheet')).includes('stripped'),
        'the day\'s sheet keeps its routes whatever their state');

  // Edit and remove a wall (South: only stripped routes left) and the circuit.
  await page.goto(base + '/gyms/' + gymB);
  await page.click('#wall-edit-' + south + ' summary');
  await page.fill('#wall-form-' + south + ' input[name="name"]', 'South Face');
  await submit('#wall-form-' + south);
  await page.click('#wall-edit-' + south + ' summary');
  await submit('#wall-remove-' + south);
  const circuit = (await api('GET', '/api/gyms/' + gymB + '/circuits')).data.circuits[0];
  await page.click('#circuit-edit-' + circuit.id + ' summary');
  await submit('#circuit-remove-' + circuit.id);
  const history = await page.textContent('#gym-history');
  check(history.includes('South Face removed') && !(await page.textContent('#wall-list')).includes('South'),
        'the head setter edits and removes a wall and the circuit (in the gym\'s history)');

  // The setter: a new route with the form.
  await as(setter);
  await page.goto(base + '/routes/new');
  await page.fill('#f-name', 'Form Route ' + n);
  await page.selectOption('#f-wall', String(north));
  await page.fill('#f-grade', '6B+');
  await page.check('.f-setter[value="' + setter + '"]');
  await page.fill('#f-setters-other', 'Guest Setter');
  await page.selectOption('#f-state', 'planned');
  await page.fill('#f-date', day);
  await page.fill('#f-moves', 'R small crimp\nL jug finish');
  await page.waitForFunction(() => document.querySelectorAll('#feedback li.fb-move').length === 2);
  check((await page.textContent('#feedback')).includes('crimp'), 'each move shows the grammar\'s reading');
  await page.click('#save');
  await page.waitForFunction(() => document.querySelector('.field-msg[data-for="grade"]').textContent !== '');
  const gradeMsg = await page.textContent('.field-msg[data-for="grade"]');
  check(gradeMsg.includes('"V"') && (await page.inputValue('#f-grade')) === '6B+',
        'a grade outside the wall\'s scale is refused at the field, naming the scale, the typing kept');
  await shot('93-story-form-refused');
  await page.fill('#f-grade', 'V3');
  await page.click('#view-text');
  const text = await page.inputValue('#crdl');
  check(text.includes('grade: V3') && text.includes('setter: Guest Setter') && text.includes('R small crimp'),
        'the text view carries the form\'s values');
  await page.fill('#crdl', text.replace('Form Route', 'Formed Route'));
  await page.click('#view-form');
  check((await page.inputValue('#f-name')) === 'Formed Route ' + n, 'and the form the text\'s');
  await Promise.all([page.waitForURL(/\/routes\/\d+$/), page.click('#save')]);
  const made = (await api('GET', '/api/routes/' + page.url().match(/(\d+)$/)[1])).data;
  check(made.gym === gymB && made.wall_id === north && made.state === 'planned' && made.set_on === day &&
        made.setters.join() === setter + ',Guest Setter', 'the setter\'s route is saved as the form said');

  // A teammate's route: the same form; two tabs, the second save refused with the first's change.
  const mates = onWall[0];
  const editUrl = base + '/routes/' + mates + '/edit';
  await page.goto(base + '/routes/' + mates);
  await Promise.all([page.waitForURL(editUrl), page.click('#edit')]);
  const tab2 = await context.newPage();
  await tab2.goto(editUrl);
  await page.fill('#f-grade', 'V4');
  await Promise.all([page.waitForURL(/\/routes\/\d+$/), page.click('#save')]);
  check((await api('GET', '/api/routes/' + mates)).data.grade === 'V4', 'a setter edits a teammate\'s route');
  await tab2.fill('#f-name', 'Other Tab');
  await tab2.click('#save');
  await tab2.waitForSelector('#conflict-current');
  check((await tab2.textContent('#conflict-current')).includes('grade: V4') &&
        (await tab2.inputValue('#f-name')) === 'Other Tab',
        'the second tab is refused, shown the first\'s change, its own typing kept');
  await tab2.screenshot({ path: require('path').join(t.out, '93-story-conflict.png'), fullPage: true });
  await tab2.close();

  // The climber member ticks a route on the wall and sees no setters' navigation.
  await as(climber);
  await page.goto(base + '/r/' + onWall[1]);
  await page.click('label.outcome:has(#outcome-send)');
  await page.click('#tick-submit');
  await page.waitForFunction(() => document.getElementById('tick-msg').textContent !== '');
  check((await page.textContent('#tick-msg')).startsWith('Ticked'), 'the climber ticks');
  await page.goto(base + '/');
  check(!(await page.$('#nav-new')) && !(await page.$('#nav-import')), 'a climber sees no setters\' navigation');

  // The head setter removes the climber: refused at once.
  await as(head);
  await page.goto(base + '/gyms/' + gymB);
  await submit('#member-remove-' + climber);
  await as(climber);
  check((await page.goto(base + '/gyms/' + gymB)).status() === 404, 'the removed climber is refused at once');

  // Another gym's head setter and a logged-out visitor: nothing of the planned route.
  const planned = made.id;
  const outsiders = async () => {
    const seen = [];
    for (const p of ['/api/routes/' + planned, '/api/routes/' + planned + '/history', '/tags.pdf?ids=' + planned,
                     '/api/gyms/' + gymB + '/tags.pdf']) {
      const r = await api('GET', p);
      if (r.status !== 404 && r.status !== 401) seen.push(p + ' ' + r.status);
    }
    const csv = await api('GET', '/api/export/routes.csv');
    if (String(csv.data).includes('Formed Route')) seen.push('export');
    const sheetRes = await page.goto(sheet);
    if ((await page.content()).includes('Formed Route') || sheetRes.status() === 200 &&
        !page.url().includes('/login')) seen.push('sheet');
    return seen;
  };
  await as(rival);
  await api('POST', '/api/gyms', { name: 'Rival ' + n });
  let seen = await outsiders();
  check(seen.length === 0, 'another gym\'s head setter sees nothing of the gym (' + seen.join(', ') + ')');
  await as(null);
  seen = await outsiders();
  check(seen.length === 0 && page.url().includes('/login?next='),
        'a logged-out visitor sees nothing and is asked to log in (' + seen.join(', ') + ')');
  done();
  void gymA;
};
