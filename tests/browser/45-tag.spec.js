// The climber's tag (issue 21): a hand-entered route (not a variation) has a
// "Tag" link; the tag page prints to one A4 and one Letter page with the
// fields and a QR code that decodes to /r/{id}; the server's tag PDF and a
// sheet of tags (/tags.pdf?ids=...) do too.
'use strict';
const fs = require('fs');
const path = require('path');
const { execFileSync } = require('child_process');

function decode(t, pdf, stem) {
  execFileSync('pdftoppm', ['-png', '-r', '200', '-f', '1', '-l', '1', '-singlefile', pdf, path.join(t.out, stem)]);
  try {
    return execFileSync('zbarimg', ['-q', '--raw', '-Sdatabar.disable', '-Sdatabar-exp.disable', path.join(t.out, stem + '.png')]).toString().trim();
  } catch (e) {
    return 'zbarimg failed: ' + e.message;
  }
}

module.exports = async (t) => {
  const { page, base, check, shot, api, out } = t;
  await page.goto(base + '/');
  if (!(await api('GET', '/api/session')).data.logged_in) {  // run alone (FILTER=45-tag)
    const user = 'tagger' + (Date.now() % 1000000);
    await api('POST', '/api/users', { username: user, password: 'password123' });
    await api('POST', '/api/sessions', { username: user, password: 'password123' });
    await page.goto(base + '/');
  }
  const crdl = 'name: Tag Test Arête \u{1F525}\ngrade: V5\ncolour: yellow\nwall: the cave\nsetter: Carol\n' +
               'date: 2026-11-26\n---\nR crimp\nL sloper\nR jug finish\n';
  const r = await api('POST', '/api/routes', { crdl, public: true });
  check(r.status === 201, 'a hand-entered route is stored (' + r.status + ')');
  const id = r.data.id;
  await page.goto(base + '/routes/' + id);
  await page.click('#tag-link');
  check(page.url().endsWith('/routes/' + id + '/tag'), 'the route page links to its tag');
  await shot('45-tag');
  const caption = page.locator('.tag-url');
  const box = await caption.boundingBox();
  const lineHeight = await caption.evaluate((e) => parseFloat(getComputedStyle(e).fontSize) * 1.6);
  check(box && box.height < lineHeight, 'the URL under the QR code is one line (' + (box && box.height) + ' px)');
  await page.emulateMedia({ media: 'print' });
  await shot('45-tag-print');
  for (const format of ['A4', 'Letter']) {
    const file = path.join(out, 'tag-print-' + format + '.pdf');
    const buf = await page.pdf({ path: file, format, printBackground: true });
    check(t.pdfPages(buf) === 1, 'the tag page prints on one ' + format + ' page (' + t.pdfPages(buf) + ')');
    const text = execFileSync('pdftotext', [file, '-']).toString();
    check(['Tag Test Arête', 'V5', 'yellow', 'Wall: the cave', 'Set by Carol', 'Set on 2026-11-26', '/r/' + id]
      .every((s) => text.includes(s)), 'the printed ' + format + ' tag has every field');
    const qr = decode(t, file, 'tag-print-' + format);
    check(qr.endsWith('/r/' + id), 'the printed ' + format + ' tag\'s QR code links to /r/' + id + ' (' + qr + ')');
  }
  await page.emulateMedia({ media: 'screen' });
  for (const [q, suffix] of [['', 'a4'], ['?paper=letter', 'letter']]) {
    const res = await page.request.get(base + '/routes/' + id + '/tag.pdf' + q);
    const body = await res.body();
    const file = path.join(out, 'tag-server-' + suffix + '.pdf');
    fs.writeFileSync(file, body);
    check(res.status() === 200 && t.pdfPages(body) === 1, 'server tag PDF (' + suffix + ') is one page');
    const qr = decode(t, file, 'tag-server-' + suffix);
    check(qr.endsWith('/r/' + id), 'the server tag\'s QR code (' + suffix + ') links to /r/' + id + ' (' + qr + ')');
  }
  const sheet = await page.request.get(base + '/tags.pdf?ids=' + Array(9).fill(id).join(','));
  check(sheet.status() === 200 && t.pdfPages(await sheet.body()) === 2, 'a sheet of 9 tags is two pages');
};
