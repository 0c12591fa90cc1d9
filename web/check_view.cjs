// Checks a page `argil view` wrote, in headless Chromium (Debian's, driven by
// playwright-core) loading it from file://:
//   node check_view.cjs PAGE SCREENSHOT.png [--run]
// It must render the surfaces (not blank; a model's own pixel where one of its
// vertices projects), a click on a known vertex must pick that face and (u, v),
// and with --run the timeline must play to its last frame, where the deepest
// point shows blue (moved in). Exits 0 when every check passes, 1 when one
// fails, 2 on a bad call, 77 when Chromium is not installed.
"use strict";
const fs = require("fs");
const path = require("path");

const CHROMIUM = process.env.ARGIL_CHROMIUM || "/usr/bin/chromium";
// Software WebGL (SwiftShader); no network: Chromium's background traffic is
// refused on a closed machine.
const ARGS = [
  "--no-sandbox",
  "--use-angle=swiftshader",
  "--enable-unsafe-swiftshader",
  "--disable-quic",
  "--no-first-run",
  "--disable-background-networking",
  "--disable-component-update",
  "--disable-sync",
];

let failures = 0;
function check(ok, what) {
  console.log(`${ok ? "ok  " : "FAIL"} ${what}`);
  if (!ok) failures += 1;
}

// Share of the canvas's pixels that are not the background, and the RGB at
// a client pixel, read back from the WebGL canvas (preserveDrawingBuffer).
function canvasPixels(page, at) {
  return page.evaluate((at) => {
    const gl = document.querySelector("#view canvas");
    const c = document.createElement("canvas");
    c.width = gl.width;
    c.height = gl.height;
    const g = c.getContext("2d");
    g.drawImage(gl, 0, 0);
    const d = g.getImageData(0, 0, c.width, c.height).data;
    const bg = [d[0], d[1], d[2]]; // a corner is background
    let model = 0;
    for (let i = 0; i < d.length; i += 4) {
      if (Math.abs(d[i] - bg[0]) + Math.abs(d[i + 1] - bg[1]) + Math.abs(d[i + 2] - bg[2]) > 24) model += 1;
    }
    const rect = gl.getBoundingClientRect();
    const rgbAt = (p) => {
      const x = Math.round(((p.x - rect.left) * c.width) / rect.width);
      const y = Math.round(((p.y - rect.top) * c.height) / rect.height);
      const i = 4 * (y * c.width + x);
      return [d[i], d[i + 1], d[i + 2]];
    };
    return { share: model / (d.length / 4), background: bg, at: at.map(rgbAt) };
  }, at);
}

async function main() {
  const [pagePath, screenshot, ...flags] = process.argv.slice(2);
  if (!pagePath || !screenshot) {
    console.error("usage: node check_view.cjs PAGE SCREENSHOT.png [--run]");
    process.exit(2);
  }
  if (!fs.existsSync(CHROMIUM)) {
    console.log(`skipped: no Chromium at ${CHROMIUM} (make deps installs Debian's chromium)`);
    process.exit(77);
  }
  const { chromium } = require("playwright-core");
  const browser = await chromium.launch({ executablePath: CHROMIUM, args: ARGS });
  try {
    const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
    const errors = [];
    page.on("pageerror", (e) => errors.push(e.message));
    page.on("console", (m) => m.type() === "error" && errors.push(m.text()));
    // Any request leaving file:// is a page that is not self-contained.
    const requests = [];
    page.on("request", (r) => !r.url().startsWith("file:") && requests.push(r.url()));
    await page.goto("file://" + path.resolve(pagePath));
    await page.waitForFunction(() => window.argilView !== undefined, null, { timeout: 60000 });
    const ready = await page.evaluate(() => window.argilView.ready);
    check(ready, "the page loads its data and starts" + (ready ? "" : ": " + (await page.evaluate(() => window.argilView.error))));
    if (!ready) return;
    check(requests.length === 0, `no network request (${requests.length}: ${requests.slice(0, 3).join(" ")})`);

    const faces = await page.evaluate(() => window.argilView.faces());
    // A visible vertex of the largest face: the one nearest the view's centre
    // whose pixel picks its own face.
    const largest = faces.reduce((best, f, i) => (f.vertices > faces[best].vertices ? i : best), 0);
    const n = faces[largest].vertices;
    let picked = null, target = null;
    for (let j = 0; j < 25 && !picked; ++j) {
      const k = Math.floor(((j + 0.5) / 25) * n);
      const v = await page.evaluate(([f, k]) => window.argilView.vertex(f, k), [largest, k]);
      const p = await page.evaluate((x) => window.argilView.project(x), v.position);
      if (p.x < 360 || p.x > 900 || p.y < 20 || p.y > 640) continue; // under a panel or off view
      await page.mouse.click(p.x, p.y);
      const pick = await page.evaluate(() => window.argilView.lastPick());
      if (pick && pick.face === faces[largest].face && pick.model === faces[largest].model) {
        picked = pick;
        target = { vertex: v, pixel: p };
      }
    }
    check(picked !== null, `a click on a vertex of ${faces[largest].model} face ${faces[largest].face} picks that face`);
    if (picked) {
      const du = Math.abs(picked.u - target.vertex.uv[0]), dv = Math.abs(picked.v - target.vertex.uv[1]);
      const dp = Math.hypot(...picked.point.map((x, c) => x - target.vertex.position[c]));
      const size = await page.evaluate(() => window.argilView.size());
      check(dp < 0.01 * size, `the picked point is the vertex's (${dp.toPrecision(3)} mm off, the models are ${size.toPrecision(3)} mm)`);
      const span = await page.evaluate((f) => window.argilView.uvExtent(f), largest);
      check(du <= 0.01 * span[0] && dv <= 0.01 * span[1],
        `the picked (u, v) = (${picked.u.toPrecision(6)}, ${picked.v.toPrecision(6)}) is the vertex's (${target.vertex.uv.map((x) => x.toPrecision(6)).join(", ")}) within 1% of the face's range`);
      const text = await page.textContent("#pick-text");
      check(text.includes(`face ${picked.face}`) && text.includes("(u, v)"), "the pick panel names the face and (u, v)");
      const keyframe = await page.inputValue("#keyframe");
      check(/"position":\[/.test(keyframe), "the pick gives a script keyframe");
    }

    if (flags.includes("--run")) {
      const frames = await page.evaluate(() => window.argilView.frameCount());
      check(frames > 1, `the run has a timeline (${frames} frames)`);
      await page.evaluate(() => window.argilView.setFrame(0));
      await page.click("#play");
      await page.waitForFunction(() => !window.argilView.playing(), null, { timeout: 60000 });
      const at = await page.evaluate(() => window.argilView.frame());
      check(at === frames - 1, `play reaches the last frame (${at + 1} of ${frames})`);
      const label = await page.textContent("#frame-label");
      check(label.includes(`frame ${frames}/${frames}`), `the timeline says so: "${label}"`);
      await page.uncheck("#show-tool"); // the tool's glass would tint the dent
      const deepest = await page.evaluate(() => window.argilView.deepest());
      check(deepest !== null && deepest.deviation < 0, `a point moved in (${deepest && deepest.deviation.toPrecision(3)} mm)`);
      if (deepest) {
        const p = await page.evaluate((x) => window.argilView.project(x), deepest.position);
        const pixels = await canvasPixels(page, [p]);
        const [r, g, b] = pixels.at[0];
        check(b > r + 20, `the deepest point is drawn blue (rgb ${r}, ${g}, ${b})`);
      }
      await page.check("#show-tool");
    }

    const pixels = await canvasPixels(page, target ? [target.pixel] : []);
    check(pixels.share > 0.05, `the surfaces cover ${(100 * pixels.share).toFixed(1)}% of the view`);
    if (target) {
      const [r, g, b] = pixels.at[0];
      const bg = pixels.background;
      check(Math.abs(r - bg[0]) + Math.abs(g - bg[1]) + Math.abs(b - bg[2]) > 24,
        `the picked vertex's pixel is the model's (rgb ${r}, ${g}, ${b}; background ${bg.join(", ")})`);
    }
    check(errors.length === 0, `no script error (${errors.join("; ")})`);
    await page.screenshot({ path: screenshot });
    console.log(`screenshot: ${screenshot}`);
  } finally {
    await browser.close();
  }
}

main().then(
  () => process.exit(failures ? 1 : 0),
  (e) => {
    console.error(e.stack || String(e));
    process.exit(1);
  }
);
