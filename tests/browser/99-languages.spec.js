// The UI's languages (issue 32): an account set to German sees German pages (html lang, labels,
// dates as 28.11.2026) and ticks a route on a phone in German; a browser asking for French
// (Accept-Language) sees French pages without an account, and a tag sheet printed from it is in
// French (pdftotext: "Ouverte par", "jaune"); a gym's default language is set over the API and
// on the gym page, whose dashboard and setting day a German head setter sees in German; the
// scripts and the app's sentences too: a wall's gap lines, the editor's readings and a refused
// grade at its field in German, the tick form's script in French; a variation's card (page and
// PDF) in German, and a setting-day slot's reasons in French (the app's messages by id).
'use strict';
const fs = require('fs');
const path = require('path');
const { execFileSync } = require('child_process');

module.exports = async (t) => {
  const { page, base, check, shot, api, out } = t;
  const n = Date.now() % 100000;
  const user = 'sprache' + n;
  const password = 'correct horse battery';
  const ctx = page.context();
  const lang = () => page.evaluate(() => document.documentElement.lang);
  const text = (sel) => page.textContent(sel);

  await ctx.clearCookies();
  await page.goto(base + '/signup');
  await page.fill('#username', user);
  await page.fill('#password', password);
  await Promise.all([page.waitForURL(base + '/'), page.click('#submit')]);
  const put = await api('PUT', '/api/account', { language: 'de' });
  check(put.status === 200 && put.data.language === 'de', 'the account is set to German (' + put.status + ')');

  // A gym (its default language French) with a route on its wall: colour "gelb", no moves.
  const gym = await api('POST', '/api/gyms', { name: 'Sprachhalle ' + n });
  const gput = await api('PUT', '/api/gyms/' + gym.data.id, { language: 'fr' });
  check(gput.status === 200 && gput.data.language === 'fr', 'PUT /api/gyms/{gym} sets the gym\'s language (' + gput.status + ')');
  const bad = await api('PUT', '/api/gyms/' + gym.data.id, { language: 'xx' });
  check(bad.status === 400 && /language/.test(bad.data.error), 'an unknown language is refused naming the field');
  const crdl = 'name: Gelbe Kante ' + n + '\ngrade: V3\ncolour: gelb\n---\n';
  const made = await api('POST', '/api/routes', { crdl, public: true, gym: gym.data.id, state: 'set' });
  check(made.status === 201, 'a route without moves is set (' + made.status + ')');
  const rid = made.data.id;

  // German, from the account: the route list, its dates, the account page.
  await page.goto(base + '/?q=' + encodeURIComponent('Gelbe Kante ' + n));
  check(await lang() === 'de', '<html lang="de"> for the German account');
  check((await text('h1')).trim() === 'Routen' && (await text('#logout')).includes('Abmelden'),
        'the route list says "Routen" and "Abmelden"');
  const added = await page.textContent('#route-list tbody tr td:last-child');
  check(/^\d{2}\.\d{2}\.\d{4}$/.test(added.trim()), 'the date is in the German format (' + added.trim() + ')');
  await page.goto(base + '/account');
  check((await text('h1')).includes('Dein Konto') && (await text('main')).includes('Passwort ändern'),
        'the account page is German');

  // A tick on a phone in German.
  await page.setViewportSize({ width: 390, height: 844 });
  await page.goto(base + '/r/' + rid);
  check(await lang() === 'de' && (await text('#tick-form h2')).includes('Abhaken'), '/r/{id} on the phone is German');
  await page.click('label.outcome:has(#outcome-send)');
  await page.fill('#tick-attempts', '3');
  await page.click('#tick-submit');
  await page.waitForFunction(() => document.getElementById('tick-msg').textContent !== '');
  const msg = await text('#tick-msg');
  check(msg.startsWith('Abgehakt: Durchstieg'), 'the tick is confirmed in German (' + msg + ')');
  await shot('99-tick-german');
  await page.goto(base + '/logbook');
  const day = await page.textContent('#ticks tr.tick td');
  check((await text('h1')).includes('Dein Logbuch') && /^\d{2}\.\d{2}\.\d{4}$/.test(day.trim()),
        'the logbook is German, its day ' + day.trim());
  await page.setViewportSize({ width: 1200, height: 900 });

  // The German head setter's gym page, dashboard and setting day are German too; the gym's
  // language is chosen on its page (the form sends PUT /api/gyms/{gym} {"language"}).
  const gp = base + '/gyms/' + gym.data.id;
  await page.goto(gp);
  check((await text('main')).includes('Wände') && (await text('#gym-language')).includes('Sprache der Halle'),
        'the gym page is German, with the gym-language form');
  await page.selectOption('#gym-language-select', 'de');
  await Promise.all([page.waitForNavigation(), page.click('#gym-language button[type="submit"]')]);
  check((await api('GET', '/api/gyms/' + gym.data.id)).data.language === 'de' &&
        await page.inputValue('#gym-language-select') === 'de', 'the form sets the gym\'s language');
  await shot('99-gym-german');
  await page.goto(gp + '/dashboard');
  check((await text('#dashboard-title')).includes('was hängt, was fehlt') && (await text('main')).includes('Grundriss'),
        'the dashboard is German (' + (await text('#dashboard-title')) + ')');
  await page.goto(gp + '/setting-day');
  check((await text('#day-title')).startsWith('Schraubtag') && (await text('#day-propose')).includes('Vorschlagen'),
        'the setting-day page is German');
  await shot('99-setting-day-german');

  // The scripts and the app's sentences in German too: a wall's grade targets give gap lines
  // in German; the route editor's readings of moves and a refused grade are German, the
  // field's name and the scale as typed.
  const wall = (await api('POST', '/api/gyms/' + gym.data.id + '/walls', { name: 'Höhle ' + n, scale: 'V' })).data.id;
  await page.goto(gp + '/dashboard');
  await page.click('#wall-' + wall + ' details summary');
  await page.fill('#targets-' + wall + ' input[name="grades"]', 'V3: 2, V5: 1');
  await Promise.all([page.waitForNavigation(), page.click('#targets-' + wall + ' button[type="submit"]')]);
  const gaps = (await text('#gaps-' + wall)).trim();
  check(gaps.includes('Wand Höhle ' + n + ': 2 × V3 fehlen, 1 × V5 fehlen'), 'the gap line is German (' + gaps + ')');
  await shot('99-dashboard-german');
  await page.goto(base + '/routes/' + rid + '/edit');
  await page.selectOption('#f-wall', String(wall));
  await page.fill('#f-grade', '6B+');
  await page.fill('#f-moves', 'R small crimp');
  await page.waitForFunction(() => document.querySelectorAll('#feedback li.fb-move').length === 1);
  check((await text('#feedback')).includes('rechte Hand'), 'the editor reads the move in German (' + (await text('#feedback')).trim() + ')');
  await page.click('#save');
  await page.waitForFunction(() => document.querySelector('.field-msg[data-for="grade"]').textContent !== '');
  const refused = await text('.field-msg[data-for="grade"]');
  check(refused.startsWith('grade: „6B+“ ist kein Grad der Skala „V“') && (await text('#save-msg')).includes('nicht gespeichert'),
        'a refused grade is German at its field (' + refused + ')');
  await shot('99-editor-german');

  // A variation's card in German (page and PDF): its annotations, summary and table heads.
  const movesOf = [['V3', 'R small crimp (crux)\nL small crimp\nR sidepull\nR match\nL gaston\nR crimp\nL jug finish\n'],
                   ['V4', 'L sloper\nR small crimp (crux)\nL heel hook\nR pinch\nL crimp\nR top out\n'],
                   ['V5', 'R jug\nL crimp\nR crimp\nL undercling\nR sloper\nL jug finish\n']];
  const inputs = [];
  for (const [i, [grade, moves]] of movesOf.entries()) {
    const r = await api('POST', '/api/routes', { crdl: 'name: Höhlenroute ' + n + '-' + i + '\ngrade: ' + grade +
                                                 '\n---\n' + moves, public: true, gym: gym.data.id, wall, state: 'set' });
    inputs.push(r.data.id);
  }
  const varied = await api('POST', '/api/variations', { routes: inputs.slice(0, 2), name: 'Karte ' + n, grade: 'V4',
                                                       colour: 'yellow', wall: 'Höhle' });
  check(varied.status === 201, 'a variation for the card (' + varied.status + ')');
  await page.goto(base + '/variations/' + varied.data.id);
  const summary = (await text('p.summary')).trim();
  check(/\d+ von \d+ Zügen geändert/.test(summary) && (await text('.card-facts')).includes('Grad V4'),
        'the card page is German (' + summary.slice(0, 80) + ')');
  // Issue 32: none of the card's English words (rows' notes, the setter's notes in detail, the
  // parameters line, the colour's name), whatever the variation drew.
  const cardText = (await text('#plan')) + ' ' + (await text('.plan-notes'));
  const english = ['(crux)', '(match?)', '(hand swapped)', 'Preset ', 'reference IC', 'Reproduce:', 'Summary:',
                   'Warning', 'mean estimate', 'yellow', 'Colour', 'moves changed', 'suggested:'];
  check(english.every(w => !cardText.includes(w)) && cardText.includes('Farbe gelb') &&
        cardText.includes('Nachmachen: strangebeta vary') && cardText.includes('Zusammenfassung:'),
        'the card has none of its English words (' + english.filter(w => cardText.includes(w)).join(', ') + ')');
  await shot('99-card-german');
  const cardPdf = await page.request.get(base + '/variations/' + varied.data.id + '.pdf');
  const cardFile = path.join(out, 'card-german.pdf');
  fs.writeFileSync(cardFile, await cardPdf.body());
  const cardWords = execFileSync('pdftotext', [cardFile, '-']).toString().replace(/\s+/g, ' ');
  check(cardPdf.status() === 200 && /Zügen geändert/.test(cardWords) && cardWords.includes('Grad V4') &&
        cardWords.includes('Scannen für Rückmeldung') && !cardWords.includes('moves changed') &&
        cardWords.includes('Farbe gelb') && !/Preset |reference IC|trajectories|\(crux\)|\(match\?\)/.test(cardWords),
        'the card PDF is German (' + cardWords.replace(/\s+/g, ' ').slice(0, 120) + ')');

  // A setting-day slot in French (the account's language): the candidates' reasons and the
  // predicted grade's basis are the app's messages, translated by their ids.
  await api('PUT', '/api/account', { language: 'fr' });
  const dayAhead = new Date(Date.now() + 30 * 864e5).toISOString().slice(0, 10);
  await page.goto(gp + '/setting-day?date=' + dayAhead + '&walls=' + wall);
  check(await lang() === 'fr' && (await page.$$('.day-candidate')).length >= 1, 'the setting day proposes in French');
  const why = await text('.day-candidate p.why');
  const details = await page.$$eval('.day-candidate ul.reasons li', (l) => l.map((e) => e.textContent).join(' | '));
  check(/mouvements? nouveaux? par rapport aux voies d'origine|rejetée/.test(details) &&
        !/new against its inputs|no warnings|bits per move/.test(details),
        'the reasons are French (' + details.slice(0, 140) + ')');
  check(!/any grade|any style|warning/.test(why), 'the why line is French (' + why.trim().slice(0, 100) + ')');
  await shot('99-setting-day-french');
  await api('PUT', '/api/account', { language: 'de' });
  await api('PUT', '/api/gyms/' + gym.data.id, { language: 'fr' });

  // French, from the browser's Accept-Language (no account).
  await ctx.clearCookies();
  await page.setExtraHTTPHeaders({ 'Accept-Language': 'fr-FR,fr;q=0.9,en;q=0.5' });
  try {
    await page.goto(base + '/login');
    check(await lang() === 'fr' && (await text('h1')).includes('Se connecter'), 'the log-in page is French');
    await page.goto(base + '/r/' + rid);
    check(await lang() === 'fr' && (await text('#tick-form h2')).includes('Cocher') &&
          (await text('#tick-submit')).includes('Enregistrer la croix'), '/r/{id} is French');
    await page.click('#tick-submit');
    await page.waitForFunction(() => document.getElementById('tick-msg').textContent !== '');
    const pick = await text('#tick-msg');
    check(pick.includes('Touchez d\'abord flash'), 'the tick form\'s script speaks French (' + pick + ')');
    await shot('99-route-french');
    const sheet = await page.request.get(base + '/tags.pdf?ids=' + rid,
                                         { headers: { 'Accept-Language': 'fr-FR,fr;q=0.9' } });
    const file = path.join(out, 'tags-french.pdf');
    fs.writeFileSync(file, await sheet.body());
    const words = execFileSync('pdftotext', [file, '-']).toString();
    check(sheet.status() === 200 && words.includes('Ouverte par') && words.includes('Ouverte le') &&
          words.includes('jaune'), 'the tag sheet is French (' + words.replace(/\s+/g, ' ').slice(0, 120) + ')');
  } finally {
    await page.setExtraHTTPHeaders({});
  }
  await page.goto(base + '/login');
  check(await lang() === 'en', 'without them the pages are English again');
};
