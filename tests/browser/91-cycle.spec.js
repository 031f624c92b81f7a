// The cycle's records and writes (issue 31): a head setter of two gyms sets up the second one
// from its page (a wall, a circuit, two members), edits and removes a wall and the circuit, and
// removes a member whose open session is refused at once; two tabs edit one route and the second
// save is refused with the first's change shown, then applied again; a route is set and stripped
// with the route page's buttons (its typed set date kept), and the wall page sets all of today's
// planned routes and strips the wall.
'use strict';

module.exports = async (t) => {
  const { page, base, check, shot, api, context } = t;
  const n = Date.now() % 100000;
  const head = 'cyhead' + n, setter = 'cyset' + n, climber = 'cyclimb' + n;
  const password = 'correct horse battery';

  async function signUp(user) {
    await page.context().clearCookies();
    await page.goto(base + '/signup');
    await page.fill('#username', user);
    await page.fill('#password', password);
    await Promise.all([page.waitForURL(base + '/'), page.click('#submit')]);
  }
  // Submits a form of `p` and waits for the reload.
  async function submit(formId, p = page) {
    await Promise.all([p.waitForNavigation(), p.click('#' + formId + ' button[type="submit"]')]);
  }
  // A session of `user` outside the browser (a climber's open tab elsewhere).
  async function session(user) {
    const r = await fetch(base + '/api/sessions', {
      method: 'POST', headers: { 'Content-Type': 'application/json' },
      body: JSON.stringify({ username: user, password }),
    });
    const cookie = (r.headers.get('set-cookie') || '').split(';')[0];
    return async (path) => (await fetch(base + path, { headers: { Cookie: cookie } })).status;
  }
  page.on('dialog', (d) => d.accept());

  await signUp(setter);
  await signUp(climber);
  await signUp(head);
  const first = (await api('POST', '/api/gyms', { name: 'First ' + n })).data.id;
  const second = (await api('POST', '/api/gyms', { name: 'Second ' + n })).data.id;
  const gymUrl = base + '/gyms/' + second;
  const refused = await api('POST', '/api/routes', { crdl: 'name: X\n---\nR jug\n' });
  check(refused.status === 400 && /^gym:/.test(refused.data.error),
        'a head setter of two gyms must name the gym of a new route (' + refused.status + ')');

  // The second gym, set up from its page.
  await page.goto(gymUrl);
  for (const [name, angle] of [['Cave', '30'], ['Slab', '-5']]) {
    await page.fill('#wall-name', name);
    await page.fill('#wall-angle', angle);
    await submit('new-wall');
  }
  await page.fill('#circuit-colour', 'green');
  await submit('new-circuit');
  for (const [user, role] of [[setter, 'setter'], [climber, 'climber']]) {
    await page.fill('#member-name', user);
    await page.selectOption('#member-role', role);
    await submit('new-member');
  }
  check((await page.textContent('#member-list')).includes(climber), 'two members added');
  let walls = (await api('GET', '/api/gyms/' + second + '/walls')).data.walls;
  const cave = walls.find((w) => w.name === 'Cave');
  const slab = walls.find((w) => w.name === 'Slab');

  // Edit the Slab (name, angle, floor plan), then remove it; edit and remove the circuit.
  await page.click('#wall-edit-' + slab.id + ' summary');
  const wf = '#wall-form-' + slab.id;
  await page.fill(wf + ' input[name="name"]', 'Slab Two');
  await page.fill(wf + ' input[name="angle"]', '-12');
  for (const [k, v] of [['x', '1'], ['y', '2'], ['w', '3'], ['h', '2']]) {
    await page.fill(wf + ' input[name="plan.' + k + '"]', v);
  }
  await submit('wall-form-' + slab.id);
  walls = (await api('GET', '/api/gyms/' + second + '/walls')).data.walls;
  const edited = walls.find((w) => w.id === slab.id);
  check(edited && edited.name === 'Slab Two' && edited.angle === -12 && edited.plan && edited.plan.w === 3,
        'the head setter edits a wall from the gym page (name, angle, floor plan)');
  await page.click('#wall-edit-' + slab.id + ' summary');
  await submit('wall-remove-' + slab.id);
  check(!(await page.textContent('#wall-list')).includes('Slab Two'), 'the head setter removes a wall');
  const circuit = (await api('GET', '/api/gyms/' + second + '/circuits')).data.circuits[0];
  await page.click('#circuit-edit-' + circuit.id + ' summary');
  await page.fill('#circuit-form-' + circuit.id + ' input[name="colour"]', 'lime');
  await page.fill('#circuit-form-' + circuit.id + ' input[name="grade_from"]', 'V0');
  await submit('circuit-form-' + circuit.id);
  check((await page.textContent('#circuit-list')).includes('lime'), 'the head setter edits a circuit');
  await page.click('#circuit-edit-' + circuit.id + ' summary');
  await submit('circuit-remove-' + circuit.id);
  check((await page.$('#circuit-list')) === null, 'the head setter removes a circuit');

  // The climber's open session reads the gym; removed, the very next request is refused.
  const climberGet = await session(climber);
  check(await climberGet('/api/gyms/' + second) === 200, 'the climber reads the gym');
  await submit('member-remove-' + climber);
  check(!(await page.textContent('#member-list')).includes(climber), 'the head setter removes the climber');
  check(await climberGet('/api/gyms/' + second) === 404 && await climberGet('/gyms/' + second) === 404,
        'the removed climber is refused at once (API and page)');
  const history = await page.textContent('#gym-history');
  check(history.includes('wall Slab edited (now Slab Two)') && history.includes('removed'),
        'the gym page shows the gym history');
  await shot('91-cycle-gym');

  // Two tabs edit one route: the second save is refused, showing the first's change.
  const crdl = 'name: Two Tabs\ngrade: V3\nset: 2026-09-15\n---\nR crimp\nL jug\n';
  const made = await api('POST', '/api/routes', { crdl, gym: second, public: false, wall: cave.id,
                                                  state: 'planned' });
  const routeUrl = base + '/routes/' + made.data.id;
  const tab2 = await context.newPage();
  await page.goto(routeUrl);
  await tab2.goto(routeUrl);
  await page.fill('#route-setters-input', setter);
  await submit('route-gym-form');
  await tab2.fill('#route-setters-input', 'Guest');
  await tab2.click('#route-gym-form button[type="submit"]');
  await tab2.waitForSelector('#route-gym-form .msg.conflict');
  const msg = await tab2.textContent('#route-gym-form .msg');
  check(msg.includes('Someone else saved this first') && msg.includes(setter),
        'the second tab is refused and shown the first tab\'s change (' + msg + ')');
  await tab2.screenshot({ path: require('path').join(t.out, '91-cycle-conflict.png'), fullPage: true });
  await submit('route-gym-form', tab2);  // apply theirs again over the current revision
  let route = (await api('GET', '/api/routes/' + made.data.id)).data;
  check(route.setters.join() === 'Guest', 'saving again applies the second tab\'s change');
  await tab2.close();

  // Set and strip with the buttons; the typed set date stays.
  await page.goto(routeUrl);
  await submit('route-set');
  route = (await api('GET', '/api/routes/' + made.data.id)).data;
  check(route.state === 'set' && route.set_on === '2026-09-15', 'Set on the wall keeps the typed date (' +
        route.set_on + ')');
  check(await page.$('#route-plan') === null && await page.$('#route-strip') !== null,
        'a set route offers Strip only');
  await submit('route-strip');
  route = (await api('GET', '/api/routes/' + made.data.id)).data;
  check(route.state === 'stripped' && /^\d{4}-\d{2}-\d{2}$/.test(route.strip_on), 'Strip strips it');
  check(await page.$('#route-state-buttons') === null, 'nothing leaves the archive by a button');

  // The wall page: set all of today's planned routes, then strip the wall.
  await page.goto(base + '/walls/' + cave.id);
  const today = await page.getAttribute('#wall-set-today input[name="day"]', 'value');
  for (const name of ['Today A', 'Today B']) {
    await api('POST', '/api/routes', { crdl: 'name: ' + name + '\n---\nR crimp\nL jug\n', gym: second,
                                       public: false, wall: cave.id, state: 'planned', set_on: today });
  }
  await page.goto(base + '/walls/' + cave.id);
  await submit('wall-set-today');
  check((await page.$$('#wall-set tbody tr')).length === 2, 'the wall page sets today\'s planned routes');
  await shot('91-cycle-wall');
  await submit('wall-strip');
  check(await page.$('#wall-set') === null && (await page.$$('#wall-stripped tbody tr')).length === 3,
        'the wall page strips the wall');
  void first;
};
