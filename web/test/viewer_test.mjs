// The viewer in a real browser (Debian's Chromium, headless, driven by playwright-core): it
// connects to a real kerf-server, draws the server's surface, follows a cut that kerf-haptic
// makes, and two tabs show the same frame.
//   node test/viewer_test.mjs KERF_SERVER KERF_HAPTIC    (from web/, after `npm run build`)
// Screenshots go to test/screenshots/.
import { spawn } from 'node:child_process';
import { mkdirSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { createInterface } from 'node:readline';
import { chromium } from 'playwright-core';

const [server, haptic] = process.argv.slice(2);
let failures = 0;
function check(ok, what) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`);
  if (!ok) failures += 1;
}
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

// Starts a process; `lines(pattern)` resolves with the first line of its output matching it,
// `exited` when it exits (however early).
function start(command, args) {
  const child = spawn(command, args, { stdio: ['ignore', 'pipe', 'inherit'] });
  const exited = new Promise((resolve) => child.on('exit', resolve));
  const seen = [], waiting = [];
  createInterface({ input: child.stdout }).on('line', (line) => {
    seen.push(line);
    for (const w of waiting) { const m = line.match(w.pattern); if (m) w.resolve(m); }
  });
  const line = (pattern) => new Promise((resolve, reject) => {
    for (const l of seen) { const m = l.match(pattern); if (m) return resolve(m); }
    waiting.push({ pattern, resolve });
    child.on('exit', (code) => reject(new Error(`${command} exited (${code}) before ${pattern}`)));
  });
  return { child, line, exited };
}

async function waitFor(page, predicate, what, ms = 20000, argument = undefined) {
  const end = Date.now() + ms;
  while (Date.now() < end) {
    if (await page.evaluate(predicate, argument)) return true;
    await sleep(100);
  }
  check(false, `${what} (timed out; page state ${JSON.stringify(await page.evaluate(() => window.kerf))})`);
  return false;
}

async function sessionInfo(base, id) {
  const list = await (await fetch(`${base}/api/sessions`)).json();
  return (list.sessions ?? []).find((s) => s.session_id === id);
}

const journal = mkdtempSync(`${tmpdir()}/kerf-viewer-`);
let kerfServer = start(server, ['--listen=127.0.0.1:0', '--http_listen=127.0.0.1:0',
                                `--journal_dir=${journal}`, '--web_root=dist']);
const browser = await chromium.launch({
  executablePath: '/usr/bin/chromium',
  args: ['--headless', '--no-sandbox', '--disable-gpu', '--disable-background-networking',
         '--disable-component-update', '--no-first-run'],
});
try {
  const [, web] = await kerfServer.line(/^kerf-server web on (\S+)$/);
  const base = `http://${web}`;
  const [, grpc] = await kerfServer.line(/^kerf-server listening on (\S+)$/);
  // A session whose tissue settles for 3 s (time for the pages to load; it still moves under
  // its load while it is cut), then a 4 s cut along the straight path. Its surface is counted
  // at once, before the cut, however slowly the pages load.
  const cutter = start(haptic, [`--server=${grpc}`, '--path=../server/lab/paths/lattice-straight.json',
                                '--device=path', '--slowdown=16', '--settle_seconds=3',
                                '--keep_session']);
  const [, session, token] = await cutter.line(/^kerf-haptic: session (\S+), observer token (\S+)$/);
  const uncutInfo = await sessionInfo(base, session);
  const pages = [await browser.newPage({ viewport: { width: 960, height: 640 } }),
                 await browser.newPage({ viewport: { width: 960, height: 640 } })];
  for (const page of pages) await page.goto(`${base}/#session=${session}&token=${token}`);
  const [first, second] = pages;
  let before = { surface_triangles: 0 };
  if (await waitFor(first, () => window.kerf.triangles > 0 && window.kerf.connected, 'the page draws the surface')) {
    // On a loaded machine the pages may load after the cut began; the count changes with each
    // cut pose then, and the page follows a frame behind, so the two are compared until they
    // agree (between poses, or once the cut is done), for 15 s at most.
    let drawn = -1;
    for (const end = Date.now() + 15000; Date.now() < end;) {
      before = await sessionInfo(base, session);
      drawn = await first.evaluate(() => window.kerf.triangles);
      if (drawn === Number(before.surface_triangles)) break;
      await sleep(50);
    }
    check(drawn === Number(before.surface_triangles),
          `the page draws the server's surface (${drawn} triangles; the server has ${before.surface_triangles})`);
  }
  mkdirSync('test/screenshots', { recursive: true });
  const uncut = await first.screenshot({ path: 'test/screenshots/before-cut.png' });
  await cutter.exited;  // the cut is done
  await waitFor(first, () => window.kerf.onCut > 0, 'the cut appears on the page');
  await sleep(500);
  const after = await sessionInfo(base, session);
  const drawnAfter = await first.evaluate(() => window.kerf.triangles);
  check(drawnAfter === Number(after.surface_triangles) && drawnAfter > Number(uncutInfo.surface_triangles),
        `after the cut the page draws the server's surface (${drawnAfter} triangles; the server has ${after.surface_triangles})`);
  const cut = await first.screenshot({ path: 'test/screenshots/after-cut.png' });
  check(!uncut.equals(cut), 'the picture changed with the cut');
  // Both tabs drew the same frames: the numbers each drew lately overlap, and they are at most
  // half a second apart (read a few times: a tab the shared machine stalled for a moment
  // catches up; one that stopped drawing does not).
  let a = [], b = [];
  for (let read = 0; read < 5; ++read) {
    [a, b] = await Promise.all(pages.map((p) => p.evaluate(() => window.kerf.recent)));
    if (Math.abs(a.at(-1) - b.at(-1)) <= 30) break;
    await sleep(200);
  }
  const common = a.filter((n) => b.includes(n));
  check(common.length > 100 && Math.abs(a.at(-1) - b.at(-1)) <= 30,
        `two tabs show the same frames (${common.length} frame numbers in common; now ${a.at(-1)} and ${b.at(-1)})`);
  // The force heat map: a second socket, at the FORCES level, colours the surface.
  await first.check('#heat');
  await waitFor(first, () => window.kerf.forceFrames > 10 && window.kerf.largestForce > 0,
                'the heat map gets the nodal forces');
  check(await first.evaluate(() => window.kerf.largestForce > 0), 'the heat map has forces to show');
  await first.screenshot({ path: 'test/screenshots/heat-map.png' });
  await first.uncheck('#heat');
  // The server restarts (its sessions come back from the journal): both tabs reconnect.
  kerfServer.child.kill('SIGTERM');
  await kerfServer.exited;
  kerfServer = start(server, [`--listen=${grpc}`, `--http_listen=${web}`,
                              `--journal_dir=${journal}`, '--web_root=dist']);
  await kerfServer.line(/^kerf-server listening on /);
  for (const page of pages) {
    await waitFor(page, () => window.kerf.reconnects > 0 && window.kerf.connected &&
                              window.kerf.triangles > 0, 'the tab reconnects after a restart');
  }
  const restored = await sessionInfo(base, session);
  const redrawn = await Promise.all(pages.map((p) => p.evaluate(() => window.kerf.triangles)));
  check(redrawn.every((n) => n === Number(restored?.surface_triangles)),
        `after the restart both tabs draw the restored surface (${redrawn}; the server has ${restored?.surface_triangles})`);
  // Still live: the frames it draws keep advancing. (How fast is the machine's, not the
  // page's: frames/s and the frames skipped, latest winning, are printed for the record.)
  const drawnBefore = await first.evaluate(() => window.kerf.sequence);
  await waitFor(first, (from) => window.kerf.sequence >= from + 30, 'the page keeps drawing', 20000,
                drawnBefore);
  const stats = await first.evaluate(() => window.kerf);
  check(stats.sequence >= drawnBefore + 30,
        `live after the restart: frame ${drawnBefore} then ${stats.sequence} (${stats.fps.toFixed(1)} frames/s, ${stats.gaps} skipped of ${stats.frames})`);
} catch (e) {
  check(false, `${e}`);
} finally {
  await browser.close();
  kerfServer.child.kill('SIGTERM');
  rmSync(journal, { recursive: true, force: true });
}
console.log(failures === 0 ? 'viewer_test: all passed' : `viewer_test: ${failures} failed`);
process.exit(failures === 0 ? 0 : 1);
