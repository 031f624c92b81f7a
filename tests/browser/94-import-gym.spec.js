// Issue 32, route lists as gyms have them: a head setter imports a German gym's list (gym scale
// 1-6, colour names, sectors, setters with accents and spaces, no moves) on the import page
// (columns prefilled from the German header, preview, confirm), prints a sector's tags (the
// colour names in pdftotext, a tag's QR decoded by zbarimg), sets targets in the gym scale,
// imports a changed list (2 renamed, 1 regraded, 3 removed, 2 new) and sees exactly those
// changes; then a French gym through the import page in a French browser (locale fr-FR).
'use strict';
const fs = require('fs');
const path = require('path');
const { execFileSync } = require('child_process');
const { chromium } = require('playwright-core');

module.exports = async (t) => {
  const { page, base, check, shot, api, out } = t;
  const n = Date.now() % 100000;
  const password = 'correct horse battery';

  await page.context().clearCookies();
  await page.goto(base + '/signup');
  await page.fill('#username', 'halle' + n);
  await page.fill('#password', password);
  await Promise.all([page.waitForURL(base + '/'), page.click('#submit')]);
  const gym = (await api('POST', '/api/gyms', { name: 'Boulderhalle ' + n })).data.id;
  const gp = '/api/gyms/' + gym;
  const scale = await api('POST', gp + '/scales', { name: 'Halle 1-6', labels: [
    { label: '1', from: 'VB', to: 'V0' }, { label: '2', from: 'V1', to: 'V2' },
    { label: '3', from: 'V3', to: 'V3' }, { label: '4', from: 'V4', to: 'V5' },
    { label: '5', from: 'V6', to: 'V7' }, { label: '6', from: 'V8', to: 'V12' }] });
  check(scale.status === 201, 'the gym scale 1-6 is made (' + scale.status + ')');

  const list = 'Nr,Name,Grad,Sektor,Farbe,Schrauber\n' +
    '1,Gelber Riss,3,Sektor A,gelb,Simon Räss\n' +
    '2,Blaue Platte,2,Sektor A,blau,Simon Räss; Anna Müller\n' +
    '3,Schwarzes Dach,6,Sektor A,schwarz,Anna Müller\n' +
    '4,Rote Kante,4,Sektor B,rot,Simon Räss\n' +
    '5,Grüne Welle,1,Sektor B,grün,Anna Müller\n' +
    '6,Weißer Hai,5,Sektor B,weiß,Simon Räss\n';
  await page.goto(base + '/gyms/' + gym);
  await Promise.all([page.waitForURL(/\/import$/), page.click('#gym-import')]);
  await page.fill('#import-data', list);
  await page.click('#import-read');
  await page.waitForSelector('#import-preview:not([hidden])');
  const mapped = await page.$$eval('.import-map', (ss) => ss.map((s) => s.dataset.field + '=' + s.value).join(','));
  check(['id=Nr', 'name=Name', 'grade=Grad', 'wall=Sektor', 'colour=Farbe', 'setters=Schrauber']
    .every((m) => mapped.includes(m)), 'the columns are prefilled from the German header (' + mapped + ')');
  const summary = await page.textContent('#import-summary');
  check(summary.startsWith('6 new, 0 changed, 0 no longer in the list'), 'the preview counts (' + summary + ')');
  check((await api('GET', '/api/routes?gym=' + gym)).data.total === 0, 'the preview wrote nothing');
  await shot('94-import-preview');
  await page.click('#import-confirm');
  await page.waitForSelector('#import-done.ok');
  check((await page.textContent('#import-done')).startsWith('6 created'), 'confirmed: 6 created');

  const walls = (await api('GET', gp + '/walls')).data.walls;
  const a = walls.find((w) => w.name === 'Sektor A');
  check(a && a.scale === 'Halle 1-6', 'the new sector reads the gym scale (' + (a && a.scale) + ')');
  // A German head setter: the tags print in their language (the account's, issue 32).
  const de = await api('PUT', '/api/account', { language: 'de' });
  check(de.status === 200, 'the head setter reads German (' + de.status + ')');
  const pdf = await page.request.get(base + gp + '/tags.pdf?wall=' + a.id);
  check(pdf.status() === 200, 'the sector\'s tags print (' + pdf.status() + ')');
  const file = path.join(out, '94-sektor-a.pdf');
  fs.writeFileSync(file, await pdf.body());
  const text = execFileSync('pdftotext', [file, '-']).toString();
  check(['Gelber Riss', 'gelb', 'blau', 'schwarz', 'Simon Räss'].every((s) => text.includes(s)),
    'the tags show the names, colour names and setters (' + text.replace(/\s+/g, ' ').slice(0, 200) + ')');
  // A tag's QR code, decoded from the printed page (zbarimg, scripts/setup.sh), leads to a route
  // of the sector.
  execFileSync('pdftoppm', ['-r', '150', '-f', '1', '-l', '1', '-png', file, path.join(out, '94-sektor-a')]);
  const png = fs.readdirSync(out).find((f) => f.startsWith('94-sektor-a') && f.endsWith('.png'));
  let qr = '';
  try {
    qr = execFileSync('zbarimg', ['-q', '--raw', '-Sdatabar.disable', '-Sdatabar-exp.disable', path.join(out, png)]).toString().trim().split('\n')[0];
  } catch (e) { qr = 'zbarimg failed: ' + e.message; }
  const onA = (await api('GET', '/api/routes?gym=' + gym + '&wall=' + a.id)).data.routes.map((r) => r.id);
  const qrId = Number((qr.match(/\/r\/(\d+)$/) || [])[1]);
  check(onA.includes(qrId), 'a tag\'s QR decodes to a route of the sector (' + qr + ')');
  const tg = await api('PUT', gp + '/walls/' + a.id + '/targets', { grades: { '3': 2, '6': 1 } });
  check(tg.status === 200, 'targets in the gym scale are accepted (' + tg.status + ')');
  const bad = await api('PUT', gp + '/walls/' + a.id + '/targets', { grades: { 'V4': 1 } });
  check(bad.status === 400, 'a V grade is refused on the 1-6 sector (' + bad.status + ')');
  // Circuits in the gym scale's labels, refused otherwise; the mapping a season would suggest
  // (no ticks yet: every label kept as it is).
  const circ = await api('POST', gp + '/circuits', { colour: 'gelb', grade_from: '2', grade_to: '4' });
  check(circ.status === 201, 'a circuit 2-4 in the gym scale (' + circ.status + ')');
  const circBad = await api('POST', gp + '/circuits', { colour: 'rot', grade_from: 'V2', grade_to: '4' });
  check(circBad.status === 400 && /Halle 1-6/.test(circBad.data.error), 'a V grade circuit is refused naming the scale');
  const sug = await api('GET', gp + '/scales/' + encodeURIComponent('Halle 1-6') + '/suggest');
  check(sug.status === 200 && sug.data.labels.length === 6 && sug.data.labels.every((l) => l.kept) &&
    sug.data.labels[3].from === 'V4' && sug.data.walls === 2, 'the suggestion keeps every label without ticks');

  // The changed list: 1 and 2 renamed, 3 regraded, 4-6 gone, 7 and 8 new.
  const changed = 'Nr,Name,Grad,Sektor,Farbe,Schrauber\n' +
    '1,Gelbe Rinne,3,Sektor A,gelb,Simon Räss\n' +
    '2,Blauer Traum,2,Sektor A,blau,Simon Räss; Anna Müller\n' +
    '3,Schwarzes Dach,5,Sektor A,schwarz,Anna Müller\n' +
    '7,Lila Laune,2,Sektor C,lila,Anna Müller\n' +
    '8,Türkis,4,Sektor C,türkis,Simon Räss\n';
  await page.reload();
  await page.fill('#import-data', changed);
  await page.click('#import-read');
  // The head setter reads German now: the page's script speaks it too.
  await page.waitForFunction(() => document.querySelector('#import-summary').textContent.includes('2 neu'));
  const s2 = await page.textContent('#import-summary');
  check(s2.startsWith('2 neu, 3 geändert, 3 nicht mehr in der Liste: abschrauben?'), 'the changed list previews (' + s2 + ')');
  const changes = await page.$$eval('#import-rows tr.import-changed td:last-child', (tds) => tds.map((td) => td.textContent));
  check(changes.join('|') === 'name: Gelber Riss -> Gelbe Rinne|name: Blaue Platte -> Blauer Traum|grade: 6 -> 5',
    'exactly those changes (' + changes.join('|') + ')');
  await page.check('#import-strip');
  await page.click('#import-confirm');
  await page.waitForSelector('#import-done.ok');
  check((await page.textContent('#import-done')).startsWith('2 angelegt, 3 aktualisiert, 3 abgeschraubt'), 'confirmed with strip');
  await shot('94-import-changed');
  const set = (await api('GET', '/api/routes?gym=' + gym + '&state=set&sort=name')).data.routes.map((r) => r.name);
  check(set.join(',') === 'Blauer Traum,Gelbe Rinne,Lila Laune,Schwarzes Dach,Türkis', 'on the wall now: ' + set.join(','));
  const gone = (await api('GET', '/api/routes?gym=' + gym + '&state=stripped&sort=name')).data.routes.map((r) => r.name);
  check(gone.join(',') === 'Grüne Welle,Rote Kante,Weißer Hai', 'stripped: ' + gone.join(','));

  // A French gym, its head setter in a French browser (locale fr-FR: Accept-Language): the page
  // answers in French, the import page reads the French header, previews and imports.
  const browser = await chromium.launch({ executablePath: process.env.SB_CHROMIUM || '/usr/bin/chromium',
    headless: true, args: ['--headless', '--no-sandbox', '--disable-gpu', '--no-first-run'] });
  try {
    const frCtx = await browser.newContext({ locale: 'fr-FR', viewport: { width: 1200, height: 900 } });
    const fp = await frCtx.newPage();
    const frApi = async (method, url, body) => fp.evaluate(async ([method, url, body]) => {
      const m = document.querySelector('meta[name="csrf-token"]');
      const headers = { 'Accept': 'application/json', 'Content-Type': 'application/json' };
      if (m) headers['X-CSRF-Token'] = m.content;
      const r = await fetch(url, { method, headers, body: body == null ? undefined : JSON.stringify(body) });
      return { status: r.status, data: await r.json().catch(() => null) };
    }, [method, url, body === undefined ? null : body]);
    await fp.goto(base + '/signup');
    await fp.fill('#username', 'salle' + n);
    await fp.fill('#password', password);
    await Promise.all([fp.waitForURL(base + '/'), fp.click('#submit')]);
    check(await fp.getAttribute('html', 'lang') === 'fr', 'the French browser gets French pages');
    const fr = (await frApi('POST', '/api/gyms', { name: 'Salle de bloc ' + n })).data.id;
    const frList = 'Réf,Nom,Cotation,Secteur,Couleur,Ouvreur\n' +
      'F1,Dalle jaune,6a,Mur Est,jaune,Élodie Garçon\nF2,Toit noir,7b,Mur Est,noir,Élodie Garçon\n';
    await fp.goto(base + '/gyms/' + fr + '/import');
    check(await fp.getAttribute('html', 'lang') === 'fr', 'the import page answers in French');
    await fp.fill('#import-data', frList);
    await fp.click('#import-read');
    await fp.waitForSelector('#import-preview:not([hidden])');
    const frMapped = await fp.$$eval('.import-map', (ss) => ss.map((s) => s.dataset.field + '=' + s.value).join(','));
    check(['id=Réf', 'name=Nom', 'grade=Cotation', 'wall=Secteur', 'colour=Couleur', 'setters=Ouvreur']
      .every((m) => frMapped.includes(m)), 'the columns are prefilled from the French header (' + frMapped + ')');
    const frSummary = await fp.textContent('#import-summary');
    check(/^2\D/.test(frSummary), 'the French list previews 2 new (' + frSummary + ')');
    await fp.screenshot({ path: path.join(out, '94-import-fr.png'), fullPage: true });
    await fp.click('#import-confirm');
    await fp.waitForSelector('#import-done.ok');
    const frRoutes = (await frApi('GET', '/api/routes?gym=' + fr + '&sort=name')).data.routes;
    check(frRoutes.map((r) => r.name + ':' + r.grade + ':' + r.colour).join(',') ===
      'Dalle jaune:6a:jaune,Toit noir:7b:noir', 'the French list is imported (' +
      frRoutes.map((r) => r.name).join(',') + ')');
    const again = await frApi('POST', '/api/gyms/' + fr + '/import', { format: 'csv', data: frList, confirm: true });
    check(again.status === 201 && again.data.created === 0 && again.data.skipped === 2, 'importing it twice duplicates nothing');
  } finally {
    await browser.close();
  }
};
