// The head setter's import page (/gyms/{gym}/import, issue 32): read a pasted
// or uploaded list, choose the columns (prefilled from the header names by
// the server's guess), preview, confirm.
'use strict';

(function () {
  const $ = (sel) => document.querySelector(sel);
  // Issue 32: the page's messages in its language (script_messages.h), by their English text.
  const MSG = {};
  for (const el of document.querySelectorAll('script.sb-messages')) {
    try { Object.assign(MSG, JSON.parse(el.textContent)); } catch (e) { /* English */ }
  }
  const tr = (s, ...args) => (MSG[s] || s).replace(/\{(\d)\}/g, (m, i) => (args[i - 1] !== undefined ? String(args[i - 1]) : m));
  const root = $('#import-gym');
  if (!root) return;
  const gym = root.dataset.gym;
  const csrf = () => {
    const m = document.querySelector('meta[name="csrf-token"]');
    return m ? m.content : '';
  };
  async function post(body) {
    const res = await fetch('/api/gyms/' + gym + '/import', {
      method: 'POST', credentials: 'same-origin',
      headers: { 'Content-Type': 'application/json', 'Accept': 'application/json', 'X-CSRF-Token': csrf() },  // i18n: HTTP headers
      body: JSON.stringify(body),
    });
    let data = null;
    try { data = await res.json(); } catch (e) { data = { error: String(res.status) }; }
    return { status: res.status, data };
  }
  const say = (el, text, ok) => { el.textContent = text; el.className = 'msg ' + (ok ? 'ok' : 'error'); };  // i18n: classes
  let fileName = '';
  let mappingShown = false;

  $('#import-file').addEventListener('change', async (e) => {
    const f = e.target.files[0];
    if (!f) return;
    fileName = f.name;
    $('#import-data').value = await f.text();
    if (/\.json$/i.test(f.name)) $('#import-format').value = 'json';
    else if (/\.csv$/i.test(f.name)) $('#import-format').value = 'csv';
    mappingShown = false;
    preview();
  });

  function request(confirm) {
    const body = {
      format: $('#import-format').value,
      data: $('#import-data').value,
      file: fileName || 'list',
      confirm,
      strip_missing: $('#import-strip').checked,
    };
    if (mappingShown) {
      body.mapping = {};
      for (const s of document.querySelectorAll('.import-map')) body.mapping[s.dataset.field] = s.value;
      body.guess = false;
    }
    return body;
  }

  function fillMapping(columns, mapping) {
    for (const s of document.querySelectorAll('.import-map')) {
      s.textContent = '';
      const none = document.createElement('option');
      none.value = ''; none.textContent = tr('(none)');
      s.appendChild(none);
      for (const c of columns) {
        const o = document.createElement('option');
        o.value = c; o.textContent = c;
        s.appendChild(o);
      }
      s.value = mapping[s.dataset.field] || '';
    }
    $('#import-mapping').hidden = false;
    mappingShown = true;
  }

  function cell(row, text) {
    const td = document.createElement('td');
    td.textContent = text;
    row.appendChild(td);
    return td;
  }

  function showPreview(d) {
    const summary = tr('{1} new, {2} changed, {3} no longer in the list', d.new, d.changed, d.missing) +
      (d.missing ? tr(': strip them?') : '.') + (d.same ? ' ' + tr('({1} unchanged)', d.same) : '') +
      (d.new_walls && d.new_walls.length ? ' ' + tr('New sectors: {1}.', d.new_walls.join(', ')) : '');
    $('#import-summary').textContent = summary;
    $('#import-strip-label').hidden = !d.missing;
    const errs = $('#import-errors');
    errs.textContent = '';
    for (const e of d.errors) {
      const li = document.createElement('li');
      li.textContent = e.text;
      errs.appendChild(li);
    }
    $('#import-confirm').disabled = d.errors.length > 0;
    const body = $('#import-rows');
    body.textContent = '';
    for (const r of d.rows) {
      const row = document.createElement('tr');
      row.className = 'import-' + r.action;
      cell(row, r.line ? String(r.line) : '');
      cell(row, tr(r.action));
      cell(row, r.name);
      cell(row, r.grade);
      cell(row, r.wall);
      cell(row, r.colour);
      cell(row, (r.setters || []).join(', '));
      cell(row, (r.changes || []).join('; '));
      body.appendChild(row);
    }
    $('#import-preview').hidden = false;
  }

  async function preview() {
    const msg = $('#import-msg');
    if (!$('#import-data').value.trim()) return say(msg, tr('Paste a list or choose a file.'));
    say(msg, tr('Reading…'), true);
    const r = await post(request(false));
    if (r.status !== 200) {
      $('#import-preview').hidden = true;
      return say(msg, (r.data && (r.data.message || r.data.error)) || String(r.status));
    }
    say(msg, '', true);
    if (!mappingShown) fillMapping(r.data.columns, r.data.mapping);
    $('#import-done').textContent = '';
    showPreview(r.data);
  }

  $('#import-read').addEventListener('click', () => { mappingShown = false; preview(); });
  for (const s of document.querySelectorAll('.import-map')) s.addEventListener('change', preview);
  $('#import-confirm').addEventListener('click', async () => {
    const btn = $('#import-confirm');
    if (btn.disabled) return;
    btn.disabled = true;
    try {
      const r = await post(request(true));
      if (r.status === 201) {
        const d = r.data;
        say($('#import-done'), tr('{1} created, {2} updated, {3} stripped, {4} left as they were',
          d.created, d.updated, d.stripped, d.skipped), true);
      } else {
        say($("#import-done"), (r.data && (r.data.message || r.data.error)) || String(r.status));
      }
    } finally {
      btn.disabled = false;
    }
  });
})();
