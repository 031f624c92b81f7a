// Strange Beta: the gym pages' forms (issue 21). A form with data-api="METHOD URL" sends its
// fields as a JSON object (numbers for inputs of type number, arrays for data-list fields split
// at commas, nothing for empty optional fields) and reloads the page, or follows data-next
// (":id" = the new id) on success; errors go to the form's .msg element.
'use strict';

(function () {
  const csrf = () => {
    const m = document.querySelector('meta[name="csrf-token"]');
    return m ? m.content : '';
  };

  async function api(method, url, body) {
    const headers = { 'Accept': 'application/json', 'Content-Type': 'application/json' };
    if (csrf()) headers['X-CSRF-Token'] = csrf();
    const res = await fetch(url, { method, headers, credentials: 'same-origin',
                                   body: JSON.stringify(body) });
    let data = null;
    try { data = await res.json(); } catch (e) { data = null; }
    return { status: res.status, data };
  }

  // "V3: 2, V4: 1" -> {"V3": 2, "V4": 1} (data-map fields; the dashboard's targets).
  function mapOf(text) {
    const out = {};
    for (const part of text.split(',')) {
      const i = part.lastIndexOf(':');
      if (i < 0) continue;
      const key = part.slice(0, i).trim();
      const n = Number(part.slice(i + 1).trim());
      if (key) out[key] = Number.isNaN(n) ? part.slice(i + 1).trim() : n;
    }
    return out;
  }

  function fieldsOf(form) {
    const body = {};
    for (const el of form.elements) {
      if (!el.name || el.disabled) continue;
      let v = el.value.trim();
      if (el.type === 'checkbox') { body[el.name] = el.checked; continue; }
      if (v === '' && el.dataset.optional !== undefined) continue;
      if (el.type === 'number' && v !== '') v = Number(v);
      else if (el.dataset.list !== undefined) v = v === '' ? [] : v.split(',').map((s) => s.trim()).filter(Boolean);
      else if (el.dataset.int !== undefined && v !== '') v = Number(v);
      else if (el.dataset.map !== undefined) v = mapOf(v);
      body[el.name] = v;
    }
    return body;
  }

  for (const form of document.querySelectorAll('form[data-api]')) {
    form.addEventListener('submit', async (ev) => {
      ev.preventDefault();
      const [method, url] = form.dataset.api.split(' ');
      const button = form.querySelector('button[type="submit"]');
      if (button) button.disabled = true;
      const r = await api(method, url, fieldsOf(form));
      if (button) button.disabled = false;
      const msg = form.querySelector('.msg');
      if (r.status >= 200 && r.status < 300) {
        const next = form.dataset.next;
        if (next) location.href = next.replace(':id', r.data && r.data.id !== undefined ? r.data.id : '');
        else location.reload();
        return;
      }
      if (msg) {
        msg.textContent = (r.data && r.data.error) || ('Failed (' + r.status + ')');
        msg.classList.add('bad');
      }
    });
  }
})();
