// Visibility follows the gym (issue 31): a head setter of gym A makes a draft and a planned
// route; a head setter of gym B and a logged-out visitor see nothing of them (list, search,
// route page, history, tag sheet, CSV export); a logged-out visitor of A's page logs in and is
// back on it; a climber member of A sees no setters' navigation; a setter of A sees "Edit" on
// a teammate's route on the wall.
'use strict';
module.exports = async (t) => {
  const { page, base, check, shot, api } = t;
  const n = Date.now() % 100000;
  const headA = 'vishead' + n, headB = 'visrival' + n, climber = 'visclimb' + n, setter = 'visset' + n;
  const password = 'correct horse battery';

  async function logIn(user) {
    await page.context().clearCookies();
    await page.goto(base + '/login');
    await page.fill('#username', user);
    await page.fill('#password', password);
    await Promise.all([page.waitForURL(base + '/'), page.click('#submit')]);
  }
  async function signUp(user) {
    await page.context().clearCookies();
    await page.goto(base + '/signup');
    await page.fill('#username', user);
    await page.fill('#password', password);
    await Promise.all([page.waitForURL(base + '/'), page.click('#submit')]);
  }

  for (const u of [climber, setter, headB, headA]) await signUp(u);
  // Gym A, its team and wall; a draft, a planned route and one on the wall, none published.
  const gym = (await api('POST', '/api/gyms', { name: 'Hidden Holds ' + n })).data.id;
  await api('POST', '/api/gyms/' + gym + '/members', { username: climber, role: 'climber' });
  await api('POST', '/api/gyms/' + gym + '/members', { username: setter, role: 'setter' });
  const wall = (await api('POST', '/api/gyms/' + gym + '/walls', { name: 'North', discipline: 'bouldering' })).data.id;
  const make = async (tag, state, extra) => (await api('POST', '/api/routes', Object.assign({
    crdl: 'name: Secret ' + tag + ' ' + n + '\ngrade: V2\n---\nR crimp\nL sloper-' + tag + n + '\n',
    gym, state, wall: String(wall),
  }, extra || {}))).data.id;
  const draft = await make('draft', 'draft');
  const planned = await make('planned', 'planned', { set_on: '2026-12-24' });
  const onWall = await make('wall', 'set');
  check(draft && planned && onWall, 'the head setter of gym A makes a draft, a planned route and a set one');
  await page.goto(base + '/routes/' + planned);
  check((await page.textContent('#library-tag')).includes('gym only') && !(await page.isChecked('#route-library')),
        'a gym route is not in the shared library by default');

  // What an outsider may ask for: none of it answers.
  async function outsiderSees() {
    const seen = [];
    for (const id of [draft, planned]) {
      for (const p of ['/api/routes/' + id, '/api/routes/' + id + '/history', '/tags.pdf?ids=' + id,
                       '/routes/' + id + '/tag']) {
        const r = await api('GET', p);
        if (r.status !== 404) seen.push(p + ' ' + r.status);
      }
      const resp = await page.goto(base + '/routes/' + id);
      if (resp.status() !== 404 || (await page.content()).includes('Secret')) seen.push('/routes/' + id);
    }
    const list = await api('GET', '/api/routes?limit=500');
    if (JSON.stringify(list.data).includes('Secret')) seen.push('list');
    const search = await api('GET', '/api/routes?q=' + encodeURIComponent('Secret'));
    if (search.data.total !== 0) seen.push('search');
    for (const f of ['routes', 'moves']) {
      const csv = await api('GET', '/api/export/' + f + '.csv');
      if (String(csv.data).includes('Secret') || String(csv.data).includes('sloper-')) seen.push(f + '.csv');
    }
    const sheet = await api('GET', '/api/gyms/' + gym + '/tags.pdf?wall=' + wall);
    if (sheet.status !== 404) seen.push('gym tags.pdf ' + sheet.status);
    return seen;
  }
  await logIn(headB);
  await api('POST', '/api/gyms', { name: 'Rival Rocks ' + n });
  let seen = await outsiderSees();
  check(seen.length === 0, "gym B's head setter sees nothing of A's draft and plan (" + seen.join(', ') + ')');

  await page.context().clearCookies();
  seen = await outsiderSees();
  check(seen.length === 0, "a logged-out visitor sees nothing of A's draft and plan (" + seen.join(', ') + ')');
  // The route on the wall: at its QR code's page, for anyone.
  const qr = await page.goto(base + '/r/' + onWall);
  check(qr.status() === 200 && (await page.content()).includes('Secret wall'), 'the route on the wall opens at /r/{id}');

  // A logged-out visitor of the gym's page: the log-in page, then back to it.
  await page.goto(base + '/gyms/' + gym);
  check(page.url().startsWith(base + '/login?next=/gyms/' + gym), 'a gym page sends a logged-out visitor to log in');
  await page.fill('#username', headA);
  await page.fill('#password', password);
  await Promise.all([page.waitForURL(base + '/gyms/' + gym), page.click('#submit')]);
  check((await page.textContent('#gym-title')).includes('Hidden Holds'), 'and back to the gym page after logging in');
  check(await page.$('a.wall-tags') !== null, "the gym page links the wall's tag sheet");

  // A climber member: no setters' navigation.
  await logIn(climber);
  const navs = ['#nav-new', '#nav-vary', '#nav-studies', '#nav-drift', '#nav-import'];
  const shown = [];
  for (const s of navs) if (await page.$(s)) shown.push(s);
  check(shown.length === 0, 'a climber sees no setters\' navigation (' + shown.join(', ') + ')');
  await shot('92-climber-nav');
  const asClimber = await page.goto(base + '/routes/' + planned);
  check(asClimber.status() === 404, 'a climber does not see a planned route');

  // A setter: "Edit" on a teammate's route on the wall; the library box too.
  await logIn(setter);
  check(await page.$('#nav-new') !== null && await page.$('#nav-vary') !== null, 'a setter has the setters\' navigation');
  await page.goto(base + '/routes/' + onWall);
  check(await page.isVisible('#edit') && await page.isVisible('#route-library'),
        "a setter sees Edit (and the library box) on a teammate's route");
  await shot('92-setter-edit');
  await page.goto(base + '/walls/' + wall);
  check(await page.isVisible('#wall-tags'), "the wall page links the wall's tag sheet");
  await page.goto(base + '/routes/' + draft);
  check(!(await page.$('#edit')), "a teammate's draft stays its owner's (no Edit)");
  // Publishing the route on the wall from its page: the rival sees it then.
  await page.goto(base + '/routes/' + onWall);
  await Promise.all([page.waitForNavigation(), page.check('#route-library')]);
  check((await page.textContent('#library-tag')).includes('shared library'), 'the setter publishes it to the shared library');
  await logIn(headB);
  check((await api('GET', '/api/routes/' + onWall)).status === 200, 'then the other gym sees it');
};
