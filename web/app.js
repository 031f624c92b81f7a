// Strange Beta web app: the little bit of vanilla JS behind the server-rendered pages.
'use strict';

(function () {
  const $ = (sel) => document.querySelector(sel);
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

  // Calls the JSON API; resolves to {status, data}.
  async function api(method, url, body) {
    const headers = { 'Accept': 'application/json' };  // i18n: HTTP headers
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

  // Error messages name form fields by their labels, not internal names.
  const LABELS = { var_ic: tr('Variation IC'), ref_ic: tr('Reference IC'), max_repeat: tr('Max repeat'),
    skip: tr('Skip'), step: tr('Step'), params: tr('System parameters'), mask: tr('Mask'), system: tr('System'),
    integrator: tr('Integrator'), mapping: tr('Mapping'), preset: tr('Preset'), routes: tr('Routes'),
    public: tr('Visibility'), keep_start: tr('Keep start'), keep_finish: tr('Keep finish'),
    crux_window: tr('Crux window'), alternate_hands: tr('Alternate hands'), match: tr('Match moves'),
    target_effect: tr('Target effect'), target_change: tr('Target change'),
    smooth_method: tr('Smoothing method'), effect: tr('Target effect'), change: tr('Target change') };
  // The IC search names constraints as options ("crux-window"): the same labels.
  const label = (k) => LABELS[k.replace(/-/g, '_')] || k;
  function humane(msg) {
    msg = String(msg);
    // "no variation IC within 100 grid steps (...) of (...) meets every constraint: crux-window
    // could not be met (failed most often; ...)": say it as a setter would.
    const m = msg.match(/^no variation IC within (\d+) grid steps .* meets every constraint: ([a-z-]+) could not be met/);
    if (m) {
      return tr('No variation IC within {1} grid steps of your variation IC meets every constraint: "{2}" could not be met. Try a wider crux window, fewer constraints or another variation IC.',
        m[1], label(m[2]));
    }
    return msg.replace(/^([a-z_]+):/, (x, k) => label(k) + ':');
  }

  function say(el, text, ok) {
    if (!el) return;
    el.textContent = text;
    el.classList.toggle('ok', !!ok);
    el.classList.toggle('bad', !ok);
  }

  // Issue 31: the gym this page writes to (the header's switcher; none: personal or asked).
  const pageGym = () => {
    const m = document.querySelector('meta[name="sb-gym"]');
    return m ? Number(m.content) : undefined;
  };
  const gymSwitch = $('#gym-switch');
  const setGymCookie = (id) => {
    document.cookie = 'sb_gym=' + id + '; path=/; max-age=31536000; SameSite=Lax';
  };
  // A page of a gym (its pages, a wall, a route of it) is that gym's: the header shows it,
  // the page writes to it, and the next pages (New route, Import) stay with it.
  const ownerGym = document.querySelector('meta[name="sb-page-gym"]');
  if (ownerGym) setGymCookie(ownerGym.content);
  if (gymSwitch) {
    gymSwitch.addEventListener('change', () => {
      const id = gymSwitch.value;
      setGymCookie(id);
      // A gym's page goes to the chosen gym's same page (a setting day keeps its date); a
      // wall's or a route's to the chosen gym's page; other pages stay, with ?gym=.
      if (ownerGym || /^\/(gyms\/\d+|walls\/\d+)/.test(location.pathname)) {
        const rest = (location.pathname.match(/^\/gyms\/\d+((\/[a-z-]+)*)/) || [])[1] || '';
        const date = rest ? new URL(location.href).searchParams.get('date') : null;
        location.href = '/gyms/' + id + rest + (date ? '?date=' + encodeURIComponent(date) : '');
        return;
      }
      const u = new URL(location.href);
      u.searchParams.set('gym', id);
      location.href = u.toString();
    });
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
      if (r.status !== 201) return say($('#form-msg'), (r.data && (r.data.message || r.data.error)) || tr('Sign-up failed'));
      const l = await login(u, p);
      if (l.status !== 200) return say($('#form-msg'), tr('Account made; please log in.'));
      location.href = '/';
    });
  }
  const loginForm = $('#login-form');
  if (loginForm) {
    loginForm.addEventListener('submit', async (ev) => {
      ev.preventDefault();
      const r = await login($('#username').value, $('#password').value);
      if (r.status !== 200) return say($('#form-msg'), (r.data && (r.data.message || r.data.error)) || tr('Log-in failed'));
      // Back to the page that sent here (issue 31: a gym page), on this site only.
      const next = new URLSearchParams(location.search).get('next') || '';
      // Its query too (?date=...): letters, digits and the URL's own punctuation only.
      location.href = /^\/[A-Za-z0-9/_.-]*(\?[A-Za-z0-9_.~%=&+,-]*)?$/.test(next) && !next.startsWith('//') ? next : '/';
    });
  }
  const logout = $('#logout');
  if (logout) {
    logout.addEventListener('click', async () => {
      await api('DELETE', '/api/sessions');
      location.href = '/';
    });
  }

  // ---- route editor: the form and the CRDL text (issue 31), live feedback ----
  const editor = $('#editor');
  if (editor) {
    const ta = $('#crdl');
    const list = $('#feedback');
    const inGym = !!editor.dataset.gym;
    const routeId = editor.dataset.routeId;
    const KEY = /^([A-Za-z0-9_-]+):(?:[ \t]+(.*)|[ \t]*)$/;
    // Header keys the form owns; the others stay as they are (kept in `extra`).
    const OWN = inGym ? ['name', 'grade', 'colour', 'color', 'setter', 'state', 'set', 'date', 'wall']
                      : ['name', 'grade', 'colour', 'color', 'setter'];
    let extra = [];   // header lines of the text the form does not show, in order
    let lineMap = []; // what each line of the last text built from the form came from
    let view = 'form';
    const val = (sel) => ($(sel) ? $(sel).value.trim() : '');
    const ISO = /^\d{4}-\d{2}-\d{2}$/;

    function splitText(text) {
      const lines = text.replace(/\r/g, '').split('\n');
      const sep = lines.findIndex((l) => l.trim() === '---');
      return { header: sep < 0 ? lines : lines.slice(0, sep), moves: sep < 0 ? [] : lines.slice(sep + 1) };
    }
    function settersOfForm() {
      const out = Array.from(document.querySelectorAll('.f-setter:checked')).map((c) => c.value);
      for (const n of val('#f-setters-other').split(',')) if (n.trim()) out.push(n.trim());
      return out;
    }
    function scaleHint() {
      const w = $('#f-wall');
      const opt = w && w.selectedOptions[0];
      const hint = $('#f-grade-scale');
      const dl = $('#grade-labels');
      dl.textContent = '';
      const scale = opt ? opt.dataset.scale : '';
      if (!scale) { hint.textContent = hint.dataset.any; return; }
      const labels = (opt.dataset.labels || '').split('|').filter(Boolean);
      hint.textContent = tr('in the wall\'s scale "{1}"', scale) + (labels.length ? ': ' + labels.join(', ') : '');
      for (const l of labels) { const o = document.createElement('option'); o.value = l; dl.appendChild(o); }
    }
    // The text -> the form. `all`: the gym fields too (a switch from the text view);
    // otherwise they stay as the page drew them from the record.
    function textToForm(text, all) {
      const { header, moves } = splitText(text);
      extra = [];
      const notes = [], setters = [];
      for (const line of header) {
        const m = line.match(KEY);
        const key = m ? m[1].toLowerCase() : '';
        const value = m ? (m[2] || '').trim() : '';
        if (!m) { if (line.trim() || notes.length) notes.push(line); continue; }
        if (!OWN.includes(key)) { extra.push(line); continue; }
        if (key === 'name') $('#f-name').value = value;
        else if (key === 'grade') $('#f-grade').value = value;
        else if (key === 'colour' || key === 'color') $('#f-colour').value = value;
        else if (key === 'setter') setters.push(value);
        else if (!all) continue;
        else if (key === 'state') {
          const sel = $('#f-state');
          if (!Array.from(sel.options).some((o) => o.value === value)) sel.add(new Option(value, value));
          sel.value = value;
        } else if (key === 'set' || key === 'date') {
          if (ISO.test(value)) $('#f-date').value = value; else extra.push(line);
        } else if (key === 'wall') {
          const opt = Array.from($('#f-wall').options).find((o) => o.value && o.dataset.name.toLowerCase() === value.toLowerCase());
          if (opt) $('#f-wall').value = opt.value; else extra.push(line);
        }
      }
      while (notes.length && !notes[notes.length - 1].trim()) notes.pop();
      $('#f-notes').value = notes.join('\n');
      while (moves.length && !moves[moves.length - 1].trim()) moves.pop();
      $('#f-moves').value = moves.join('\n');
      // Setters: the text's lines (a personal route, or a switch from the text view).
      if (all || !$('#f-setters-other').dataset.gym) {
        const boxes = Array.from(document.querySelectorAll('.f-setter'));
        const others = [];
        for (const b of boxes) b.checked = false;
        for (const s of setters) {
          const b = boxes.find((x) => x.value.toLowerCase() === s.toLowerCase());
          if (b) b.checked = true; else others.push(s);
        }
        $('#f-setters-other').value = others.join(', ');
      }
      // The circuit follows the colour (issue 31: the one chosen stays while its colour does).
      const circ = $('#f-circuit');
      if (circ) {
        const colour = val('#f-colour').toLowerCase();
        const cur = circ.selectedOptions[0];
        if (!(cur && cur.value && cur.dataset.colour.toLowerCase() === colour)) {
          const c = Array.from(circ.options).find((o) => o.value && o.dataset.colour.toLowerCase() === colour);
          circ.value = c ? c.value : '';
        }
      }
      scaleHint();
    }
    // The form -> the text (and lineMap: the field of each line).
    function formToText() {
      const out = [];
      lineMap = [];
      const add = (line, field) => { out.push(line); lineMap.push(field); };
      if (val('#f-name')) add('name: ' + val('#f-name'), 'name');
      if (val('#f-grade')) add('grade: ' + val('#f-grade'), 'grade');
      if (val('#f-colour')) add('colour: ' + val('#f-colour'), 'colour');
      if (inGym) {
        const w = $('#f-wall').selectedOptions[0];
        if (w && w.value) add('wall: ' + w.dataset.name, 'wall');
      }
      for (const s of settersOfForm()) add('setter: ' + s, 'setters');
      if (inGym) {
        if (val('#f-state') && val('#f-state') !== 'draft') add('state: ' + val('#f-state'), 'state');
        if (val('#f-date')) add('set: ' + val('#f-date'), 'set_on');
      }
      for (const l of extra) add(l, 'crdl');
      const notes = $('#f-notes').value.replace(/\r/g, '');
      if (notes.trim()) for (const l of notes.split('\n')) add(l, 'notes');
      const moves = $('#f-moves').value.replace(/\r/g, '');
      if (!out.length && !moves.trim()) { lineMap = []; return ''; }  // nothing typed yet
      add('---', 'moves');
      let k = 0;
      for (const l of moves.split('\n')) { if (l.trim() || moves.trim()) add(l, 'moves:' + (++k)); }
      return out.join('\n') + '\n';
    }
    const currentText = () => (view === 'form' ? formToText() : ta.value);

    function showView(which) {
      if (which === view) return;
      if (which === 'form') textToForm(ta.value, true);
      else ta.value = formToText();
      view = which;
      $('#route-form').hidden = which !== 'form';
      $('#text-view').hidden = which !== 'text';
      $('#view-form').setAttribute('aria-selected', String(which === 'form'));
      $('#view-text').setAttribute('aria-selected', String(which === 'text'));
      editor.classList.toggle('form-view', which === 'form');
      refresh();
    }

    let timer = null, seq = 0, holdMsg = false;
    async function refresh() {
      const mine = ++seq;
      const text = currentText();
      // Nothing typed yet: nothing to complain about (issue 21).
      if (!(view === 'form' ? val('#f-moves') || val('#f-name') : ta.value.trim())) {
        list.innerHTML = '';
        say($('#save-msg'), '', true);
        return;
      }
      const r = await api('POST', '/api/feedback', { crdl: text });
      if (mine !== seq || r.status !== 200) return;
      list.innerHTML = '';
      const sepLine = text.split('\n').findIndex((l) => l.trim() === '---') + 1;
      for (const l of r.data.lines) {
        if (l.kind === 'blank') continue;
        const li = document.createElement('li');
        // The form shows the moves numbered as moves; the text its lines.
        li.value = view === 'form' && sepLine && l.line > sepLine ? l.line - sepLine : l.line;
        li.className = 'fb-' + l.kind + (l.kind === 'move' && r.data.language && !l.parsed ? ' unparsed' : '');
        const src = document.createElement('code');
        src.textContent = l.text;
        li.appendChild(src);
        const note = document.createElement('span');
        note.className = 'reading';
        if (l.kind === 'move') {
          // The climbing part of the reading ("jug (big, good-hold)"), not the parser's internals.
          const climbing = (l.reading || '').split(' — ')[0];
          note.textContent = (l.hand === 'L' ? tr('left hand') : tr('right hand')) + (l.crux ? ' · ' + tr('crux') : '') +
            ' · ' + (r.data.language ? (l.parsed ? climbing : tr('not understood as a move')) : l.move) +
            (r.data.language && l.parsed && l.style ? ' · ' + tr('style: {1}', l.style) : '');
          for (const d of (l.did_you_mean || [])) {
            const dy = document.createElement('span');
            dy.className = 'did-you-mean';
            dy.textContent = ' · ' + tr('unknown word "{1}": did you mean "{2}"?', d.word, d.suggestion);
            note.appendChild(dy);
            li.classList.add('unparsed');
          }
        } else if (l.kind === 'error') {
          note.textContent = l.error || tr('not a move: start with L or R');
        } else if (l.kind === 'meta') {
          note.textContent = tr('metadata');
        } else if (l.kind === 'separator') {
          note.textContent = tr('moves follow');
        } else if (l.kind === 'comment') {
          note.textContent = tr('comment');
        } else {
          note.textContent = tr('description');
        }
        li.appendChild(note);
        list.appendChild(li);
      }
      const msg = $('#save-msg');
      if (holdMsg) return;
      if (!r.data.ok && r.data.error) {
        say(msg, tr('line {1}: {2}', r.data.error.line, r.data.error.message));
      } else {
        say(msg, trn('{1} move', '{1} moves', r.data.moves, r.data.moves), true);
      }
    }
    const later = () => { clearTimeout(timer); timer = setTimeout(refresh, 200); };
    // A refusal stays said until the user types again.
    const typed = () => { holdMsg = false; later(); };
    ta.addEventListener('input', typed);
    $('#route-form').addEventListener('input', typed);
    $('#route-form').addEventListener('change', later);
    if ($('#f-wall')) $('#f-wall').addEventListener('change', scaleHint);
    if ($('#f-circuit')) {
      $('#f-circuit').addEventListener('change', () => {
        const o = $('#f-circuit').selectedOptions[0];
        if (o && o.value) $('#f-colour').value = o.dataset.colour;
      });
    }
    $('#view-form').addEventListener('click', () => showView('form'));
    $('#view-text').addEventListener('click', () => showView('text'));
    textToForm(ta.value, false);
    editor.classList.add('form-view');
    refresh();

    // Issue 31: the form as the record was when this page drew it (then as the other save
    // left it): a save refused as stale keeps what the user changed and takes every other
    // field from the record as stored now, so saving again loses nobody's edit.
    const FIELDS = { '#f-name': tr('name'), '#f-grade': tr('grade'), '#f-colour': tr('hold colour'),
                     '#f-wall': tr('wall'), '#f-circuit': tr('circuit'), '#f-state': tr('state'),
                     '#f-date': tr('date'), '#f-notes': tr('notes'), '#f-moves': tr('moves'), '#public': tr('who can see it'),
                     other: tr('other header lines') };
    function snapshot() {
      const s = {};
      for (const f of Object.keys(FIELDS)) if ($(f)) s[f] = $(f).value;
      if (inGym || document.querySelector('.f-setter')) s.setters = settersOfForm().join(', ');
      s.other = extra.join('\n');  // the text's header lines the form does not show
      return s;
    }
    function setSetters(names) {
      const boxes = Array.from(document.querySelectorAll('.f-setter'));
      const others = [];
      for (const b of boxes) b.checked = false;
      for (const n of names) {
        const b = boxes.find((x) => x.value.toLowerCase() === n.toLowerCase());
        if (b) b.checked = true; else others.push(n);
      }
      $('#f-setters-other').value = others.join(', ');
    }
    function setSelect(sel, value) {
      const el = $(sel);
      if (!el) return;
      if (!Array.from(el.options).some((o) => o.value === value)) el.add(new Option(value, value));
      el.value = value;
    }
    function restore(s) {
      for (const f of Object.keys(FIELDS)) {
        if (!$(f) || !(f in s)) continue;
        if ($(f).tagName === 'SELECT') setSelect(f, s[f]); else $(f).value = s[f];
      }
      if ('setters' in s) setSetters(s.setters.split(',').map((x) => x.trim()).filter(Boolean));
      if ('other' in s) extra = s.other ? s.other.split('\n') : [];
    }
    let loaded = snapshot();
    // The record as stored now (the 409's "current") in the form's terms.
    function theirsOf(cur) {
      textToForm(cur.crdl || '', true);
      if (inGym) {
        if ($('#f-wall')) setSelect('#f-wall', cur.wall_id == null ? '' : String(cur.wall_id));
        if ($('#f-circuit')) setSelect('#f-circuit', cur.circuit == null ? '' : String(cur.circuit));
        if (typeof cur.state === 'string') setSelect('#f-state', cur.state);
        if ($('#f-date')) $('#f-date').value = cur.set_on || '';
        if (Array.isArray(cur.setters)) setSetters(cur.setters);
      }
      const lib = 'library' in cur ? cur.library : cur.public;
      if ($('#public') && typeof lib === 'boolean') setSelect('#public', lib ? '1' : '0');
      return snapshot();
    }
    function mergeConflict(cur) {
      const mine = snapshot();
      const theirs = theirsOf(cur);
      const merged = {}, taken = [], kept = [], both = [];
      for (const k of Object.keys(mine)) {
        const name = FIELDS[k] || k;
        const mineChanged = mine[k] !== loaded[k], theirsChanged = theirs[k] !== loaded[k];
        merged[k] = mineChanged ? mine[k] : theirs[k];
        if (mineChanged && theirsChanged && mine[k] !== theirs[k]) both.push(name);
        else if (mineChanged) kept.push(name);
        else if (theirsChanged) taken.push(name);
      }
      restore(merged);
      loaded = theirs;
      if (view === 'text') ta.value = formToText();
      scaleHint();
      return { taken, kept, both };
    }

    // A refusal next to the field it names ("grade: ...", or a located error's line).
    function fieldMessage(err, line) {
      holdMsg = true;
      for (const m of document.querySelectorAll('.field-msg')) m.textContent = '';
      let field = '', text = humane(err);
      if (line && view === 'form' && lineMap[line - 1]) {
        field = lineMap[line - 1];
        const mv = field.match(/^moves:(\d+)$/);
        if (mv) { field = 'moves'; text = tr('line {1} of the moves: {2}', mv[1], err.replace(/^[^:]*:\d+:\d+: /, '')); }
      } else if (line) {
        field = 'crdl';
      } else {
        const m = String(err).match(/^([a-z_]+)(?:\[\d+\])?:/);
        if (m) field = m[1] === 'color' ? 'colour' : m[1];
        if (field === 'crdl' && view === 'form') field = 'moves';
      }
      const box = document.querySelector('.field-msg[data-for="' + field + '"]');
      if (box && !(view === 'text' && field !== 'crdl' && box.closest('#route-form'))) {
        box.textContent = text;
        box.classList.add('bad');
        say($('#save-msg'), field === 'crdl' ? tr('not saved: see the text') : tr('not saved: see the field "{1}"', field));
      } else {
        say($('#save-msg'), text);
      }
    }

    $('#save').addEventListener('click', async () => {
      const text = currentText();
      if (view === 'text') textToForm(text, true);  // the gym fields the text names
      const body = { crdl: text, public: $('#public').value === '1' };
      if (inGym) {
        if (!routeId) body.gym = Number(editor.dataset.gym);
        body.wall = val('#f-wall');
        body.setters = settersOfForm();
        // A route's state changes only when asked (the cycle's rule, app::CheckTransition).
        if (!routeId || val('#f-state') !== editor.dataset.state) body.state = val('#f-state');
        body.set_on = val('#f-date');
        if ($('#f-circuit')) body.circuit = val('#f-circuit');  // issue 31: its id, "" = none
      } else if (!routeId) {
        body.gym = null;  // a personal route, in no gym's lists
      }
      if (routeId && editor.dataset.revision) body.revision = Number(editor.dataset.revision);
      const r = routeId ? await api('PUT', '/api/routes/' + routeId, body) : await api('POST', '/api/routes', body);
      if (r.status === 200 || r.status === 201) {
        location.href = '/routes/' + (routeId || r.data.id);
      } else if (r.status === 409 && r.data && r.data.current && /^revision:/.test(r.data.error || '')) {
        // Issue 31: someone saved first. Show theirs; keep ours; saving again applies ours.
        const cur = r.data.current;
        editor.dataset.revision = cur.revision;
        editor.dataset.state = cur.state;
        let box = $('#conflict');
        if (!box) {
          box = document.createElement('div');
          box.id = 'conflict';
          box.className = 'conflict';
          $('#save-msg').after(box);
        }
        box.textContent = '';
        const m = mergeConflict(cur);
        const p = document.createElement('p');
        p.textContent = tr('Someone else saved this route first (now revision {1}, state {2}).',
            cur.revision, tr(cur.state)) + ' ' +
          (m.taken.length ? tr('Their changes are now in the form: {1}.', m.taken.join(', ')) + ' ' : '') +
          (m.kept.length ? tr('Yours are kept: {1}.', m.kept.join(', ')) + ' ' : '') +
          (m.both.length ? tr('Changed by both, yours kept (theirs below): {1}.', m.both.join(', ')) + ' ' : '') +
          tr('Their text is below. Save again to save the form as it is now.');
        p.id = 'conflict-merge';
        const pre = document.createElement('pre');
        pre.id = 'conflict-current';
        pre.textContent = cur.crdl;
        box.append(p, pre);
        say($('#save-msg'), tr('not saved: changed meanwhile'));
        holdMsg = true;
      } else {
        fieldMessage(errorOf(r), r.data && r.data.line);
      }
    });
  }

  // Issue 31: a gym route's "Shared library" box on its page (PUT {"library"}).
  const lib = $('#route-library');
  if (lib) {
    lib.addEventListener('change', async () => {
      const r = await api('PUT', '/api/routes/' + lib.dataset.id, { library: lib.checked });
      if (r.status === 200) {
        location.reload();
      } else {
        lib.checked = !lib.checked;
        say($('#library-msg'), humane(errorOf(r)));
      }
    });
  }

  const del = $('#delete-route');
  if (del) {
    del.addEventListener('click', async () => {
      if (!confirm(tr('Delete this route?'))) return;
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
    let suggested = [];  // grid indices of suggested ICs
    const FIELDS = ['preset', 'novelty', 'system', 'params', 'integrator', 'step', 'ref_ic', 'var_ic', 'skip',
      'mapping', 'mask', 'max_repeat', 'name', 'grade', 'colour', 'wall', 'setter', 'date', 'notes',
      'visibility', 'metric', 'crux_window', 'match', 'target_effect', 'target_change', 'smooth_method'];
    // Checkboxes of the form state (the setter's constraints), '1' in the URL when ticked.
    const CHECKS = ['keep_start', 'keep_finish', 'alternate_hands'];
    const DEFAULTS = { preset: 'setter', novelty: 'mix', metric: 'effect', match: 'text', smooth_method: 'vomm' };
    const ADVANCED = ['system', 'params', 'integrator', 'step', 'ref_ic', 'var_ic', 'skip', 'mapping', 'mask',
      'max_repeat', 'crux_window', 'match', 'target_effect', 'target_change', 'smooth_method'].concat(CHECKS);
    const chosen = $('#chosen');
    const selectedRoutes = () => Array.from(chosen.querySelectorAll('li')).map((li) => Number(li.dataset.id));

    // The whole form state lives in the URL (replaceState), so Back, reload and shared links
    // restore it; the server renders the routes named there, in that order.
    function saveState() {
      const q = new URLSearchParams();
      const ids = selectedRoutes();
      if (ids.length) q.set('routes', ids.join(','));
      for (const k of FIELDS) {
        const el = $('#' + k);
        if (el && el.value.trim() && el.value !== DEFAULTS[k]) q.set(k, el.value);
      }
      for (const k of CHECKS) if ($('#' + k).checked) q.set(k, '1');
      if ($('#smooth').checked) q.set('smooth', '1');
      if ($('#duplicate') && $('#duplicate').checked) q.set('duplicate', '1');
      if ($('#route-find').value.trim()) q.set('find', $('#route-find').value.trim());
      const s = q.toString();
      history.replaceState(null, '', '/vary' + (s ? '?' + s : ''));
    }
    function loadState() {
      const q = new URLSearchParams(location.search);
      for (const k of FIELDS) {
        const el = $('#' + k);
        if (el && q.has(k)) el.value = q.get(k);
      }
      $('#smooth').checked = q.get('smooth') === '1';
      if ($('#duplicate')) $('#duplicate').checked = q.get('duplicate') === '1';
      for (const k of CHECKS) $('#' + k).checked = q.get(k) === '1';
      if (ADVANCED.some((k) => q.has(k))) $('#advanced').open = true;
    }
    loadState();

    function chosenItem(id, name, moves, extra) {
      const li = document.createElement('li');
      li.dataset.id = id; li.dataset.moves = moves; li.dataset.name = name;
      const n = document.createElement('span'); n.className = 'pick-name'; n.textContent = name;
      const small = document.createElement('small'); small.textContent = ' (' + trn('{1} move', '{1} moves', moves, moves) + extra + ') ';
      const btns = document.createElement('span'); btns.className = 'pick-buttons';
      for (const [cls, label, text] of [['up', tr('Move up'), '↑'], ['down', tr('Move down'), '↓'], ['remove', tr('Remove'), '✕']]) {
        const b = document.createElement('button'); b.type = 'button'; b.className = cls;
        b.textContent = text; b.setAttribute('aria-label', label + ' ' + name); btns.appendChild(b);
      }
      li.append(n, small, btns);
      return li;
    }
    function routesChanged() {
      const e = $('#chosen-empty');
      if (e) e.hidden = selectedRoutes().length > 0;
      const names = Array.from(chosen.querySelectorAll('li')).map((li) => li.dataset.name);
      $('#name').placeholder = !names.length ? tr('Variation of the chosen routes')
        : names.length === 1 ? tr('Variation of {1}', names[0])
          : names.length <= 3 ? tr('Variation of {1} and {2}', names.slice(0, -1).join(', '), names[names.length - 1])
            : tr('Variation of {1}, {2} and {3} more', names[0], names[1], names.length - 2);
      saveState();
      loadMap();
    }
    chosen.addEventListener('click', (ev) => {
      const b = ev.target.closest('button'); if (!b) return;
      const li = b.closest('li');
      if (b.classList.contains('up') && li.previousElementSibling) chosen.insertBefore(li, li.previousElementSibling);
      else if (b.classList.contains('down') && li.nextElementSibling) chosen.insertBefore(li.nextElementSibling, li);
      else if (b.classList.contains('remove')) li.remove();
      else return;
      routesChanged();
    });
    function foundItem(r) {
      const li = document.createElement('li');
      li.dataset.id = r.id; li.dataset.moves = r.moves; li.dataset.name = r.name;
      const n = document.createElement('span'); n.className = 'pick-name'; n.textContent = r.name;
      const small = document.createElement('small');
      small.textContent = ' (' + trn('{1} move', '{1} moves', r.moves, r.moves) + (r.grade ? ', ' + r.grade : '') + (r.public ? '' : ', ' + tr('private')) + ') ';
      const b = document.createElement('button'); b.type = 'button'; b.className = 'add'; b.textContent = tr('Add');
      b.setAttribute('aria-label', tr('Add {1}', r.name));
      li.append(n, small, b);
      return li;
    }
    $('#found').addEventListener('click', (ev) => {
      const b = ev.target.closest('button.add'); if (!b) return;
      const li = b.closest('li');
      const small = li.querySelector('small').textContent.replace(/^\s*\(\d+ moves/, '').replace(/\)\s*$/, '');
      chosen.appendChild(chosenItem(li.dataset.id, li.dataset.name, li.dataset.moves, small));
      routesChanged();
    });
    let findSeq = 0, findTimer = null, foundOffset = $('#found').children.length;
    async function find(more) {
      const mine = ++findSeq;
      const q = new URLSearchParams({ limit: '20', offset: String(more ? foundOffset : 0) });
      if ($('#route-find').value.trim()) q.set('q', $('#route-find').value.trim());
      const r = await api('GET', '/api/routes?' + q.toString());
      if (mine !== findSeq || r.status !== 200) return;
      if (!more) { $('#found').innerHTML = ''; foundOffset = 0; }
      for (const x of r.data.routes) $('#found').appendChild(foundItem(x));
      foundOffset += r.data.routes.length;
      $('#found-count').textContent = trn('{1} route', '{1} routes', r.data.total, r.data.total);
      $('#found-more').hidden = foundOffset >= r.data.total;
    }
    $('#route-find').addEventListener('input', () => { clearTimeout(findTimer); findTimer = setTimeout(() => { find(false); saveState(); }, 200); });
    $('#route-find').addEventListener('keydown', (ev) => { if (ev.key === 'Enter') { ev.preventDefault(); find(false); } });  // i18n: a key's name
    $('#found-more').addEventListener('click', () => find(true));

    function params() {
      const p = { preset: $('#preset').value };
      for (const k of ['system', 'integrator', 'mapping']) if ($('#' + k).value) p[k] = $('#' + k).value;
      for (const k of ['params', 'ref_ic', 'var_ic', 'mask']) if ($('#' + k).value.trim()) p[k] = $('#' + k).value.trim();
      for (const k of ['step']) if ($('#' + k).value.trim()) p[k] = Number($('#' + k).value);
      for (const k of ['skip', 'max_repeat']) if ($('#' + k).value.trim()) p[k] = parseInt($('#' + k).value, 10);
      return p;
    }
    // The setter's constraints, named as the JSON API's fields; defaults are left out.
    function setterFields() {
      const f = {};
      for (const k of CHECKS) if ($('#' + k).checked) f[k] = true;
      if ($('#crux_window').value.trim()) f.crux_window = $('#crux_window').value.trim();
      for (const k of ['target_effect', 'target_change']) if ($('#' + k).value.trim()) f[k] = Number($('#' + k).value);
      for (const k of ['match', 'smooth_method']) if ($('#' + k).value !== DEFAULTS[k]) f[k] = $('#' + k).value;
      return f;
    }
    // The paper's figure 4: warm colours for little variation, cold for much.
    function colour(t) {  // 0 (little) .. 1 (much): red .. yellow .. green .. blue
      const stops = [[178, 24, 43], [244, 165, 130], [253, 219, 120], [146, 197, 222], [33, 102, 172], [22, 40, 110]];
      const x = Math.max(0, Math.min(1, t)) * (stops.length - 1);
      const i = Math.min(stops.length - 2, Math.floor(x)), f = x - i;
      const c = stops[i].map((v, k) => Math.round(v + f * (stops[i + 1][k] - v)));
      return 'rgb(' + c.join(',') + ')';
    }
    const round = (v) => Math.round(v * 1e6) / 1e6;
    function maxOf(vals) { let m = 0; for (const v of vals) m = Math.max(m, v); return m; }
    function legend() {
      const el = $('#map-legend'); if (!el || !map) return;
      const metrics = $('#metric').value === 'both' ? ['effect', 'change'] : [$('#metric').value];
      el.innerHTML = '';
      for (const m of metrics) {
        const max = maxOf(map[m]);
        const row = document.createElement('div'); row.className = 'legend-row';
        const lo = document.createElement('span'); lo.textContent = m + ' 0';
        const bar = document.createElement('span'); bar.className = 'legend-bar';
        bar.style.background = 'linear-gradient(to right,' + [0, .2, .4, .6, .8, 1].map(colour).join(',') + ')';  // i18n: CSS
        const hi = document.createElement('span');
        hi.textContent = (m === 'effect' ? tr('{1} of {2} moves change', max, map.length) : tr('{1} (mean distance)', Math.round(max * 100) / 100));
        row.append(lo, bar, hi); el.appendChild(row);
      }
      const note = document.createElement('div'); note.className = 'hint';
      note.textContent = tr('warm = little variation, cold = much');
      el.appendChild(note);
    }
    function cellOf(ic) {  // grid cell of an IC in the map's plane, or null when outside
      if (!map) return null;
      const n = map.grid, ax = map.axes;
      const i = Math.round((ic[ax[0]] - map.x[0]) / (map.x[1] - map.x[0]));
      const j = Math.round((ic[ax[1]] - map.y[0]) / (map.y[1] - map.y[0]));
      return i >= 0 && i < n && j >= 0 && j < n ? [i, j] : null;
    }
    function draw() {
      if (!canvas || !map) return;
      const ctx = canvas.getContext('2d');
      const both = $('#metric').value === 'both';
      const metrics = both ? ['effect', 'change'] : [$('#metric').value];
      const n = map.grid, w = canvas.width / metrics.length, cell = w / n, H = canvas.height, ch = H / n;
      ctx.clearRect(0, 0, canvas.width, H);
      metrics.forEach((m, p) => {
        const vals = map[m], max = maxOf(vals), x0 = p * w;
        for (let j = 0; j < n; j++) for (let i = 0; i < n; i++) {
          ctx.fillStyle = colour(max ? vals[j * n + i] / max : 0);
          ctx.fillRect(x0 + i * cell, H - (j + 1) * ch, Math.ceil(cell), Math.ceil(ch));
        }
        const mark = (c, shape, color) => {
          if (!c) return;
          const cx = x0 + (c[0] + 0.5) * cell, cy = H - (c[1] + 0.5) * ch, r = Math.max(4, cell * 0.8);
          ctx.lineWidth = 2; ctx.strokeStyle = '#000'; ctx.fillStyle = color;
          ctx.beginPath();
          if (shape === 'circle') ctx.arc(cx, cy, r, 0, 2 * Math.PI);
          else if (shape === 'square') ctx.rect(cx - r, cy - r, 2 * r, 2 * r);
          else if (shape === 'diamond') { ctx.moveTo(cx, cy - r); ctx.lineTo(cx + r, cy); ctx.lineTo(cx, cy + r); ctx.lineTo(cx - r, cy); ctx.closePath(); }
          else { ctx.arc(cx, cy, r * 0.7, 0, 2 * Math.PI); ctx.fill(); }
          ctx.stroke();
          ctx.lineWidth = 1;
        };
        mark([Math.floor(n / 2), Math.floor(n / 2)], 'circle');
        mark(cellOf([-16, -12, 52]), 'square'); mark(cellOf([-16, -13.5, 52]), 'square');
        for (const k of suggested) mark([k % n, Math.floor(k / n)], 'diamond');
        const cur = $('#var_ic').value.split(',').map(Number);
        if (picked) mark(picked, 'dot', '#fff');
        else if (cur.length === 3 && cur.every(Number.isFinite)) mark(cellOf(cur), 'dot', '#fff');
        if (both) { ctx.fillStyle = '#000'; ctx.font = '12px sans-serif'; ctx.fillText(m, x0 + 4, 14); }  // i18n: a CSS font
      });
      $('#map-info').textContent = tr('{1} moves; axes {2} (right), {3} (up)', map.length, 'xyz'[map.axes[0]], 'xyz'[map.axes[1]]);
      legend();
    }
    function cellAt(ev) {
      const rect = canvas.getBoundingClientRect();
      const panes = $('#metric').value === 'both' ? 2 : 1, n = map.grid;
      let fx = (ev.clientX - rect.left) / rect.width * panes;
      fx -= Math.floor(Math.min(fx, panes - 1e-9));
      const i = Math.min(n - 1, Math.max(0, Math.floor(fx * n)));
      const j = Math.min(n - 1, Math.max(0, Math.floor((rect.bottom - ev.clientY) / rect.height * n)));
      return [i, j];
    }
    function icOf(c) {
      const ic = map.center.slice();
      ic[map.axes[0]] = map.x[c[0]];
      ic[map.axes[1]] = map.y[c[1]];
      return ic.map(round);
    }
    function readout(c, prefix) {
      const k = c[1] * map.grid + c[0];
      $('#map-readout').textContent = prefix + ' ' + tr('IC {1}: {2} of {3} moves change; change {4}', icOf(c).join(', '),
        map.effect[k], map.length, Math.round(map.change[k] * 100) / 100);
    }
    async function loadMap() {
      if (!canvas) return;
      const p = params();
      delete p.var_ic;
      const ids = selectedRoutes();
      const q = new URLSearchParams({ params: JSON.stringify(p), plane: 'xy', grid: '41', spacing: '0.2' });
      if (ids.length) q.set('routes', ids.join(','));
      $('#map-info').textContent = tr('computing…');
      const r = await api('GET', '/api/landscape?' + q.toString());
      if (r.status !== 200) { $('#map-info').textContent = (r.data && (r.data.message || r.data.error)) || tr('no map'); return; }
      map = r.data;
      canvas.width = $('#metric').value === 'both' ? 820 : 410;
      canvas.dataset.ready = '1';
      draw();
    }
    if (canvas) {
      canvas.addEventListener('mousemove', (ev) => { if (map) readout(cellAt(ev), tr('Hover:')); });
      canvas.addEventListener('click', (ev) => {
        if (!map) return;
        ev.preventDefault();
        picked = cellAt(ev);
        $('#var_ic').value = icOf(picked).join(',');
        readout(picked, tr('Chosen:'));
        draw();
        saveState();
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
        if (r.status !== 200) { list.textContent = (r.data && (r.data.message || r.data.error)) || tr('no candidates'); return; }
        suggested = r.data.candidates.map((c) => c.index);
        for (const c of r.data.candidates) {
          const li = document.createElement('li');
          const b = document.createElement('button');
          b.type = 'button';
          b.className = 'link-dark';
          b.textContent = c.ic.map(round).join(', ') + ' — ' + tr('{1} moves change, change {2}', c.effect, c.change);
          b.addEventListener('click', () => {
            $('#var_ic').value = c.ic.map(round).join(',');
            if (map) { picked = [c.index % map.grid, Math.floor(c.index / map.grid)]; readout(picked, tr('Chosen:')); }
            draw();
            saveState();
          });
          li.appendChild(b);
          list.appendChild(li);
        }
        draw();
      });
      $('#metric').addEventListener('change', () => { canvas.width = $('#metric').value === 'both' ? 820 : 410; draw(); saveState(); });
      $('#map-refresh').addEventListener('click', loadMap);
      $('#preset').addEventListener('change', loadMap);
      loadMap();
    }
    varyForm.addEventListener('input', saveState);
    varyForm.addEventListener('change', saveState);
    routesChanged();
    varyForm.addEventListener('submit', async (ev) => {
      ev.preventDefault();
      const ids = selectedRoutes();
      if (!csrf()) return say($('#vary-msg'), tr('Log in first to generate a variation.'));
      if (!ids.length) return say($('#vary-msg'), tr('Choose at least one route.'));
      saveState();
      const body = Object.assign(params(), { routes: ids, smooth: $('#smooth').checked });
      // Issue 33: the novelty asked of the setter's gallery (mix, the default, left out).
      if (body.preset === 'setter' && $('#novelty').value !== 'mix') body.novelty = $('#novelty').value;
      for (const k of ['name', 'grade', 'colour', 'wall', 'setter', 'date', 'notes']) if ($('#' + k).value.trim()) body[k] = $('#' + k).value.trim();
      if ($('#visibility').value) body.public = $('#visibility').value === 'public';
      if ($('#duplicate').checked) body.duplicate = true;
      Object.assign(body, setterFields());
      say($('#vary-msg'), tr('Generating…'), true);
      if (pageGym() !== undefined && body.gym === undefined) body.gym = pageGym();
      const r = await api('POST', '/api/variations', body);
      if (r.status === 201 || r.status === 200) {
        // Issue 22: the setter's preset chose the gallery's best; the plan page says so.
        if (r.data.gallery) {
          try { sessionStorage.setItem('sb-gallery-' + r.data.id, JSON.stringify(r.data.gallery)); } catch (e) { /* private mode */ }
        }
        location.href = '/variations/' + r.data.id + (r.data.existing ? '?existing=1' : '');
        return;
      }
      const err = (r.data && r.data.error) || tr('error {1}', r.status);
      say($('#vary-msg'), humane((r.data && r.data.message) || err));
      // An error about a constraint: show the panel that has the field.
      if (/^(keep_|crux_|alternate_|match|target_|smooth_method|max_repeat)|no variation IC within/.test(err)) $('#advanced').open = true;
    });
  }

  // ---- plan page ----
  const printBtn = $('#print');
  if (printBtn) printBtn.addEventListener('click', () => window.print());
  const plan = $('#plan');
  if (plan && new URLSearchParams(location.search).get('existing') === '1') {
    const p = document.createElement('p');
    p.className = 'notice no-print';
    p.id = 'existing';
    p.textContent = tr('You made this variation before from the same routes and parameters: here it is. Tick "Make a new copy" on the vary page for a second one.');
    plan.parentNode.insertBefore(p, plan);
  }

  // The setter's gallery note (issue 22): which candidate the setter's preset
  // stored and why, from the vary form's reply (this tab only).
  const planId = plan && (location.pathname.match(/^\/variations\/(\d+)/) || [])[1];
  let gallery = null;
  try { gallery = planId && JSON.parse(sessionStorage.getItem('sb-gallery-' + planId) || 'null'); } catch (e) { gallery = null; }
  if (gallery) {
    const p = document.createElement('p');
    p.className = 'notice no-print';
    p.id = 'gallery-note';
    p.textContent = tr('The setter\'s preset: the best of {1} candidates ({2} kept by the filter), score {3}: {4}.',
      gallery.count, gallery.kept, gallery.score, (gallery.reasons_text || gallery.reasons).join('; '));
    plan.parentNode.insertBefore(p, plan);
    // Issue 33: the novelty asked could not be met, and why.
    const why = gallery.novelty_note_text || gallery.novelty_note;
    if (why) {
      const n = document.createElement('p');
      n.className = 'notice no-print';
      n.id = 'novelty-note';
      n.textContent = why;
      plan.parentNode.insertBefore(n, plan);
    }
  }

  // ---- import page ----
  const importCrdl = $('#import-crdl');
  if (importCrdl) {
    importCrdl.addEventListener('click', async () => {
      if (importCrdl.disabled) return;  // one import at a time
      const files = $('#crdl-files').files;
      importCrdl.disabled = true;
      try {
        // One request: every file is checked before any is stored, and a
        // file imported before (same content) is skipped, not duplicated.
        const list = [];
        for (const f of files) list.push({ name: f.name, crdl: await f.text() });
        const r = await api('POST', '/api/import/crdl', { files: list, gym: pageGym() });
        if (r.status === 201) {
          const skipped = r.data.skipped || [];
          // Issue 31: where the routes went (a gym, or the importer's own) and a link to each.
          const g = r.data.gym;
          const said = g ? tr('{1} imported into {2}', r.data.imported, g.name) : tr('{1} imported as your own routes', r.data.imported);
          say($('#crdl-msg'), said + (skipped.length ? '; ' + skipped.join('; ') : ''), true);
          const out = $('#crdl-imported');
          if (out) {
            out.textContent = '';
            if (g) {
              const a = document.createElement('a');
              a.href = g.url;
              a.id = 'crdl-gym';
              a.textContent = tr('Open {1}', g.name);
              out.appendChild(a);
            }
            const ul = document.createElement('ul');
            for (const route of r.data.routes || []) {
              const li = document.createElement('li');
              const a = document.createElement('a');
              a.href = route.url;
              a.textContent = route.name || ('#' + route.id);
              li.appendChild(a);
              ul.appendChild(li);
            }
            if (ul.children.length) out.appendChild(ul);
            out.hidden = !out.children.length;
          }
        } else {
          say($('#crdl-msg'), errorOf(r), false);
        }
      } finally {
        importCrdl.disabled = false;
      }
    });
  }
  const importCsv = $('#import-csv');
  if (importCsv) {
    importCsv.addEventListener('click', async () => {
      if (importCsv.disabled) return;  // one import at a time
      const rf = $('#routes-csv').files[0], mf = $('#moves-csv').files[0];
      if (!rf || !mf) return say($('#csv-msg'), tr('Choose both files.'));
      const notes = $('#csv-notes');
      notes.textContent = '';
      notes.hidden = true;
      importCsv.disabled = true;
      say($('#csv-msg'), tr('Importing…'), true);
      try {
        const r = await api('POST', '/api/import/csv', { routes_csv: await rf.text(), moves_csv: await mf.text(),
                                                          gym: pageGym() });
        if (r.status === 201) {
          const skipped = r.data.skipped || [];
          say($('#csv-msg'), tr('{1} routes imported, {2} notes', r.data.imported, skipped.length), true);
          for (const n of skipped) {
            const li = document.createElement('li');
            li.textContent = n;
            notes.appendChild(li);
          }
          notes.hidden = skipped.length === 0;
        } else {
          say($('#csv-msg'), errorOf(r));
        }
      } finally {
        importCsv.disabled = false;
      }
    });
  }
})();
