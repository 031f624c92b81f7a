// A 390 px wide phone: no horizontal scroll on the main pages.
'use strict';
module.exports = async (t) => {
  const { page, base, check, shot } = t;
  await page.setViewportSize({ width: 390, height: 844 });
  const pages = [['/', 'phone-routes'], ['/vary', 'phone-vary'], ['/routes/new', 'phone-editor']];
  if (t.state.orderVariation) pages.push(['/variations/' + t.state.orderVariation, 'phone-card']);
  for (const [p, name] of pages) {
    await page.goto(base + p);
    await page.waitForTimeout(300);
    const w = await page.evaluate(() => document.documentElement.scrollWidth);
    await shot(name);
    check(w <= 390, p + ' at 390 px has no horizontal scroll (' + w + ' px)');
  }
  await page.setViewportSize({ width: 1200, height: 900 });
};
