// Strange Beta: the setting-day page (issue 22). Each candidate's Accept form carries the
// candidate as proposed (data-accept, JSON); submitting posts it with the chosen setter to
// data-url and, on success, shows links to the planned route, its card and its tag.
'use strict';

(function () {
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
      const headers = { 'Accept': 'application/json', 'Content-Type': 'application/json' };
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
        msg.append('Planned: ');
        for (const [label, href] of [['route ' + data.id, data.url], ['card', data.card],
                                     ['tag', data.tag]]) {
          const a = document.createElement('a');
          a.href = href;
          a.textContent = label;
          a.className = 'accepted-' + label.split(' ')[0];
          msg.append(a, ' ');
        }
        return;
      }
      button.disabled = false;
      msg.textContent = (data && data.error) || ('Failed (' + res.status + ')');
      msg.classList.add('bad');
    });
  }
})();
