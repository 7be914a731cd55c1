// The time from `relief preview` being started to the page's first frame of the terrain, in
// Debian's Chromium (headless, WebGL in SwiftShader: no GPU here), started with relief as a user
// would open the printed address. Prints one JSON line: milliseconds from START_EPOCH_MS (when the
// command was started) to the browser launched, to the navigation's start, and to the first frame;
// and the page's own steps.
// Usage: node preview_first_frame.cjs URL_FILE START_EPOCH_MS
const { chromium } = require('playwright-core');
const fs = require('fs');

const [urlFile, start] = [process.argv[2], Number(process.argv[3])];
(async () => {
  const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    args: ['--no-sandbox', '--enable-unsafe-swiftshader', '--use-angle=swiftshader', '--disable-gpu-sandbox'],
  });
  const launched = Date.now();
  const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
  let url = '';
  while (!(url = fs.existsSync(urlFile) ? fs.readFileSync(urlFile, 'utf8').split('\n')[0] : '')) await new Promise((r) => setTimeout(r, 20));
  await page.goto(url);
  await page.waitForFunction(() => window.reliefPreview && window.reliefPreview.ready, null, { timeout: 300000, polling: 20 });
  const r = await page.evaluate(() => ({ origin: performance.timeOrigin, timings: window.reliefPreview.timings,
                                          model: window.reliefPreview.page().model }));
  console.log(JSON.stringify({ launchMs: launched - start, navigationMs: Math.round(r.origin - start),
                               firstFrameMs: Math.round(r.origin + r.timings['first frame'] - start),
                               steps: Object.fromEntries(Object.entries(r.timings).map(([k, v]) => [k, Math.round(v)])),
                               model: r.model }));
  await browser.close();
})().catch((e) => { console.error(e); process.exit(1); });
