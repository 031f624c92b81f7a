// Closing the paper's loop (issue 23): five climbers tick two hand-set routes and two engine
// variations of the same grades on one wall; the wall's report shows the counts and the
// Wilcoxon / Welch comparison of their stars; the wall page shows each route's ascent grade.
'use strict';
module.exports = async (t) => {
  const { page, base, check, shot, api } = t;
  const n = Date.now() % 100000;
  const head = 'rphead' + n;
  const password = 'correct horse battery';
  const ctx = page.context();

  await ctx.clearCookies();
  await page.setViewportSize({ width: 1200, height: 900 });
  await page.goto(base + '/signup');
  await page.fill('#username', head);
  await page.fill('#password', password);
  await Promise.all([page.waitForURL(base + '/'), page.click('#submit')]);

  const gym = (await api('POST', '/api/gyms', { name: 'Report Gym ' + n })).data.id;
  const wall = await api('POST', '/api/gyms/' + gym + '/walls', { name: 'Cave' });
  check(wall.status === 201, 'the head setter adds a wall (' + wall.status + ')');
  const hand = [];
  for (const g of ['V3', 'V4']) {
    const crdl = 'name: Hand ' + g + ' ' + n + '\ngrade: ' + g + '\n---\nR crimp\nL sloper\nR gaston\nL jug finish\n';
    const r = await api('POST', '/api/routes', { crdl, public: true, gym, wall: 'Cave', state: 'set' });
    check(r.status === 201, 'a hand-set ' + g + ' on the wall (' + r.status + ')');
    hand.push(r.data.id);
  }
  // Two variations made by the engine, graded and set on the same wall.
  const vary = [];
  for (const g of ['V3', 'V4']) {
    const v = await api('POST', '/api/variations',
                        { routes: hand, public: true, gym, name: 'Vary ' + g + ' ' + n, grade: g });
    check(v.status === 201, 'the engine makes a ' + g + ' variation (' + v.status + ')');
    const put = await api('PUT', '/api/routes/' + v.data.id, { state: 'set', wall: 'Cave' });
    check(put.status === 200, 'and it is set on the wall (' + put.status + ')');
    vary.push(v.data.id);
  }

  // Five climbers (phones without accounts) tick all four: the hand-set ones get more stars.
  const handStars = [5, 4, 4, 5, 3], varyStars = [2, 3, 2, 1, 3];
  for (let i = 0; i < 5; ++i) {
    await ctx.clearCookies();
    for (let k = 0; k < 2; ++k) {
      for (const [id, stars] of [[hand[k], handStars[i]], [vary[k], varyStars[i]]]) {
        const r = await api('POST', '/api/routes/' + id + '/ticks',
                            { outcome: i % 2 ? 'send' : 'flash', attempts: i % 2 ? 3 : null, stars,
                              comment: i === 0 && k === 0 ? 'great moves ' + n : '' });
        check(r.status === 201 && !r.data.held, 'climber ' + (i + 1) + ' ticks ' + id + ' (' + r.status + ')');
      }
    }
  }

  await ctx.clearCookies();
  await page.goto(base + '/login');
  await page.fill('#username', head);
  await page.fill('#password', password);
  await Promise.all([page.waitForURL(base + '/'), page.click('#submit')]);
  await page.goto(base + '/gyms/' + gym);
  await Promise.all([page.waitForURL(/\/report\?wall=/), page.click('#wall-list a.wall-report')]);
  const totals = await page.$eval('#report-totals', (e) => ({ ...e.dataset, text: e.textContent }));
  check(totals.routes === '4' && totals.ticks === '20' && totals.climbers === '5',
        'the report counts 4 routes, 20 ticks, 5 climbers: ' + totals.text);
  const cmp = await page.$eval('#report-comparison', (e) => ({ ...e.dataset }));
  check(cmp.variationRatings === '10' && cmp.handRatings === '10' && cmp.enough === '1',
        'the comparison rests on 10 + 10 ratings (' + JSON.stringify(cmp) + ')');
  const verdict = await page.textContent('#report-verdict');
  check(/Variations are liked less than hand-set routes of the same grades/.test(verdict),
        'the verdict says it in words: ' + verdict);
  const wp = Number(await page.getAttribute('#wilcoxon-p', 'data-v'));
  const tp = Number(await page.getAttribute('#welch-p', 'data-v'));
  check(wp > 0 && wp < 0.05 && tp > 0 && tp < 0.05, 'Wilcoxon p = ' + wp + ', Welch p = ' + tp);
  check((await page.textContent('#report-comments')).includes('great moves ' + n),
        'the head setter reads the comments');
  check((await page.$$('#report-routes td.ascent[data-ticks="5"]')).length === 4,
        'each route shows its ascent grade from 5 ticks');
  await shot('98-report');

  // The API: the same figures.
  const json = (await api('GET', '/api/gyms/' + gym + '/report?wall=Cave')).data;
  check(json.variations_vs_hand_set.wilcoxon.p === wp, 'the API gives the same Wilcoxon p');

  // The wall page shows the ascent grades in its rows.
  await page.click('a[href^="/walls/"]');
  await page.waitForSelector('#wall-title');
  const cells = await page.$$eval('#wall-set td.ascent', (c) => c.map((x) => x.textContent));
  check(cells.length === 4 && cells.every((c) => /^V\S+ \(80%: V\S+ to V\S+\) from 5 ticks/.test(c)),
        'the wall page shows each route\'s ascent grade: ' + cells.join(' | '));
  await shot('98-wall');

  // The study editor's picker finds any route by search and tells same-named ones apart.
  await page.goto(base + '/studies/new');
  await page.fill('#study-find', 'Vary V3 ' + n);
  await page.waitForFunction((id) => document.querySelector('input.study-route[value="' + id + '"]') !== null &&
                             document.querySelectorAll('input.study-route').length === 1, vary[0]);
  const where = await page.textContent('.route-picks label small.where');
  check(where.includes('Report Gym ' + n) && where.includes('Cave'),
        'the picker shows gym and wall of a found route: ' + where);
  await page.check('input.study-route[value="' + vary[0] + '"]');
  check((await page.textContent('#study-order')).includes('Vary V3 ' + n), 'a found route can be chosen');
  await page.fill('#study-find', 'Hand V4 ' + n);
  await page.waitForFunction(() => document.querySelectorAll('input.study-route').length === 2);
  check(await page.isChecked('input.study-route[value="' + vary[0] + '"]'), 'a new search keeps the chosen routes');

  // More routes than the first page: "More routes" fetches the next ones.
  let total = (await api('GET', '/api/routes?limit=1')).data.total;
  for (let k = 0; total <= 55; ++k, ++total) {
    await api('POST', '/api/routes', { crdl: 'name: Filler ' + k + '\ngrade: V1\n---\nR jug\n', public: true });
  }
  await page.goto(base + '/studies/new');
  const firstPage = (await page.$$('input.study-route')).length;
  check(firstPage === 50 && await page.isVisible('#study-more'), 'the picker lists 50 routes and offers more (' + firstPage + ')');
  await page.click('#study-more');
  await page.waitForFunction((k) => document.querySelectorAll('input.study-route').length > k, firstPage);
  check((await page.$$('input.study-route')).length > 50, '"More routes" adds the next page');

  // Studies and Drift are in the navigation.
  check(await page.$('#nav-studies') !== null && await page.$('#nav-drift') !== null,
        'Studies and Drift are in the navigation');
};
