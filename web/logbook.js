// The climbers' logbook (issue 23): the tick form of /r/{id} (outcome in one
// tap, "Log tick" the second; stars, felt grade and comment optional) and the
// setters' accept/discard of held ticks. JSON API in docs/web.md ("Logbook").
'use strict';
(function () {
  // Issue 32: the page's messages in its language (src/web/script_messages.cc), by their
  // English text; the server's refusals in it too ("message" beside the English "error").
  const MSG = {};
  for (const el of document.querySelectorAll('script.sb-messages')) {
    try { Object.assign(MSG, JSON.parse(el.textContent)); } catch (e) { /* English */ }
  }
  const tr = (s, ...args) => (MSG[s] || s).replace(/\{(\d)\}/g, (m, i) => (args[i - 1] !== undefined ? String(args[i - 1]) : m));
  const errorOf = (r) => (r.data && (r.data.message || r.data.error)) || tr('error {1}', r.status);
  const csrf = () => {
    const m = document.querySelector('meta[name="csrf-token"]');
    return m ? m.content : '';
  };

  async function send(method, url, body) {
    const headers = { 'Content-Type': 'application/json' };
    if (csrf()) headers['X-CSRF-Token'] = csrf();
    const res = await fetch(url, { method, headers, body: JSON.stringify(body || {}),
                                   credentials: 'same-origin' });
    let data = {};
    try { data = await res.json(); } catch (e) { /* empty body */ }
    return { ok: res.ok, status: res.status, data };
  }

  function say(el, text, ok) {
    el.textContent = text;
    el.className = 'msg ' + (ok ? 'ok' : 'bad');
  }

  const form = document.getElementById('tick-form');
  if (form) {
    const tries = document.getElementById('attempts-field');
    const sync = () => {
      const o = form.querySelector('input[name="outcome"]:checked');
      tries.hidden = !o || o.value === 'flash';
    };
    form.querySelectorAll('input[name="outcome"]').forEach((r) => r.addEventListener('change', sync));
    sync();
    // Issue 32: the page's language — the server puts the translated
    // messages on the form (data-msg-*, "{1}" the outcome's label).
    const label = (o) => {
      const span = o.parentElement.querySelector('span');
      return span ? span.textContent : o.value;
    };
    form.addEventListener('submit', async (ev) => {
      ev.preventDefault();
      const msg = document.getElementById('tick-msg');
      const o = form.querySelector('input[name="outcome"]:checked');
      if (!o) { say(msg, tr('Tap flash, send or attempt first.'), false); return; }
      const body = { outcome: o.value };
      const a = document.getElementById('tick-attempts').value;
      if (o.value !== 'flash' && a !== '') body.attempts = parseInt(a, 10);
      const s = form.querySelector('input[name="stars"]:checked');
      if (s) body.stars = parseInt(s.value, 10);
      const felt = document.getElementById('tick-felt').value.trim();
      if (felt) body.felt_grade = felt;
      const c = document.getElementById('tick-comment').value.trim();
      if (c) body.comment = c;
      const r = await send('POST', '/api/routes/' + form.dataset.route + '/ticks', body);
      if (!r.ok) { say(msg, errorOf(r), false); return; }
      const done = r.data.edited ? tr('Tick updated: {1}', label(o)) : tr('Ticked: {1}', label(o));
      say(msg, done + (r.data.held ? ' ' + tr('(held for the setters to check)') : '') + '.',
          true);
      const g = r.data.ascent;
      const p = document.getElementById('ascent-ticks');
      if (g && g.fitted && p) {
        p.textContent = g.ticks;
        document.getElementById('ascent-value').textContent = g.grade;
        document.getElementById('ascent-interval').textContent =
            '(' + tr('80%: {1} to {2}', g.lo_grade, g.hi_grade) + ')';
      }
    });
  }

  const held = document.getElementById('held-ticks');
  if (held) {
    held.addEventListener('click', async (ev) => {
      const b = ev.target;
      if (!(b instanceof HTMLButtonElement)) return;
      const li = b.closest('.held-tick');
      const what = b.classList.contains('tick-accept') ? 'accept' : 'discard';
      const r = await send('POST', '/api/routes/' + held.dataset.route + '/ticks/' +
                                   li.dataset.tick + '/' + what, {});
      if (r.ok) {
        li.textContent = what === 'accept' ? tr('Accepted.') : tr('Discarded.');
        li.className = 'decided';
      }
    });
  }
})();
