// Strange Beta: the setting-day page (issue 22). Each candidate's Accept form carries the
// candidate as proposed (data-accept, JSON); submitting posts it with the chosen setter to
// data-url and, on success, shows links to the planned route, its card and its tag.
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

  for (const form of document.querySelectorAll('form.day-accept')) {
    form.addEventListener('submit', async (ev) => {
      ev.preventDefault();
      const body = JSON.parse(form.dataset.accept);
      body.setter = form.elements.setter.value;
      const button = form.querySelector('button[type="submit"]');
      button.disabled = true;
      const headers = { 'Accept': 'application/json', 'Content-Type': 'application/json' };  // i18n: HTTP headers
      if (csrf()) headers['X-CSRF-Token'] = csrf();
      const res = await fetch(form.dataset.url, { method: 'POST', headers,
                                                  credentials: 'same-origin',
                                                  body: JSON.stringify(body) });
      let data = null;
      try { data = await res.json(); } catch (e) { data = null; }
      const msg = form.querySelector('.msg');
      msg.textContent = '';
      if (res.status === 201 && data) {
        msg.classList.remove('bad');
        msg.append(tr('Planned:') + ' ');
        for (const [kind, label, href] of [['route', tr('route {1}', data.id), data.url],
                                           ['card', tr('card'), data.card], ['tag', tr('tag'), data.tag]]) {
          const a = document.createElement('a');
          a.href = href;
          a.textContent = label;
          a.className = 'accepted-' + kind;
          msg.append(a, ' ');
        }
        return;
      }
      button.disabled = false;
      msg.textContent = (data && (data.message || data.error)) || tr('Failed ({1})', res.status);
      msg.classList.add('bad');
    });
  }
})();
