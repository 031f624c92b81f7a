// The logbook (issue 23): five climbers on 390 px phones tick a route (flash, sends, attempts,
// stars); one clears its cookies and stuffs "V9" grades from new identities, which are held and
// shown to the setter; the route page shows the ascent grade with its interval; a climber signs
// in and finds their phone's ticks merged into their logbook, and their chance on the route.
'use strict';
module.exports = async (t) => {
  const { page, base, check, shot, api } = t;
  const n = Date.now() % 100000;
  const head = 'lbhead' + n, ann = 'lbann' + n;
  const password = 'correct horse battery';
  const ctx = page.context();

  async function signUp(user) {
    await ctx.clearCookies();
    await page.goto(base + '/signup');
    await page.fill('#username', user);
    await page.fill('#password', password);
    await Promise.all([page.waitForURL(base + '/'), page.click('#submit')]);
  }
  async function logIn(user) {
    await page.goto(base + '/login');
    await page.fill('#username', user);
    await page.fill('#password', password);
    await Promise.all([page.waitForURL(base + '/'), page.click('#submit')]);
  }
  // One tick from the phone's current cookies: two taps (outcome, "Log tick") plus extras.
  async function tick(rid, outcome, attempts, stars, felt) {
    await page.goto(base + '/r/' + rid);
    await page.click('label.outcome:has(#outcome-' + outcome + ')');
    if (attempts) await page.fill('#tick-attempts', String(attempts));
    if (stars) await page.click('.stars label:has(#stars-' + stars + ')');
    if (felt) await page.fill('#tick-felt', felt);
    await page.click('#tick-submit');
    await page.waitForFunction(() => document.getElementById('tick-msg').textContent !== '');
    return page.textContent('#tick-msg');
  }

  await signUp(ann);
  await signUp(head);
  const gym = await api('POST', '/api/gyms', { name: 'Logbook Gym ' + n });
  check(gym.status === 201, 'the head setter makes a gym (' + gym.status + ')');
  const crdl = 'name: Tick Ladder ' + n + '\ngrade: V4\n---\nR crimp\nL sloper\nR jug finish\n';
  const made = await api('POST', '/api/routes', { crdl, public: true, gym: gym.data.id, state: 'set' });
  check(made.status === 201, 'and sets a route (' + made.status + ')');
  const rid = made.data.id;

  await page.setViewportSize({ width: 390, height: 844 });
  const climbers = [['flash', null, 5, 'V4'], ['send', 3, 4, 'V4'], ['send', 5, 3, 'V5'],
                    ['attempt', 4, 2, 'V5'], ['send', 2, 4, 'V4']];
  let annPhone = null;
  for (let i = 0; i < climbers.length; ++i) {
    await ctx.clearCookies();
    const [o, a, s, f] = climbers[i];
    const msg = await tick(rid, o, a, s, f);
    check(msg.startsWith('Ticked: ' + o) && !msg.includes('held'), 'climber ' + (i + 1) + ' ticks: ' + msg);
    if (i === 0) {
      annPhone = (await ctx.cookies()).filter((c) => c.name === 'sb_climber');
      const w = await page.evaluate(() => document.documentElement.scrollWidth);
      check(w <= 390, '/r/{id} at 390 px has no horizontal scroll (' + w + ' px)');
      await shot('95-tick-phone');
    }
  }
  const again = await tick(rid, 'send', 2, 5, 'V4');  // the fifth phone edits its tick
  check(again.startsWith('Tick updated'), 'a second tick the same day edits it');

  // One phone clears its cookies and votes V9 six times: held.
  let held = 0;
  for (let i = 0; i < 6; ++i) {
    await ctx.clearCookies();
    if ((await tick(rid, 'attempt', 10, 1, 'V9')).includes('held')) ++held;
  }
  check(held === 6, 'the stuffed V9 ticks are held (' + held + ' of 6)');
  const ascent = (await api('GET', '/api/routes/' + rid + '/ascent')).data;
  check(ascent.ticks === 5 && ascent.felt_median !== 'V9', 'held ticks count nowhere (' +
        ascent.ticks + ' ticks, felt ' + ascent.felt_median + ')');

  // The setter sees them on the route page, with the ascent grade and its interval.
  await ctx.clearCookies();
  await page.setViewportSize({ width: 1200, height: 900 });
  await logIn(head);
  await page.goto(base + '/routes/' + rid);
  check((await page.$$('#held-ticks .held-tick')).length === 6, 'the setter sees six held ticks');
  const shown = await page.textContent('#ascent-grade');
  check(/Ascent grade V\S+ \(80%: V\S+ to V\S+\) from 5 ticks/.test(shown), 'the route page shows the ascent grade with its interval: ' + shown);
  await page.click('#held-ticks .held-tick:first-child .tick-discard');
  await page.waitForFunction(() => document.querySelector('#held-ticks .decided') !== null);
  await shot('95-route-held');
  const list = (await api('GET', '/api/routes/' + rid + '/ticks')).data.ticks;
  check(list.filter((x) => x.state === 'discarded').length === 1, 'the setter discards one');

  // Ann signs in on her phone: its tick joins her logbook.
  await ctx.clearCookies();
  await ctx.addCookies(annPhone);
  await page.setViewportSize({ width: 390, height: 844 });
  await logIn(ann);
  await page.goto(base + '/logbook');
  const rows = await page.$$('#ticks tr.tick');
  check(rows.length === 1 && (await page.textContent('#ticks')).includes('Tick Ladder ' + n),
        'the phone\'s tick is in the signed-in climber\'s logbook');
  check((await page.textContent('#pyramid')).includes('V4'), 'the pyramid counts the flash at V4');
  await shot('95-logbook-phone');
  // Issue 35: signed in with a tick at the gym, her chance on the route shows under its grade.
  await page.goto(base + '/r/' + rid);
  const chance = await page.textContent('#chance');
  check(/Your chance to flash: \S+% · to send this session: \S+%/.test(chance),
        'the chance line appears after ticks: ' + chance);
  await page.setViewportSize({ width: 1200, height: 900 });
};
