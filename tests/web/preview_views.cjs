// Drives relief preview's page in Debian's Chromium (playwright-core, from web/package-lock.json):
// waits for the first frame, then for each view sets it, screenshots the terrain alone (the page's
// chrome hidden, the sky transparent) at the still's size, and presses "Use this view"; after each,
// the scene file is copied so that the test renders the still each view wrote. Then two of the
// views as keyframes (the K key) and Save path.
// Usage: node preview_views.cjs URL SCENE_FILE OUT_DIR
const { chromium } = require('playwright-core');
const fs = require('fs');
const path = require('path');

const [url, sceneFile, outDir] = process.argv.slice(2);

// The views, from the terrain's box: a bearing, an elevation above the horizontal, a distance in
// half-diagonals of the box, the field of view across the still.
const views = [
  { name: 'oblique', azimuthDeg: 135, elevationDeg: 30, distance: 2.6, fovDeg: 40 },
  { name: 'low', azimuthDeg: 250, elevationDeg: 6, distance: 2.2, fovDeg: 50 },
  { name: 'down', azimuthDeg: 0, elevationDeg: 90, distance: 2.4, fovDeg: 35 },
];

(async () => {
  const t0 = Date.now();
  const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    args: ['--no-sandbox', '--enable-unsafe-swiftshader', '--use-angle=swiftshader', '--disable-gpu-sandbox'],
  });
  const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
  page.on('console', (m) => console.log(`page ${m.type()}: ${m.text()}`));
  page.on('pageerror', (e) => { console.log(`page error: ${e.message}`); process.exitCode = 1; });
  await page.goto(url);
  await page.waitForFunction(() => window.reliefPreview && window.reliefPreview.ready, null, { timeout: 120000 });
  const firstFrame = await page.evaluate(() => window.reliefPreview.firstFrameMs);
  console.log(`first frame drawn ${(firstFrame / 1000).toFixed(2)} s after the page's navigation started`);
  console.log(`first frame drawn ${((Date.now() - t0) / 1000).toFixed(2)} s after the browser was started`);
  console.log(`the page's steps (ms): ${JSON.stringify(await page.evaluate(() => window.reliefPreview.timings))}`);
  console.log(`loading (ms): ${JSON.stringify(await page.evaluate(() => {
    const nav = performance.getEntriesByType('navigation')[0];
    const script = performance.getEntriesByType('resource').find((r) => r.name.endsWith('preview.js'));
    return { pageResponseEnd: nav.responseEnd, domInteractive: nav.domInteractive, scriptStart: script && script.startTime,
             scriptResponseEnd: script && script.responseEnd };
  }))}`);
  const facts = await page.evaluate(() => window.reliefPreview.page());
  const [lo, hi] = facts.bounds;
  const centre = [0, 1, 2].map((k) => (lo[k] + hi[k]) / 2);
  const half = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) / 2;
  await page.evaluate(({ width, height }) => window.reliefPreview.hideFurniture(width, height), facts.still);
  const viewOf = (v) => {
    const a = (v.azimuthDeg * Math.PI) / 180, e = (v.elevationDeg * Math.PI) / 180, d = v.distance * half;
    // Model axes: x east, y up, z south.
    const eye = [centre[0] + d * Math.sin(a) * Math.cos(e), centre[1] + d * Math.sin(e), centre[2] - d * Math.cos(a) * Math.cos(e)];
    return { eye, target: centre, fovDeg: v.fovDeg };
  };
  for (const v of views) {
    await page.evaluate((view) => window.reliefPreview.setView(view), viewOf(v));
    await page.locator('#view').screenshot({ path: path.join(outDir, `preview-${v.name}.png`), omitBackground: true });
    const [reply] = await Promise.all([page.waitForResponse((r) => r.url().endsWith('/use')), page.locator('#use').dispatchEvent('click')]);
    if (reply.status() !== 200) throw new Error(`Use this view: HTTP ${reply.status()} ${await reply.text()}`);
    fs.copyFileSync(sceneFile, path.join(path.dirname(sceneFile), `view-${v.name}.toml`));
    console.log(`${v.name}: ${JSON.stringify((await reply.json()).toml)}`);
  }
  // The three views as keyframes (K), then Save path: the scene's [animation] flyover.
  for (const v of views.slice(0, 2)) {
    await page.evaluate((view) => window.reliefPreview.setView(view), viewOf(v));
    await page.keyboard.press('KeyK');
  }
  const [saved] = await Promise.all([page.waitForResponse((r) => r.url().endsWith('/path')),
                                     page.locator('#savePath').dispatchEvent('click')]);
  if (saved.status() !== 200) throw new Error(`Save path: HTTP ${saved.status()} ${await saved.text()}`);
  console.log(`path: ${JSON.stringify((await saved.json()).toml)}`);
  await browser.close();
})().catch((e) => { console.error(e); process.exit(1); });
