// A private route's moves never reach a logged-out visitor through a
// variation: page, JSON, PDF, SVG, CSV export, route list, landscape, pick.
'use strict';
module.exports = async (t) => {
  const { page, base, check, api } = t;
  await page.goto(base + '/');
  const secret = 'name: Secret Project\n---\nR zanzibar crimp\nL zanzibar pinch\nR zanzibar jug\n';
  const rid = (await api('POST', '/api/routes', { crdl: secret, public: false })).data.id;
  const open = (await api('POST', '/api/routes', { crdl: 'name: Open Slab\n---\nL smear\nR edge\n', public: true })).data.id;
  const pub = await api('POST', '/api/variations', { routes: [open, rid], public: true });
  check(pub.status === 400 && !/var_ic|is_public/.test(pub.data.error), 'a public variation over a private route is refused (' + pub.data.error + ')');
  const v = await api('POST', '/api/variations', { routes: [open, rid] });
  check(v.status === 201, 'a variation of a private route is made');
  const id = v.data.id;
  const mine = await api('GET', '/api/variations/' + id);
  check(mine.data.public === false, 'it is private by default');
  // A second, anonymous browser context.
  const req = page.context().request;
  const cookies = await page.context().cookies();
  await page.context().clearCookies();
  const paths = ['/variations/' + id, '/api/variations/' + id, '/variations/' + id + '.pdf',
                 '/variations/' + id + '.pdf?paper=letter', '/variations/' + id + '.svg',
                 '/api/routes/' + rid, '/api/routes/' + rid + '.crdl', '/routes/' + rid, '/r/' + id,
                 '/api/export/routes.csv', '/api/export/moves.csv', '/api/routes?q=zanzibar', '/?q=zanzibar',
                 '/vary?routes=' + id, '/api/landscape?routes=' + id + '&grid=5',
                 '/api/pick?routes=' + id + '&grid=5&count=1'];
  let leaks = [];
  for (const p of paths) {
    const r = await req.get(base + p, { maxRedirects: 0 });
    // (the search box echoes the query itself: that is the visitor's own text)
    const body = (await r.body()).toString('latin1').replace(/value="zanzibar"/g, '');
    if (/zanzibar|Secret Project/.test(body)) leaks.push(p);
    if (p.startsWith('/api/landscape') || p.startsWith('/api/pick')) {
      if (r.status() !== 404) leaks.push(p + ' (' + r.status() + ')');
    }
  }
  check(leaks.length === 0, 'logged out, no path shows the private moves (' + paths.length + ' paths; leaks: ' + leaks.join(', ') + ')');
  await page.context().addCookies(cookies);
};
