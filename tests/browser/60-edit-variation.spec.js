// Editing a variation updates its plan: removed moves go, added moves are
// marked, provenance and parameters stay.
'use strict';
module.exports = async (t) => {
  const { page, base, check, shot, api } = t;
  const id = t.state.orderVariation;
  if (!id) return check(false, 'no variation from the vary spec to edit');
  await page.goto(base + '/variations/' + id);
  const rowsBefore = (await page.$$('table.card-moves tbody tr:not(.suggested)')).length;
  await page.click('#edit');
  await page.click('#view-text');  // the CRDL text (issue 31: the form comes first)
  await page.waitForSelector('#crdl');
  const text = await page.inputValue('#crdl');
  const lines = text.split('\n');
  const sep = lines.indexOf('---');
  const edited = lines.slice(0, sep + 1).concat(lines.slice(sep + 2)).concat(['L heel hook added by hand']).join('\n');
  await page.fill('#crdl', edited);
  await Promise.all([page.waitForURL(/\/variations\/\d+$/), page.click('#save')]);
  const rowsAfter = (await page.$$('table.card-moves tbody tr:not(.suggested)')).length;
  check(rowsAfter === rowsBefore, 'the plan shows the edited moves (' + rowsBefore + ' -> ' + rowsAfter + ')');
  const added = await page.textContent('table.card-moves tbody tr.added');
  check(added.includes('heel hook added by hand') && added.includes('added by the setter'), 'the added move is marked');
  check((await page.textContent('table.card-moves tbody tr:first-child td.from')).includes('Order'), 'moves from the variation keep their provenance');
  check((await page.textContent('.params-line')).includes('variation IC'), 'the generation parameters are kept');
  await shot('10-edited-variation');
  const j = await api('GET', '/api/variations/' + id);
  check(j.data.plan.moves.some((m) => m.added), 'the JSON plan marks the added move');
};
