#!/usr/bin/env node
// Opens a page in Debian's Chromium, headless, waits (in real time) until the page says it is
// ready (document.body.dataset.ready == "1", as lfcam's web page does once its first picture is
// drawn) or failed (dataset.error), then writes a screenshot and/or the page's DOM. It drives
// Chromium over the DevTools protocol on a pipe (--remote-debugging-pipe), with nothing but
// node's standard library: used by the browser test (src/lfcam/share/web_page_browser_test.cpp)
// and bench/web_page.sh.
//   node bench/page_screenshot.js URL --size WxH [--png OUT.png] [--dom OUT.html] [--timeout S]
// Exit status: 0 the page was ready; 1 it failed or timed out (its error, or the timeout, on
// stderr); 2 bad usage.
'use strict';
const {spawn} = require('node:child_process');
const fs = require('node:fs');
const os = require('node:os');
const path = require('node:path');

function usage(message) {
  process.stderr.write(`page_screenshot.js: ${message}\n`);
  process.exit(2);
}

const args = process.argv.slice(2);
const options = {size: [800, 600], timeout: 90};
for (let i = 0; i < args.length; ++i) {
  const a = args[i];
  if (a === '--size') {
    const m = /^(\d+)x(\d+)$/.exec(args[++i] || '');
    if (!m) usage('--size WxH');
    options.size = [Number(m[1]), Number(m[2])];
  } else if (a === '--png') options.png = args[++i];
  else if (a === '--dom') options.dom = args[++i];
  else if (a === '--timeout') options.timeout = Number(args[++i]);
  else if (a.startsWith('--')) usage(`unknown flag ${a}`);
  else options.url = a;
}
if (!options.url) usage('a URL is required');

// Chromium makes its singleton socket at TMPDIR/org.chromium.Chromium.XXXXXX/SingletonSocket,
// TMPDIR being the profile below, and a Unix socket's path is at most 107 bytes: where the
// temporary folder's own path is longer than 40, the profile goes in /tmp (Chromium refuses to
// start otherwise: "Socket path too long").
const temporary = os.tmpdir().length <= 40 ? os.tmpdir() : '/tmp';
const profile = fs.mkdtempSync(path.join(temporary, 'lfcam-chromium-'));
const chrome = spawn('chromium', [
  '--headless', '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
  '--no-first-run', '--disable-background-networking', '--disable-component-update',
  '--disable-sync', '--hide-scrollbars', `--user-data-dir=${profile}`,
  `--window-size=${options.size[0]},${options.size[1]}`, '--remote-debugging-pipe', 'about:blank',
], {
  stdio: ['ignore', 'ignore', 'pipe', 'pipe', 'pipe'],
  // Chromium's own temporary folders (org.chromium.Chromium.*) inside the profile, which goes.
  env: {...process.env, TMPDIR: profile},
  // A process group of its own (its zygote, renderers, GPU and network processes join it), so
  // that the end below can stop every one of them.
  detached: true,
});
let stderr = '';
chrome.stderr.on('data', (d) => { stderr += d; });

// The protocol: JSON messages, each ended by a NUL, to fd 3 and from fd 4.
const toChrome = chrome.stdio[3], fromChrome = chrome.stdio[4];
// A write after Chromium has gone (the close asked for at the end) is no failure.
toChrome.on('error', () => {});
let nextId = 1, buffer = '';
const pending = new Map();
fromChrome.on('data', (chunk) => {
  buffer += chunk.toString('utf8');
  let end;
  while ((end = buffer.indexOf('\0')) >= 0) {
    const message = JSON.parse(buffer.slice(0, end));
    buffer = buffer.slice(end + 1);
    if (message.id && pending.has(message.id)) {
      const {resolve, reject} = pending.get(message.id);
      pending.delete(message.id);
      if (message.error) reject(new Error(`${message.error.message} (${message.error.code})`));
      else resolve(message.result);
    }
  }
});
function send(method, params, sessionId) {
  const id = nextId++;
  toChrome.write(JSON.stringify({id, method, params: params || {}, sessionId}) + '\0');
  return new Promise((resolve, reject) => pending.set(id, {resolve, reject}));
}
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

let finishing = false;
function finish(status, message) {
  if (finishing) return;
  finishing = true;
  if (message) process.stderr.write(`page_screenshot.js: ${message}\n`);
  // Chromium's helpers (network, storage, GPU) write into the profile until they exit, and on a
  // loaded machine they outlived a killed browser process long enough to leave a third of the
  // profiles behind. So: Chromium is asked to close (it ends its helpers), the whole group is
  // then killed whatever happened, and the profile is removed, and once more a moment later for
  // what a dying helper wrote last.
  const killGroup = () => {
    try { process.kill(-chrome.pid, 'SIGKILL'); } catch (e) { /* already gone */ }
  };
  const removeProfile = () => {
    try {
      fs.rmSync(profile, {recursive: true, force: true, maxRetries: 5});
    } catch (e) { /* a temporary folder left behind is no failure of the page */ }
  };
  let ending = false;
  const done = () => {
    if (ending) return;
    ending = true;
    killGroup();
    removeProfile();
    setTimeout(() => { removeProfile(); process.exit(status); }, 300);
  };
  if (chrome.exitCode !== null || chrome.signalCode !== null) return done();
  chrome.once('exit', done);
  setTimeout(done, 3000);
  send('Browser.close').catch(() => {});
}

(async () => {
  const deadline = Date.now() + options.timeout * 1000;
  const {targetInfos} = await send('Target.getTargets');
  const page = targetInfos.find((t) => t.type === 'page');
  if (!page) return finish(1, 'Chromium opened no page');
  const {sessionId} = await send('Target.attachToTarget', {targetId: page.targetId, flatten: true});
  await send('Emulation.setDeviceMetricsOverride', {width: options.size[0],
    height: options.size[1], deviceScaleFactor: 1, mobile: false}, sessionId);
  await send('Page.enable', {}, sessionId);
  await send('Page.navigate', {url: options.url}, sessionId);
  let state = '';
  while (Date.now() < deadline) {
    const {result} = await send('Runtime.evaluate', {returnByValue: true, expression:
        'document.body ? JSON.stringify({ready: document.body.dataset.ready || "", ' +
        'error: document.body.dataset.error || ""}) : ""'}, sessionId);
    state = result.value || '';
    if (state && (JSON.parse(state).ready === '1' || JSON.parse(state).error)) break;
    await sleep(100);
  }
  const parsed = state ? JSON.parse(state) : {ready: '', error: ''};
  if (options.png) {
    const {data} = await send('Page.captureScreenshot', {format: 'png'}, sessionId);
    fs.writeFileSync(options.png, Buffer.from(data, 'base64'));
  }
  if (options.dom) {
    const {result} = await send('Runtime.evaluate', {returnByValue: true,
      expression: 'document.documentElement.outerHTML'}, sessionId);
    fs.writeFileSync(options.dom, result.value);
  }
  if (parsed.ready === '1' && !parsed.error) return finish(0);
  if (parsed.error) return finish(1, `the page says: ${parsed.error}`);
  return finish(1, `the page was not ready after ${options.timeout} s`);
})().catch((e) => finish(1, `${e.message}\n${stderr.slice(-2000)}`));

chrome.on('exit', (code) => {
  if (pending.size && !finishing) {
    finish(1, `Chromium exited (${code}) early:\n${stderr.slice(-2000)}`);
  }
});
chrome.on('error', (e) => {
  finish(1, `cannot start chromium (${e.message}): install Debian's package chromium`);
});
