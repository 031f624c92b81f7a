// The climbers' pages: route feedback (/r/{id}), study responses (/s/{id})
// and the study editor (/studies/new, /studies/{id}/edit). Every form is
// sent as JSON (the server refuses other bodies); docs/web.md lists the API.
'use strict';
(function () {
  // Issue 32: the page's messages in its language (src/web/script_messages.cc), by their
  // English text; the server's refusals in it too ("message" beside the English "error").
  const MSG = {};
  for (const el of document.querySelectorAll('script.sb-messages')) {
    try { Object.assign(MSG, JSON.parse(el.textContent)); } catch (e) { /* English */ }
  }
  const tr = (s, ...args) => (MSG[s] || s).replace(/\{(\d)\}/g, (m, i) => (args[i - 1] !== undefined ? String(args[i - 1]) : m));
  // A count's message by the page language's plural rule: the block holds its forms for 1,
  // for many and for 0 (French says "0 voie", German "0 Routen").
  const trn = (one, many, n, ...args) => {
    const f = MSG[one];
    const s = Array.isArray(f) ? f[n === 1 ? 0 : n === 0 ? 2 : 1] : (n === 1 ? one : many);
    return tr(s, ...args);
  };
  const errorOf = (r) => (r.data && (r.data.message || r.data.error)) || tr('error {1}', r.status);
  const csrf = () => {
    const m = document.querySelector('meta[name="csrf-token"]');
    return m ? m.content : '';
  };

  async function send(method, url, body) {
    const headers = { 'Content-Type': 'application/json' };
    if (csrf()) headers['X-CSRF-Token'] = csrf();
    const res = await fetch(url, { method, headers, body: JSON.stringify(body),
                                   credentials: 'same-origin' });
    let data = {};
    try { data = await res.json(); } catch (e) { /* empty body */ }
    return { ok: res.ok, status: res.status, data };
  }

  function say(el, text, ok) {
    el.textContent = text;
    el.className = 'msg ' + (ok ? 'ok' : 'bad');
  }

  // The checked value of a radio group as an integer, or null.
  function radio(form, name) {
    const el = form.querySelector('input[name="' + name + '"]:checked');
    return el ? parseInt(el.value, 10) : null;
  }

  function intOrNull(v) { return v === '' || v == null ? null : parseInt(v, 10); }

  // ---- /r/{id} ---------------------------------------------------------------
  const fb = document.getElementById('feedback-form');
  if (fb) {
    fb.addEventListener('submit', async (ev) => {
      ev.preventDefault();
      const n = parseInt(fb.dataset.items, 10);
      const answers = [];
      for (let i = 0; i < n; i++) answers.push(radio(fb, 'q' + i));
      const msg = document.getElementById('feedback-msg');
      const r = await send('POST', '/api/r/' + fb.dataset.route + '/feedback', {
        answers,
        felt_grade: document.getElementById('felt-grade').value,
        comment: document.getElementById('comment').value,
      });
      if (r.ok) {
        say(msg, tr('Thank you! Saved. You can change your answers any time.'), true);
        document.getElementById('feedback-submit').textContent = tr('Save changes');
      } else {
        say(msg, errorOf(r), false);
      }
    });
  }

  // ---- /s/{id} ---------------------------------------------------------------
  const sr = document.getElementById('study-response');
  if (sr) {
    sr.addEventListener('submit', async (ev) => {
      ev.preventDefault();
      const n = parseInt(sr.dataset.items, 10);
      const routes = [];
      for (const sec of sr.querySelectorAll('section.study-route')) {
        const k = sec.dataset.label;
        const answers = [];
        for (let i = 0; i < n; i++) answers.push(radio(sec, 'r' + k + 'q' + i));
        const rank = sec.querySelector('select.rank');
        const order = sec.querySelector('select.order');
        routes.push({ answers, rank: rank ? intOrNull(rank.value) : null,
                      order: order ? intOrNull(order.value) : null });
      }
      const demographics = {};
      for (const el of sr.querySelectorAll('input.demo')) {
        if (el.value.trim() !== '') demographics[el.dataset.key] = el.value.trim();
      }
      const msg = document.getElementById('study-msg');
      const r = await send('POST', '/api/s/' + sr.dataset.id + '/responses',
                           { routes, demographics });
      if (r.ok) {
        say(msg, tr('Thank you! Your answers are saved.'), true);
        document.getElementById('study-submit').disabled = true;
      } else {
        say(msg, errorOf(r), false);
      }
    });
  }

  // ---- /studies/new and /studies/{id}/edit ------------------------------------
  const sf = document.getElementById('study-form');
  if (sf) {
    // Routes are labelled in the order they are ticked.
    let order = [...sf.querySelectorAll('input.study-route[data-pos]')]
      .sort((a, b) => a.dataset.pos - b.dataset.pos).map((el) => el.value);
    const list = document.getElementById('study-order');
    const names = {};
    const nameOf = (el) => el.parentElement.textContent.trim();
    for (const el of sf.querySelectorAll('input.study-route')) names[el.value] = nameOf(el);
    const show = () => {
      if (!list) return;
      list.textContent = '';
      order.forEach((id) => {
        const li = document.createElement('li');
        li.textContent = names[id];
        list.appendChild(li);
      });
    };
    // Any number of routes (issue 23): one delegated handler, and the search
    // box and "More routes" fetch pages of /api/routes into the list.
    const picks = sf.querySelector('.route-picks');
    if (picks) {
      picks.addEventListener('change', (ev) => {
        const el = ev.target.closest('input.study-route');
        if (!el) return;
        names[el.value] = nameOf(el);
        order = order.filter((id) => id !== el.value);
        if (el.checked) order.push(el.value);
        show();
      });
      const gyms = JSON.parse(picks.dataset.gyms || '{}');
      const find = document.getElementById('study-find');
      const more = document.getElementById('study-more');
      const found = document.getElementById('study-found');
      let offset = parseInt(picks.dataset.offset || '0', 10), seq = 0, timer = null;
      const label = (r) => {
        const l = document.createElement('label');
        l.className = 'check';
        const box = document.createElement('input');
        box.type = 'checkbox'; box.className = 'study-route'; box.value = String(r.id);
        l.append(box, ' ' + r.name);
        if (r.is_variation) {
          const t = document.createElement('span'); t.className = 'tag'; t.textContent = tr('variation');
          l.append(' ', t);
        }
        const g = document.createElement('small'); g.textContent = r.grade || '';
        const where = [r.gym != null ? gyms[String(r.gym)] : '', r.wall_name || r.wall,
                       r.setter || r.owner, r.set_on || (r.created_at || '').slice(0, 10)]
          .filter((x) => x);
        const w = document.createElement('small'); w.className = 'where';
        w.textContent = where.join(' · ');
        l.append(' ', g, ' ', w);
        return l;
      };
      const load = async (again) => {
        const mine = ++seq;
        const q = new URLSearchParams({ limit: '50', offset: String(again ? offset : 0) });
        if (find.value.trim()) q.set('q', find.value.trim());
        const res = await fetch('/api/routes?' + q.toString(), { credentials: 'same-origin' });
        if (mine !== seq || !res.ok) return;
        const data = await res.json();
        if (!again) {
          // Keep the chosen routes; replace the rest with the results.
          for (const el of [...picks.querySelectorAll('input.study-route')]) {
            if (!el.checked) el.parentElement.remove();
          }
          offset = 0;
        }
        const present = new Set([...picks.querySelectorAll('input.study-route')].map((el) => el.value));
        for (const r of data.routes) if (!present.has(String(r.id))) picks.appendChild(label(r));
        offset += data.routes.length;
        found.textContent = trn('{1} route', '{1} routes', data.total, data.total);
        more.hidden = offset >= data.total;
      };
      find.addEventListener('input', () => { clearTimeout(timer); timer = setTimeout(() => load(false), 200); });
      find.addEventListener('keydown', (ev) => { if (ev.key === 'Enter') { ev.preventDefault(); load(false); } });  // i18n: a key's name
      more.addEventListener('click', () => load(true));
    }
    show();
    sf.addEventListener('submit', async (ev) => {
      ev.preventDefault();
      const msg = document.getElementById('study-msg');
      const body = { name: document.getElementById('study-name').value };
      if (list) {
        body.routes = order.map((id) => parseInt(id, 10));
        const choice = sf.querySelector('input[name="instrument"]:checked').value;
        if (choice === 'file') {
          const f = document.getElementById('instrument-file').files[0];
          if (!f) { say(msg, tr('instrument: choose a file'), false); return; }
          body.instrument = { file: f.name, json: await f.text() };
        } else if (choice !== 'keep') {
          body.instrument = choice;
        }
        body.demographics = document.getElementById('ask-demographics').checked;
        body.rank = document.getElementById('ask-rank').checked;
        body.order = document.getElementById('ask-order').checked;
      }
      const open = document.getElementById('study-open');
      if (open) body.open = open.checked;
      const id = sf.dataset.id;
      const r = id ? await send('PUT', '/api/studies/' + id, body)
                   : await send('POST', '/api/studies', body);
      if (r.ok) {
        window.location.href = r.data.url;
      } else {
        say(msg, errorOf(r), false);
      }
    });
  }
  // ---- /studies/{id}: held responses (the burst rule, issue 23) --------------
  const heldResponses = document.getElementById('held-responses');
  if (heldResponses) {
    const decide = async (li, what) => {
      const r = await send('POST', '/api/studies/' + heldResponses.dataset.study + '/responses/' +
                                   li.dataset.response + '/' + what, {});
      if (r.ok) {
        li.textContent = what === 'accept' ? tr('Accepted (reload to see the numbers).') : tr('Discarded.');
        li.className = 'decided';
      }
      return r.ok;
    };
    heldResponses.addEventListener('click', async (ev) => {
      const b = ev.target;
      if (!(b instanceof HTMLButtonElement)) return;
      if (b.id === 'accept-all-held') {
        // One response after another, as the buttons do; stops at the first refusal.
        b.disabled = true;
        for (const li of heldResponses.querySelectorAll('li.held-response')) {
          if (!(await decide(li, 'accept'))) break;
        }
        b.disabled = false;
        return;
      }
      const li = b.closest('.held-response');
      if (!li) return;
      await decide(li, b.classList.contains('response-accept') ? 'accept' : 'discard');
    });
  }
})();
