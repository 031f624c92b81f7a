// The gym (issue 21): a head setter creates a gym with three walls and two circuits and adds a
// setter, who plans a route on a wall, sets it, strips it and finds it in the archive
// (state=stripped); on the wall it prints its tag (pdftotext shows the fields, zbarimg decodes
// the QR code to /r/{id}) and the wall's sheet of tags; a second gym on the same server sees
// none of it.
'use strict';
const fs = require('fs');
const path = require('path');
const { execFileSync } = require('child_process');

// The first QR code on the first page of a PDF file, or why not.
function decode(out, pdf, stem) {
  execFileSync('pdftoppm', ['-png', '-r', '200', '-f', '1', '-l', '1', '-singlefile', pdf, path.join(out, stem)]);
  try {
    return execFileSync('zbarimg', ['-q', '--raw', '-Sdatabar.disable', '-Sdatabar-exp.disable', path.join(out, stem + '.png')]).toString().trim().split('\n')[0];
  } catch (e) {
    return 'zbarimg failed: ' + e.message;
  }
}
module.exports = async (t) => {
  const { page, base, check, shot, api, out } = t;
  const n = Date.now() % 100000;
  const head = 'head' + n, setter = 'crew' + n, rival = 'rival' + n;
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
  // Submits a gym page form and waits for the reload.
  async function submit(formId) {
    await Promise.all([page.waitForNavigation(), page.click('#' + formId + ' button[type="submit"]')]);
  }

  await signUp(setter);
  await signUp(rival);
  await signUp(head);
  await page.goto(base + '/gyms');
  await page.fill('#gym-name', 'Boulder Barn ' + n);
  await Promise.all([page.waitForURL(/\/gyms\/\d+$/), page.click('#new-gym button[type="submit"]')]);
  const gymUrl = page.url();
  const gym = Number(gymUrl.match(/\/gyms\/(\d+)$/)[1]);
  check((await page.textContent('#gym-title')).includes('Boulder Barn'), 'the head setter creates a gym');
  for (const [name, discipline, angle] of [['Cave', 'bouldering', '40'], ['Slab', 'bouldering', '-10'],
                                           ['Lead Wall', 'roped', '5']]) {
    await page.fill('#wall-name', name);
    await page.selectOption('#wall-discipline', discipline);
    await page.fill('#wall-angle', angle);
    await submit('new-wall');
  }
  check((await page.$$('#wall-list tbody tr')).length === 3, 'three walls');
  for (const [colour, from, to] of [['blue', 'V0', 'V2'], ['red', 'V3', 'V5']]) {
    await page.fill('#circuit-colour', colour);
    await page.fill('#circuit-from', from);
    await page.fill('#circuit-to', to);
    await submit('new-circuit');
  }
  check((await page.$$('#circuit-list li')).length === 2, 'two circuits');
  await page.fill('#member-name', setter);
  await page.selectOption('#member-role', 'setter');
  await submit('new-member');
  check((await page.textContent('#member-list')).includes(setter), 'the head setter adds a setter');
  await page.setViewportSize({ width: 390, height: 844 });
  await shot('90-gym-phone');
  await page.setViewportSize({ width: 1200, height: 900 });
  const walls = (await api('GET', '/api/gyms/' + gym + '/walls')).data.walls;
  const cave = walls.find((w) => w.name === 'Cave');

  // The setter plans a route on the Cave, sets it and strips it.
  await logIn(setter);
  const crdl = 'name: Gym Ladder ' + n + '\ngrade: V3\ncolour: red\n---\nR crimp\nL sloper\nR jug finish\n';
  const made = await api('POST', '/api/routes', { crdl, public: false, gym, wall: cave.id,
                                                   state: 'planned', set_on: '2026-12-01', setters: [setter] });
  check(made.status === 201, 'the setter plans a route on a wall (' + made.status + ')');
  const rid = made.data.id;
  await page.goto(base + '/walls/' + cave.id);
  check((await page.textContent('#wall-planned')).includes('Gym Ladder'), 'the wall page lists it as planned');
  await page.goto(base + '/routes/' + rid);
  check((await page.textContent('#route-state')).includes('planned'), 'the route page shows its state');
  check((await page.textContent('#route-wall')).includes('Cave'), 'and its wall');
  await page.selectOption('#route-state-select', 'set');
  await submit('route-gym-form');
  check((await page.textContent('#route-state')).includes('on the wall'), 'the setter sets it');
  // Its tag: the fields and a QR code to its climbers' page.
  const tagRes = await page.request.get(base + '/routes/' + rid + '/tag.pdf');
  const tagFile = path.join(out, '90-gym-tag.pdf');
  fs.writeFileSync(tagFile, await tagRes.body());
  const tagText = execFileSync('pdftotext', [tagFile, '-']).toString().replace(/\s+/g, ' ');
  check(tagRes.status() === 200 && ['Gym Ladder ' + n, 'V3', 'red', 'Cave', setter, '/r/' + rid]
    .every((f) => tagText.includes(f)), 'the tag shows name, grade, circuit, wall, setter and link');
  const qr = decode(out, tagFile, '90-gym-tag');
  check(qr.endsWith('/r/' + rid), 'the tag\'s QR code links to /r/' + rid + ' (' + qr + ')');
  const sheet = await page.request.get(base + '/api/gyms/' + gym + '/tags.pdf?wall=' + cave.id + '&state=set');
  const sheetFile = path.join(out, '90-gym-sheet.pdf');
  fs.writeFileSync(sheetFile, await sheet.body());
  check(sheet.status() === 200 &&
        execFileSync('pdftotext', [sheetFile, '-']).toString().replace(/\s+/g, ' ').includes('Gym Ladder ' + n),
        'the wall\'s sheet of tags has it (' + sheet.status() + ')');
  await page.selectOption('#route-state-select', 'stripped');
  await submit('route-gym-form');
  check((await page.textContent('#route-state')).includes('stripped'), 'and strips it');
  check((await page.$$('#route-history li')).length === 3, 'its history has three changes');
  await shot('90-route-history');
  await page.goto(base + '/?gym=' + gym);
  await page.selectOption('#state-filter', 'stripped');
  await Promise.all([page.waitForNavigation(), page.click('form.search button[type="submit"]')]);
  check(page.url().includes('state=stripped') && (await page.textContent('#route-list')).includes('Gym Ladder'),
        'the stripped route is in the archive (state=stripped)');

  // A second gym on the same server sees none of it.
  await logIn(rival);
  const other = await api('POST', '/api/gyms', { name: 'Rival Rocks ' + n });
  check(other.status === 201, 'a second gym');
  const seen = [];
  for (const p of ['/api/routes/' + rid, '/api/gyms/' + gym, '/api/gyms/' + gym + '/walls',
                   '/api/routes?gym=' + gym, '/api/routes/' + rid + '/history',
                   '/api/gyms/' + gym + '/tags.pdf', '/routes/' + rid + '/tag.pdf']) {
    const r = await api('GET', p);
    if (r.status !== 404) seen.push(p + ' ' + r.status);
  }
  const search = await api('GET', '/api/routes?q=' + encodeURIComponent('Gym Ladder'));
  if (search.data.total !== 0) seen.push('search');
  for (const p of ['/gyms/' + gym, '/walls/' + cave.id, '/routes/' + rid]) {
    await page.goto(base + p);
    if ((await page.content()).includes('Gym Ladder') || (await page.content()).includes('Boulder Barn')) seen.push(p);
  }
  check(seen.length === 0, 'the second gym sees none of it (' + seen.join(', ') + ')');
};
