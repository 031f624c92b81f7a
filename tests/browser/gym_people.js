// What the gym specs share (93-cycle-story, 95-cycle-gaps; not a *.spec.js, so run.js does not
// load it): a head setter, a setter, a climber and another gym's head setter signed up and logged
// in once outside the page (password hashing is the slow part), the browser switched to one of
// them, a form submitted and its page waited for, confirmations accepted, and a gym made
// through the JSON API with its members, walls and circuits.
'use strict';

const password = 'correct horse battery';

// The four people of a spec, named `prefix` + role + `n` (e.g. 'gphead123'), signed up and
// logged in. Returns their names and the helpers bound to `t.page`; call done() at the end
// (stops accepting confirmations: the next spec may want its own handler).
async function gymPeople(t, prefix, n) {
  const { page, base } = t;
  const names = { head: prefix + 'head' + n, setter: prefix + 'set' + n,
                  climber: prefix + 'climb' + n, rival: prefix + 'rival' + n };
  const sessions = {};
  async function account(user) {
    const post = (path) => fetch(base + path, { method: 'POST', headers: { 'Content-Type': 'application/json' },
                                                body: JSON.stringify({ username: user, password }) });
    await post('/api/users');
    const r = await post('/api/sessions');
    sessions[user] = (r.headers.get('set-cookie') || '').split(';')[0].split('=')[1];
  }
  // Confirmations accepted (another spec's handler may have accepted one already).
  const accept = (d) => d.accept().catch(() => {});
  page.on('dialog', accept);
  await Promise.all(Object.values(names).map(account));
  return {
    ...names,
    // The browser as `user` (null: logged out), at the home page.
    as: async (user) => {
      await page.context().clearCookies();
      if (user) await page.context().addCookies([{ name: 'sb_session', value: sessions[user], url: base }]);
      await page.goto(base + '/');
    },
    // Submits the form `sel` (on `p`, the spec's page unless given) and waits for the next page.
    submit: async (sel, p = page) => {
      await Promise.all([p.waitForNavigation(), p.click(sel + ' button[type="submit"]')]);
    },
    done: () => page.off('dialog', accept),
  };
}

// A gym made by the browser's user through the API: `members` { username: role }, `walls`
// [name], `circuits` [{ colour, grade_from, grade_to }], made in that order. Returns the ids:
// { id, walls: [id], circuits: [id] }.
async function makeGym(api, name, { members = {}, walls = [], circuits = [] } = {}) {
  const id = (await api('POST', '/api/gyms', { name })).data.id;
  for (const [username, role] of Object.entries(members)) {
    await api('POST', '/api/gyms/' + id + '/members', { username, role });
  }
  const made = { id, walls: [], circuits: [] };
  for (const w of walls) made.walls.push((await api('POST', '/api/gyms/' + id + '/walls', { name: w })).data.id);
  for (const c of circuits) made.circuits.push((await api('POST', '/api/gyms/' + id + '/circuits', c)).data.id);
  return made;
}

module.exports = { gymPeople, makeGym };
