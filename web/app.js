// Strange Beta web app: the little bit of vanilla JS behind the server-rendered pages.
'use strict';

(function () {
  const $ = (sel) => document.querySelector(sel);
  const csrf = () => {
    const m = document.querySelector('meta[name="csrf-token"]');
    return m ? m.content : '';
  };

  // Calls the JSON API; resolves to {status, data}.
  async function api(method, url, body) {
    const headers = { 'Accept': 'application/json' };
    if (body !== undefined) headers['Content-Type'] = 'application/json';
    if (csrf()) headers['X-CSRF-Token'] = csrf();
    const res = await fetch(url, {
      method, headers, credentials: 'same-origin',
      body: body === undefined ? undefined : JSON.stringify(body),
    });
    let data = null;
    const text = await res.text();
    try { data = text ? JSON.parse(text) : null; } catch (e) { data = { error: text }; }
    return { status: res.status, data };
  }

  function say(el, text, ok) {
    if (!el) return;
    el.textContent = text;
    el.classList.toggle('ok', !!ok);
    el.classList.toggle('bad', !ok);
  }

  // ---- accounts ----
  async function login(username, password) {
    return api('POST', '/api/sessions', { username, password });
  }

  const signup = $('#signup-form');
  if (signup) {
    signup.addEventListener('submit', async (ev) => {
      ev.preventDefault();
      const u = $('#username').value, p = $('#password').value;
      const r = await api('POST', '/api/users', { username: u, password: p });
      if (r.status !== 201) return say($('#form-msg'), (r.data && r.data.error) || 'Sign-up failed');
      const l = await login(u, p);
      if (l.status !== 200) return say($('#form-msg'), 'Account made; please log in.');
      location.href = '/';
    });
  }
  const loginForm = $('#login-form');
  if (loginForm) {
    loginForm.addEventListener('submit', async (ev) => {
      ev.preventDefault();
      const r = await login($('#username').value, $('#password').value);
      if (r.status !== 200) return say($('#form-msg'), (r.data && r.data.error) || 'Log-in failed');
      location.href = '/';
    });
  }
  const logout = $('#logout');
  if (logout) {
    logout.addEventListener('click', async () => {
      await api('DELETE', '/api/sessions');
      location.href = '/';
    });
  }

  // ---- route editor with live feedback ----
  const editor = $('#editor');
  if (editor) {
    const ta = $('#crdl');
    const list = $('#feedback');
    let timer = null, seq = 0;
    async function refresh() {
      const mine = ++seq;
      const r = await api('POST', '/api/feedback', { crdl: ta.value });
      if (mine !== seq || r.status !== 200) return;
      list.innerHTML = '';
      for (const l of r.data.lines) {
        if (l.kind === 'blank') continue;
        const li = document.createElement('li');
        li.value = l.line;
        li.className = 'fb-' + l.kind + (l.kind === 'move' && r.data.language && !l.parsed ? ' unparsed' : '');
        const src = document.createElement('code');
        src.textContent = l.text;
        li.appendChild(src);
        const note = document.createElement('span');
        note.className = 'reading';
        if (l.kind === 'move') {
          note.textContent = (l.hand === 'L' ? 'left hand' : 'right hand') + (l.crux ? ' · crux' : '') +
            ' · ' + (r.data.language ? (l.parsed ? l.reading : 'not understood by the grammar') : l.move);
        } else if (l.kind === 'error') {
          note.textContent = l.error || 'not a move: start with L or R';
        } else if (l.kind === 'meta') {
          note.textContent = 'metadata';
        } else if (l.kind === 'separator') {
          note.textContent = 'moves follow';
        } else if (l.kind === 'comment') {
          note.textContent = 'comment';
        } else {
          note.textContent = 'description';
        }
        li.appendChild(note);
        list.appendChild(li);
      }
      const msg = $('#save-msg');
      if (!r.data.ok && r.data.error) {
        say(msg, 'line ' + r.data.error.line + ': ' + r.data.error.message);
      } else {
        say(msg, r.data.moves + ' moves', true);
      }
    }
    ta.addEventListener('input', () => { clearTimeout(timer); timer = setTimeout(refresh, 200); });
    refresh();
    $('#save').addEventListener('click', async () => {
      const id = editor.dataset.routeId;
      const body = { crdl: ta.value, public: $('#public').checked };
      const r = id ? await api('PUT', '/api/routes/' + id, body) : await api('POST', '/api/routes', body);
      if (r.status === 200 || r.status === 201) {
        location.href = '/routes/' + (id || r.data.id);
      } else {
        say($('#save-msg'), (r.data && r.data.error) || ('error ' + r.status));
      }
    });
  }

  const del = $('#delete-route');
  if (del) {
    del.addEventListener('click', async () => {
      if (!confirm('Delete this route?')) return;
      const r = await api('DELETE', '/api/routes/' + del.dataset.id);
      if (r.status === 204) location.href = '/';
    });
  }

  // ---- vary page ----
  const varyForm = $('#vary-form');
  if (varyForm) {
    const canvas = $('#icmap');
    let map = null;      // the last slice
    let picked = null;   // [i, j] grid cell
    const selectedRoutes = () =>
      Array.from(document.querySelectorAll('input[name=route]:checked')).map((c) => Number(c.value));
    function params() {
      const p = { preset: $('#preset').value };
      for (const k of ['system', 'integrator', 'mapping']) if ($('#' + k).value) p[k] = $('#' + k).value;
      for (const k of ['params', 'ref_ic', 'var_ic', 'mask']) if ($('#' + k).value.trim()) p[k] = $('#' + k).value.trim();
      for (const k of ['step']) if ($('#' + k).value.trim()) p[k] = Number($('#' + k).value);
      for (const k of ['skip', 'max_repeat']) if ($('#' + k).value.trim()) p[k] = parseInt($('#' + k).value, 10);
      return p;
    }
    function colour(t) {  // 0..1 -> dark blue .. yellow
      const stops = [[13, 8, 135], [126, 3, 168], [204, 71, 120], [248, 149, 64], [240, 249, 33]];
      const x = Math.max(0, Math.min(1, t)) * (stops.length - 1);
      const i = Math.min(stops.length - 2, Math.floor(x)), f = x - i;
      const c = stops[i].map((v, k) => Math.round(v + f * (stops[i + 1][k] - v)));
      return 'rgb(' + c.join(',') + ')';
    }
    function draw() {
      if (!canvas || !map) return;
      const ctx = canvas.getContext('2d');
      const n = map.grid, cell = canvas.width / n;
      const metric = $('#metric').value;
      const vals = map[metric];
      let max = 0;
      for (const v of vals) max = Math.max(max, v);
      for (let j = 0; j < n; j++) {
        for (let i = 0; i < n; i++) {
          ctx.fillStyle = colour(max ? vals[j * n + i] / max : 0);
          // y grows upwards
          ctx.fillRect(i * cell, canvas.height - (j + 1) * cell, Math.ceil(cell), Math.ceil(cell));
        }
      }
      // The reference IC at the centre.
      const c = Math.floor(n / 2);
      ctx.strokeStyle = '#fff';
      ctx.strokeRect(c * cell, canvas.height - (c + 1) * cell, cell, cell);
      if (picked) {
        ctx.strokeStyle = '#0f0';
        ctx.lineWidth = 2;
        ctx.strokeRect(picked[0] * cell - 2, canvas.height - (picked[1] + 1) * cell - 2, cell + 4, cell + 4);
        ctx.lineWidth = 1;
      }
      $('#map-info').textContent = metric + ' 0..' + (Math.round(max * 100) / 100) + ' over ' +
        map.length + ' moves; axes ' + 'xyz'[map.axes[0]] + ' (right), ' + 'xyz'[map.axes[1]] + ' (up)';
    }
    async function loadMap() {
      if (!canvas) return;
      const p = params();
      delete p.var_ic;
      const ids = selectedRoutes();
      const q = new URLSearchParams({ params: JSON.stringify(p), plane: 'xy', grid: '41', spacing: '0.2' });
      if (ids.length) q.set('routes', ids.join(','));
      $('#map-info').textContent = 'computing…';
      const r = await api('GET', '/api/landscape?' + q.toString());
      if (r.status !== 200) { $('#map-info').textContent = (r.data && r.data.error) || 'no map'; return; }
      map = r.data;
      canvas.dataset.ready = '1';
      draw();
    }
    if (canvas) {
      canvas.addEventListener('click', (ev) => {
        if (!map) return;
        const rect = canvas.getBoundingClientRect();
        const n = map.grid;
        const i = Math.min(n - 1, Math.max(0, Math.floor((ev.clientX - rect.left) / rect.width * n)));
        const j = Math.min(n - 1, Math.max(0, Math.floor((rect.bottom - ev.clientY) / rect.height * n)));
        picked = [i, j];
        const ic = map.center.slice();
        ic[map.axes[0]] = map.x[i];
        ic[map.axes[1]] = map.y[j];
        const round = (v) => Math.round(v * 1e6) / 1e6;
        $('#var_ic').value = ic.map(round).join(',');
        $('#advanced').open = true;
        const k = j * n + i;
        $('#map-info').textContent = 'variation IC ' + $('#var_ic').value + ': effect ' + map.effect[k] +
          ' of ' + map.length + ' moves, change ' + map.change[k];
        draw();
      });
      $('#pick').addEventListener('click', async () => {
        const p = params();
        delete p.var_ic;
        const ids = selectedRoutes();
        const q = new URLSearchParams({ params: JSON.stringify(p), plane: 'xy', grid: '41', spacing: '0.2', count: '5' });
        if (ids.length) q.set('routes', ids.join(','));
        if ($('#pick-effect').value) q.set('effect', $('#pick-effect').value);
        if ($('#pick-change').value) q.set('change', $('#pick-change').value);
        const r = await api('GET', '/api/pick?' + q.toString());
        const list = $('#candidates');
        list.innerHTML = '';
        if (r.status !== 200) { list.textContent = (r.data && r.data.error) || 'no candidates'; return; }
        for (const c of r.data.candidates) {
          const li = document.createElement('li');
          const b = document.createElement('button');
          b.type = 'button';
          b.className = 'link-dark';
          const round = (v) => Math.round(v * 1e6) / 1e6;
          b.textContent = c.ic.map(round).join(', ') + ' — effect ' + c.effect + ', change ' + c.change;
          b.addEventListener('click', () => {
            $('#var_ic').value = c.ic.map(round).join(',');
            $('#advanced').open = true;
            if (map) picked = [c.index % map.grid, Math.floor(c.index / map.grid)];
            draw();
          });
          li.appendChild(b);
          list.appendChild(li);
        }
      });
      $('#metric').addEventListener('change', draw);
      $('#map-refresh').addEventListener('click', loadMap);
      for (const c of document.querySelectorAll('input[name=route]')) c.addEventListener('change', loadMap);
      $('#preset').addEventListener('change', loadMap);
      loadMap();
    }
    varyForm.addEventListener('submit', async (ev) => {
      ev.preventDefault();
      const ids = selectedRoutes();
      if (!ids.length) return say($('#vary-msg'), 'Choose at least one route.');
      const body = Object.assign(params(), { routes: ids, smooth: $('#smooth').checked });
      say($('#vary-msg'), 'Generating…', true);
      const r = await api('POST', '/api/variations', body);
      if (r.status === 201) { location.href = '/variations/' + r.data.id; return; }
      say($('#vary-msg'), (r.data && r.data.error) || ('error ' + r.status));
    });
  }

  // ---- plan page ----
  const printBtn = $('#print');
  if (printBtn) printBtn.addEventListener('click', () => window.print());

  // ---- import page ----
  const importCrdl = $('#import-crdl');
  if (importCrdl) {
    importCrdl.addEventListener('click', async () => {
      const files = $('#crdl-files').files;
      let ok = 0; const errors = [];
      for (const f of files) {
        const r = await api('POST', '/api/routes', { crdl: await f.text() });
        if (r.status === 201) ok++; else errors.push(f.name + ': ' + ((r.data && r.data.error) || r.status));
      }
      say($('#crdl-msg'), ok + ' imported' + (errors.length ? '; ' + errors.join('; ') : ''), !errors.length);
    });
  }
  const importCsv = $('#import-csv');
  if (importCsv) {
    importCsv.addEventListener('click', async () => {
      const rf = $('#routes-csv').files[0], mf = $('#moves-csv').files[0];
      if (!rf || !mf) return say($('#csv-msg'), 'Choose both files.');
      const r = await api('POST', '/api/import/csv', { routes_csv: await rf.text(), moves_csv: await mf.text() });
      if (r.status === 201) say($('#csv-msg'), r.data.imported + ' routes imported, ' + r.data.skipped.length + ' notes', true);
      else say($('#csv-msg'), (r.data && r.data.error) || ('error ' + r.status));
    });
  }
})();
