// Setting days (issue 22): a head setter proposes a setting day for a wall, reads the ranked
// gallery (score, reasons), accepts a candidate for a setter; the planned route's tag PDF prints
// its name (pdftotext) and the day's sheet lists it.
'use strict';
const fs = require('fs');
const path = require('path');
const { execFileSync } = require('child_process');

module.exports = async (t) => {
  const { page, base, check, shot, api, out } = t;
  const n = Date.now() % 100000;
  // A day ahead (a date in the past is refused, issue 33).
  const day = new Date(Date.now() + 30 * 864e5).toISOString().slice(0, 10);
  const head = 'dayhead' + n;
  const password = 'correct horse battery';
  await page.context().clearCookies();
  await page.goto(base + '/signup');
  await page.fill('#username', head);
  await page.fill('#password', password);
  await Promise.all([page.waitForURL(base + '/'), page.click('#submit')]);

  const gym = (await api('POST', '/api/gyms', { name: 'Day Gym ' + n })).data.id;
  const wall = (await api('POST', '/api/gyms/' + gym + '/walls', { name: 'Cave' })).data.id;
  const routes = [
    ['V3', 'R small crimp\nL small crimp\nR sidepull\nL gaston\nR crimp\nL jug finish\n'],
    ['V4', 'L sloper\nR small crimp\nL heel hook\nR pinch\nL crimp\nR top out\n'],
    ['V5', 'R jug\nL crimp\nR crimp\nL undercling\nR sloper\nL jug finish\n']];
  for (const [i, [grade, moves]] of routes.entries()) {
    const r = await api('POST', '/api/routes', { crdl: 'name: Day Route ' + n + '-' + i + '\ngrade: ' + grade +
                                                 '\n---\n' + moves, public: true, gym, wall: wall, state: 'set' });
    check(r.status === 201, 'a route on the wall (' + r.status + ')');
  }

  await page.goto(base + '/gyms/' + gym);
  await Promise.all([page.waitForURL(/setting-day/), page.click('#gym-setting-day')]);
  await page.fill('#day-date', day);
  await page.check('input[name="walls"][value="' + wall + '"]');
  await Promise.all([page.waitForURL(/walls=/), page.click('#day-propose')]);
  check(page.url().includes('date=' + day), 'the day\'s state is in the URL');
  const cands = await page.$$('.day-candidate');
  check(cands.length >= 1, 'the slot shows a ranked gallery (' + cands.length + ' candidates)');
  const first = await page.textContent('.day-candidate h3');
  check(/score \d+\.\d \/ 100/.test(first), 'each candidate shows its score (' + first.trim() + ')');
  check((await page.$$('.day-candidate ul.reasons li')).length >= 4, 'and why it ranks there');
  await shot('97-setting-day');

  // Issue 33: the slot's band and style edited on the page, proposed again.
  await page.fill('#slot-band-1', 'V3');
  await page.selectOption('#slot-style-1', 'sloper');
  await Promise.all([page.waitForURL(/sb=V3/), page.click('#day-slots-propose')]);
  const h2 = await page.textContent('#slot-1 h2');
  check(h2.includes('V3') && h2.includes('sloper'), 'the slot is the one edited (' + h2.trim() + ')');
  check(!(await page.$('.day-rejected .day-accept')), 'rejected candidates have no Accept button');
  // Issue 33: the best candidate's predicted grade (from its inputs' grades) and style.
  const predicted = await page.textContent('#slot-1 > .day-candidate .day-predicted');
  check(/Predicted grade V\d+/.test(predicted) && predicted.includes('80%'),
        'the best candidate shows its predicted grade with an interval (' + predicted.trim().slice(0, 60) + ')');
  check(predicted.includes('Style:'), 'and its style in words');
  const slotsUrl = page.url();

  // Accept one per slot (one wall, one slot here).
  await page.click('#slot-1 .day-candidate form.day-accept button[type="submit"]');
  await page.waitForSelector('.day-candidate .accepted-tag');
  const tagHref = await page.getAttribute('.day-candidate .accepted-tag', 'href');
  const id = Number(tagHref.match(/\/routes\/(\d+)\/tag\.pdf/)[1]);
  const route = (await api('GET', '/api/routes/' + id)).data;
  check(route.state === 'planned' && route.set_on === day && route.wall_id === wall,
        'the accepted candidate is a planned route on the wall (' + route.state + ')');
  // Reloaded: the slot shows it accepted, its other candidates folded;
  // accepting it again is refused with a message.
  await page.goto(slotsUrl);
  check(await page.getAttribute('#slot-1', 'data-accepted') === String(id),
        'after a reload the slot is filled by the accepted route');
  check((await page.textContent('#slot-1 .day-accepted')).includes('route ' + id), 'and says which');
  check(!(await page.$('#slot-1 > .day-candidate form.day-accept')), 'its other candidates are folded');
  // Print the day: the forms are not printed.
  await page.emulateMedia({ media: 'print' });
  check(!(await page.isVisible('#day-slots')), 'the printed day leaves the forms out');
  await shot('97-setting-day-print');
  await page.emulateMedia({ media: 'screen' });
  check(await page.isVisible('#day-print'), 'a Print the day button');
  const tagRes = await page.request.get(base + tagHref);
  const tagFile = path.join(out, '97-setting-day-tag.pdf');
  fs.writeFileSync(tagFile, await tagRes.body());
  const tagText = execFileSync('pdftotext', [tagFile, '-']).toString().replace(/\s+/g, ' ');
  check(tagRes.status() === 200 && tagText.includes(route.name.slice(0, 20)) && tagText.includes(head),
        'its tag prints its name and setter');

  await page.goto(base + '/gyms/' + gym + '/setting-day/sheet?date=' + day);
  const sheet = await page.textContent('main');
  check(sheet.includes(head) && sheet.includes('Cave') && sheet.includes(route.name.slice(0, 20)),
        'the day\'s sheet lists what each setter sets where');
  const tags = await page.request.get(base + await page.getAttribute('#sheet-tags', 'href'));
  const tagsFile = path.join(out, '97-setting-day-tags.pdf');
  fs.writeFileSync(tagsFile, await tags.body());
  check(tags.status() === 200 && execFileSync('pdftotext', [tagsFile, '-']).toString().replace(/\s+/g, ' ').includes(route.name.slice(0, 20)),
        'the day\'s sheet of tags prints it');
  await shot('97-setting-day-sheet');
};
