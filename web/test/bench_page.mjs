// PAGE-8's measurement: each page opened RUNS times in headless Chromium (as test_page.mjs opens
// it), the milliseconds from navigation start to the first frame with T drawn (window.fhrPage's
// firstFrame). Prints {"PAGE": [ms, ...], ...} as JSON. bench/run_bench.py (./run bench page) runs it.
// Usage: node web/test/bench_page.mjs RUNS PAGE.html...
import puppeteer from 'puppeteer-core';

const [runs, ...pages] = process.argv.slice(2);
const browser = await puppeteer.launch({
  executablePath: '/usr/bin/chromium', headless: true,
  args: ['--use-gl=angle', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--no-sandbox'],
});
const times = {};
try {
  for (let r = 0; r < Number(runs); r++) {
    for (const file of pages) { // interleaved, so that a slow phase of the machine touches every page alike
      const page = await browser.newPage();
      await page.setViewport({ width: 1280, height: 800 });
      await page.goto('file://' + file);
      await page.waitForFunction('window.fhrPage && window.fhrPage.firstFrame !== null', { timeout: 120000 });
      (times[file] ||= []).push(await page.evaluate(() => window.fhrPage.firstFrame));
      await page.close();
    }
  }
} finally {
  await browser.close();
}
console.log(JSON.stringify(times));
