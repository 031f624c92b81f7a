// The route editor: live feedback marks a bad line; saving shows the route.
'use strict';
const ROUTE = [
  'name: Browser Test Arete',
  'grade: V3',
  'setter: playwright',
  'Set by the browser test.',
  '---',
  'R big jug at the start',
  'L small crimp',
  'R match',
  'L sloper on the arete',
  'R high step to the rail',
  'L dyno to the finish jug',
  'Q this line is wrong',
].join('\n');
module.exports = async (t) => {
  const { page, base, check, shot } = t;
  await page.goto(base + '/routes/new');
  check(await page.isVisible('#route-form'), 'a new route is a form first (issue 31)');
  await page.click('#view-text');  // the CRDL text: the advanced view
  check((await page.inputValue('#crdl')) === '', 'the editor starts empty (the starter text is a placeholder)');
  await page.fill('#crdl', ROUTE);
  await page.waitForSelector('#feedback li.fb-error');
  const errLine = await page.textContent('#feedback li.fb-error');
  check(errLine.includes('Q this line is wrong'), 'editor highlights the unparsed line');
  const moves = await page.$$('#feedback li.fb-move');
  check(moves.length === 6, 'editor shows each move line (' + moves.length + ')');
  await shot('03-editor-error');
  await page.fill('#crdl', ROUTE.split('\n').slice(0, -1).join('\n'));
  await page.waitForFunction(() => !document.querySelector('#feedback li.fb-error'));
  await shot('04-editor');
  await Promise.all([page.waitForURL(/\/routes\/\d+$/), page.click('#save')]);
  t.state.routeId = Number(page.url().match(/\/routes\/(\d+)$/)[1]);
  check((await page.textContent('h1')).includes('Browser Test Arete'), 'route saved and shown');
  await shot('05-route');
  // An unknown word gets a did-you-mean from the grammar's vocabulary.
  await page.goto(base + '/routes/new');
  await page.click('#view-text');
  await page.fill('#crdl', 'name: Typo\n---\nR crmip\n');
  await page.waitForSelector('#feedback .did-you-mean');
  check((await page.textContent('#feedback .did-you-mean')).includes('"crimp"'), '"crmip" is flagged: did you mean "crimp"?');
  await shot('04b-editor-did-you-mean');
  const icon = await page.request.get(base + '/static/favicon.svg');
  check(icon.status() === 200 && (await page.$('link[rel=icon]')) !== null, 'the pages have a favicon');
  await page.goto(base + '/?q=arete');
  check((await page.textContent('#route-list')).includes('Browser Test Arete'), 'search finds the route');
};
