// Strange Beta: the gym pages' forms (issue 21). A form with data-api="METHOD URL" sends its
// fields as a JSON object (numbers for inputs of type number, arrays for data-list fields split
// at commas, nothing for empty optional fields, null for empty data-clear fields: an edit form's
// way of removing a value; an object of "a.b" fields all null is null) and reloads the page, or
// follows data-next (":id" = the new id) on success; errors go to the form's .msg element.
'use strict';

(function () {
  // Issue 32: the page's messages in its language (script_messages.h), by their English text.
  const MSG = {};
  for (const el of document.querySelectorAll('script.sb-messages')) {
    try { Object.assign(MSG, JSON.parse(el.textContent)); } catch (e) { /* English */ }
  }
  const tr = (s, ...args) => (MSG[s] || s).replace(/\{(\d)\}/g, (m, i) => (args[i - 1] !== undefined ? String(args[i - 1]) : m));
  const csrf = () => {
    const m = document.querySelector('meta[name="csrf-token"]');
    return m ? m.content : '';
  };

  async function api(method, url, body) {
    const headers = { 'Accept': 'application/json', 'Content-Type': 'application/json' };  // i18n: HTTP headers
    if (csrf()) headers['X-CSRF-Token'] = csrf();
    const res = await fetch(url, { method, headers, credentials: 'same-origin',
                                   body: JSON.stringify(body) });
    let data = null;
    try { data = await res.json(); } catch (e) { data = null; }
    return { status: res.status, data };
  }

  function fieldsOf(form) {
    const body = {};
    for (const el of form.elements) {
      if (!el.name || el.disabled) continue;
      let v = el.value.trim();
      if (el.type === 'checkbox') { body[el.name] = el.checked; continue; }
      if (v === '' && el.dataset.optional !== undefined) continue;
      if (v === '' && el.dataset.clear !== undefined) v = null;  // issue 31: cleared
      else if (el.type === 'number' && v !== '') v = Number(v);
      else if (el.dataset.list !== undefined) v = v === '' ? [] : v.split(',').map((s) => s.trim()).filter(Boolean);
      else if (el.dataset.int !== undefined && v !== '') v = Number(v);
      // data-map fields ("V3: 2, V4: 1") go as typed: the server reads them and names
      // a part it cannot read (issue 31), instead of the page dropping it.
      const dot = el.name.indexOf('.');
      if (dot > 0) {  // "plan.x": a field of an object (the wall's floor-plan rectangle)
        const outer = el.name.slice(0, dot);
        if (typeof body[outer] !== 'object' || body[outer] === null) body[outer] = {};
        body[outer][el.name.slice(dot + 1)] = v;
      } else {
        body[el.name] = v;
      }
    }
    // An object whose fields were all cleared (the floor plan's x, y, w, h) is cleared.
    for (const k of Object.keys(body)) {
      const o = body[k];
      if (o !== null && typeof o === 'object' && !Array.isArray(o) &&
          Object.keys(o).length && Object.values(o).every((x) => x === null)) body[k] = null;
    }
    return body;
  }

  // Issue 31: a stale save (409 with the record as stored now): say what it is now,
  // keep what the user typed, and move the form to the current revision so saving
  // again applies theirs over it.
  function showConflict(form, msg, data) {
    const cur = data.current || {};
    if (typeof cur.summary === 'string') {
      // Several records at once (a setting day's routes): say what they are now; the page
      // must be read again before acting on them.
      msg.textContent = tr('Not done: someone changed these routes first. They are now: {1}. Reload the page to see them, then try again.',
        cur.summary || tr('none'));
      msg.classList.add('bad', 'conflict');
      return;
    }
    const parts = [];
    for (const el of form.elements) {
      if (!el.name || el.type === 'hidden' || el.name.indexOf('.') > 0) continue;
      if (!(el.name in cur)) continue;
      // The form's wall is the wall row's name (the JSON's "wall" is the text's own line).
      const v = el.name === 'wall' && 'wall_name' in cur ? cur.wall_name : cur[el.name];
      const text = Array.isArray(v) ? v.join(', ')
        : (v !== null && typeof v === 'object') ? Object.entries(v).map(([k, x]) => k + ': ' + x).join(', ')
        : (v === null || v === '' ? '—' : v);
      parts.push(el.name + ': ' + text);
      // A field the user did not change takes the value stored now (so saving again
      // applies only what they changed, not the page's old values over the other save).
      if (el.type === 'checkbox' || (v !== null && typeof v === 'object' && !Array.isArray(v))) continue;
      const now = Array.isArray(v) ? v.join(', ') : (v === null ? '' : String(v));
      if (el.tagName === 'SELECT') {
        const def = Array.from(el.options).find((o) => o.defaultSelected) || el.options[0];
        const opt = Array.from(el.options).find((o) => o.value === now);
        if (!opt) continue;
        if (!def || el.value === def.value) el.value = now;
        for (const o of el.options) o.defaultSelected = o === opt;
      } else {
        if (el.value === el.defaultValue) el.value = now;
        el.defaultValue = now;
      }
    }
    for (const name of ['state', 'set_on', 'strip_on']) {
      if (name in cur && !parts.some((p) => p.startsWith(name + ':'))) {
        parts.push(name + ': ' + (cur[name] === '' ? '—' : cur[name]));
      }
    }
    const rev = form.querySelector('input[name="revision"]');
    if (rev && cur.revision !== undefined) rev.value = cur.revision;
    msg.textContent = tr('Someone else saved this first (now revision {1}). It is now: {2}. Your changes are still here: save again to apply yours over theirs, or reload to take theirs.', cur.revision, parts.join('; '));
    msg.classList.add('bad', 'conflict');
  }

  // The note a change left before the page reloaded (above), shown at its form.
  try {
    const note = JSON.parse(sessionStorage.getItem('sb-note') || 'null');
    sessionStorage.removeItem('sb-note');
    if (note) {
      const p = document.createElement('p');
      p.className = 'msg ok';
      p.id = 'bulk-note';
      p.setAttribute('role', 'status');
      p.textContent = note.text;
      const form = document.getElementById(note.form);
      if (form) form.after(p); else document.querySelector('main').prepend(p);
    }
  } catch (e) { /* no storage or no note */ }

  for (const form of document.querySelectorAll('form[data-api]')) {
    form.addEventListener('submit', async (ev) => {
      ev.preventDefault();
      if (form.dataset.confirm && !window.confirm(form.dataset.confirm)) return;
      const [method, url] = form.dataset.api.split(' ');
      const button = form.querySelector('button[type="submit"]');
      if (button) button.disabled = true;
      const r = await api(method, url, fieldsOf(form));
      if (button) button.disabled = false;
      const msg = form.querySelector('.msg');
      if (r.status >= 200 && r.status < 300) {
        // Issue 31: a change of several routes at once says what it left as it was.
        const left = [];
        if (r.data && r.data.drafts_of_others > 0) {
          left.push(tr('Drafts of others left as they are: {1}.', r.data.drafts_of_others));
        }
        if (r.data && r.data.not_shown > 0) {
          left.push(tr('Routes this page did not show, left as they are: {1}.', r.data.not_shown));
        }
        if (left.length) {
          try {
            sessionStorage.setItem('sb-note', JSON.stringify({ form: form.id,
              text: tr('Changed: {1}.', r.data.count) + ' ' + left.join(' ') }));
          } catch (e) { /* no storage: the page reloads without the note */ }
        }
        const next = form.dataset.next;
        if (next) location.href = next.replace(':id', r.data && r.data.id !== undefined ? r.data.id : '');
        else location.reload();
        return;
      }
      if (msg && r.status === 409 && r.data && r.data.current) {
        showConflict(form, msg, r.data);
      } else if (msg) {
        msg.textContent = (r.data && (r.data.message || r.data.error)) || tr('Failed ({1})', r.status);
        msg.classList.add('bad');
      }
    });
  }
})();
