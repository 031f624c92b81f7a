// The vary page: three routes chosen in a given order give that order;
// Back after generating restores exactly the same form; the IC map has a
// legend and a read-out and clicking it never scrolls it away; the same form
// twice gives the same variation; the setter preset is the default (issue 22).
'use strict';
const route = (name, moves) => ['name: ' + name, 'grade: V2', '---'].concat(moves).join('\n');
module.exports = async (t) => {
  const { page, base, check, shot, api } = t;
  await page.goto(base + '/');
  const ids = [];
  for (const [name, moves] of [['Order Alpha', ['R alpha jug', 'L alpha crimp', 'R alpha sloper']],
                               ['Order Bravo', ['L bravo pinch', 'R bravo gaston', 'L bravo edge']],
                               ['Order Charlie', ['R charlie pocket', 'L charlie undercling', 'R charlie jug']]]) {
    const r = await api('POST', '/api/routes', { crdl: route(name, moves), public: true });
    ids.push(r.data.id);
  }
  // Choose Charlie, Alpha, Bravo through the picker's search box.
  await page.goto(base + '/vary');
  // Issue 22: the setter's preset first and chosen; the paper's stay selectable by name.
  const presets = await page.$$eval('#preset option', (os) => os.map((o) => o.value));
  check((await page.inputValue('#preset')) === 'setter' && presets.join(',') === 'setter,default,more',
        'the vary page defaults to the setter preset (' + presets + ')');
  for (const name of ['Charlie', 'Alpha', 'Bravo']) {
    await page.fill('#route-find', 'Order ' + name);
    await page.waitForFunction((n) => {
      const items = document.querySelectorAll('#found li');
      return items.length === 1 && items[0].dataset.name === 'Order ' + n;
    }, name);
    await page.click('#found li button.add');
  }
  // Then fix the order with the buttons: Charlie, Bravo, Alpha -> move Bravo up once.
  await page.click('#chosen li[data-id="' + ids[1] + '"] button.up');
  const order = await page.$$eval('#chosen li', (ls) => ls.map((l) => l.dataset.name));
  check(order.join('|') === 'Order Charlie|Order Bravo|Order Alpha', 'the picker keeps the chosen order (' + order + ')');
  check(page.url().includes('routes=' + [ids[2], ids[1], ids[0]].join('%2C')), 'the chosen routes are in the URL in order');
  await page.waitForSelector('#icmap[data-ready="1"]');
  check((await page.textContent('#map-legend')).includes('warm = little variation'), 'the IC map has a legend');
  const box = await (await page.$('#icmap')).boundingBox();
  await page.hover('#icmap', { position: { x: box.width * 0.3, y: box.height * 0.4 } });
  check(/moves change/.test(await page.textContent('#map-readout')), 'hovering the map shows "k of n moves change"');
  const before = await page.evaluate(() => window.scrollY);
  const mapTop = (await (await page.$('#icmap')).boundingBox()).y;
  await page.click('#icmap', { position: { x: box.width * 0.2, y: box.height * 0.5 } });
  const after = await page.evaluate(() => window.scrollY);
  const mapTop2 = (await (await page.$('#icmap')).boundingBox()).y;
  check(after === before && Math.abs(mapTop - mapTop2) < 1, 'clicking the map does not scroll it away');
  const ic = await page.inputValue('#var_ic');
  check(/^-?[\d.]+,-?[\d.]+,-?[\d.]+$/.test(ic) && /Chosen/.test(await page.textContent('#map-readout')), 'clicking the map sets the variation IC (' + ic + ')');
  await page.fill('#name', 'Three in order');
  await page.fill('#colour', 'orange');
  await shot('06-vary');
  const formUrl = page.url();
  await Promise.all([page.waitForURL(/\/variations\/\d+/), page.click('#generate')]);
  const varId = Number(page.url().match(/\/variations\/(\d+)/)[1]);
  t.state.orderVariation = varId;
  const v = await api('GET', '/api/variations/' + varId);
  const inputs = v.data.inputs.map((i) => i.route);
  check(inputs.join(',') === [ids[2], ids[1], ids[0]].join(','), 'vary uses the chosen order (' + inputs + ')');
  check(v.data.parameters.keep_start === true && v.data.parameters.keep_finish === true && !formUrl.includes('preset='),
        'the default form varies with the setter preset (kept start and finish)');
  check((await page.textContent('h1')) === 'Three in order', 'the variation has the chosen name');
  check(/^The setter's preset: the best of \d+ candidates .*score [\d.]+: /.test(await page.textContent('#gallery-note')),
        "the plan page says which candidate of the setter's gallery was stored and why");
  await shot('07-plan');
  // Back: the same routes in the same order, the same IC and name.
  await page.goBack();
  await page.waitForSelector('#chosen li');
  const back = await page.$$eval('#chosen li', (ls) => ls.map((l) => Number(l.dataset.id)));
  check(back.join(',') === [ids[2], ids[1], ids[0]].join(','), 'Back after generating gives the same routes (' + back + ')');
  check((await page.inputValue('#var_ic')) === ic && (await page.inputValue('#name')) === 'Three in order',
        'Back restores the parameters and the name');
  check(page.url() === formUrl, 'the form URL is the same after Back');
  // The same form again returns the same variation.
  await Promise.all([page.waitForURL(/\/variations\/\d+/), page.click('#generate')]);
  check(Number(page.url().match(/\/variations\/(\d+)/)[1]) === varId && await page.isVisible('#existing'),
        'generating the same form again gives the same variation, and says so');
  // A reload of a shared link restores the form too.
  await page.goto(formUrl);
  const again = await page.$$eval('#chosen li', (ls) => ls.map((l) => Number(l.dataset.id)));
  check(again.join(',') === back.join(','), 'a shared link restores the chosen routes');
};
