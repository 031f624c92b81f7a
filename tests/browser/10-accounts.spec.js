// Sign-up (its rules shown), log-out, log-in with a wrong password first.
'use strict';
module.exports = async (t) => {
  const { page, base, check, shot } = t;
  const user = 'setter' + Date.now() % 100000;
  t.state.user = user;
  await page.goto(base + '/signup');
  check((await page.textContent('main')).match(/8 characters/), 'the sign-up form states its rules');
  await page.fill('#username', user);
  await page.fill('#password', 'correct horse battery');
  await Promise.all([page.waitForURL(base + '/'), page.click('#submit')]);
  check((await page.textContent('#whoami')) === user, 'sign up logs the new user in');
  await shot('01-routes');
  await page.click('#logout');
  await page.waitForSelector('#nav-login');
  check(await page.isVisible('#nav-login') && !(await page.$('#whoami')), 'log out');
  await page.goto(base + '/vary');
  check(await page.isVisible('#login-first') && await page.isDisabled('#generate'),
        'a logged-out visitor is told to log in before filling the vary form');
  await page.goto(base + '/login');
  await page.fill('#username', user);
  await page.fill('#password', 'wrong password!');
  await page.click('#submit');
  await page.waitForFunction(() => document.querySelector('#form-msg').textContent.length > 0);
  check((await page.textContent('#form-msg')).includes('wrong'), 'wrong password is refused');
  await shot('02-login');
  await page.fill('#password', 'correct horse battery');
  await Promise.all([page.waitForURL(base + '/'), page.click('#submit')]);
  check((await page.textContent('#whoami')) === user, 'log in');
};
