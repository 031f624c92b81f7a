// A gym's history: import the original site's CSV (../shared/corpus) and vary
// a route older than the newest 500 by choosing it in the picker.
'use strict';
const fs = require('fs');
const path = require('path');
module.exports = async (t) => {
  const { page, base, check, shot, api } = t;
  const dir = path.join(__dirname, '..', '..', '..', 'shared', 'corpus');
  if (!fs.existsSync(path.join(dir, 'public_routes.csv'))) {
    console.log('skip corpus: ../shared/corpus is absent');
    return;
  }
  await page.goto(base + '/import');
  await page.setInputFiles('#routes-csv', path.join(dir, 'public_routes.csv'));
  await page.setInputFiles('#moves-csv', path.join(dir, 'public_moves.csv'));
  await page.click('#import-csv');
  await page.waitForFunction(() => /imported|error/.test(document.querySelector('#csv-msg').textContent), null, { timeout: 60000 });
  const msg = await page.textContent('#csv-msg');
  check(/\d+ routes imported/.test(msg), 'the original site\'s CSV imports (' + msg.slice(0, 80) + ')');
  const all = await api('GET', '/api/routes?variations=0&sort=oldest&limit=1');
  const oldest = all.data.routes[0];
  const newest = await api('GET', '/api/routes?limit=500');
  check(newest.data.total > 500 && !newest.data.routes.some((r) => r.id === oldest.id),
        'more than 500 routes now (' + newest.data.total + '), the oldest not among the newest 500');
  await page.goto(base + '/?sort=oldest');
  check((await page.textContent('#shown')).includes('of'), 'the route list pages (' + (await page.textContent('#shown')) + ')');
  await page.goto(base + '/');
  await Promise.all([page.waitForURL(/offset=50/), page.click('#next')]);
  check((await page.$$('#route-list tbody tr')).length === 50, 'the next page of the route list has 50 routes');
  await page.goto(base + '/vary');
  await page.fill('#route-find', oldest.name);
  await page.waitForFunction((id) => !!document.querySelector('#found li[data-id="' + id + '"]'), oldest.id);
  await page.click('#found li[data-id="' + oldest.id + '"] button.add');
  await shot('11-vary-old-route');
  await Promise.all([page.waitForURL(/\/variations\/\d+/), page.click('#generate')]);
  const v = await api('GET', '/api/variations/' + page.url().match(/\/variations\/(\d+)/)[1]);
  check(v.data.inputs.length === 1 && v.data.inputs[0].route === oldest.id,
        'a route older than the newest 500 is varied by choosing it in the picker (' + oldest.name + ')');
  await page.goto(base + '/routes/' + oldest.id);
  await Promise.all([page.waitForURL(/\/vary/), page.click('#vary-this')]);
  check((await page.$$('#chosen li')).length === 1, '"Vary this route" opens the form with that route chosen');
};
