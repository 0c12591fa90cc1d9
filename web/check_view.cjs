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
    const size = await page.evaluate(() => window.argilView.size());
    // Picking: a click on the centroid of a known triangle must hit that
    // triangle and return its face and the centroid's (u, v), unless another
    // triangle nearer the eye hides it. Triangles of the largest faces,
    // at least 6 px^2 on screen, away from the panels.
    const order = faces.map((f, i) => i).sort((a, b) => faces[b].vertices - faces[a].vertices).slice(0, 20);
    const eye = await page.evaluate(() => window.argilView.eye());
    const distance = (p) => Math.hypot(...p.map((x, c) => x - eye[c]));
    let matched = 0, hidden = 0, target = null;
    const mismatches = [];
    for (const f of order) {
      const count = await page.evaluate((f) => window.argilView.triangleCount(f), f);
      for (let j = 0; j < 40 && matched < 3 && mismatches.length === 0; ++j) {
        const t = Math.floor(((j * 7919) % 40 + 0.5) * (count / 40));
        const tri = await page.evaluate(([f, t]) => window.argilView.triangle(f, t), [f, t]);
        const px = [];
        for (const p of tri.positions) px.push(await page.evaluate((x) => window.argilView.project(x), p));
        const area = Math.abs((px[1].x - px[0].x) * (px[2].y - px[0].y) - (px[2].x - px[0].x) * (px[1].y - px[0].y)) / 2;
        const centre = [0, 1, 2].map((c) => (tri.positions[0][c] + tri.positions[1][c] + tri.positions[2][c]) / 3);
        const uv = [0, 1].map((c) => (tri.uv[0][c] + tri.uv[1][c] + tri.uv[2][c]) / 3);
        const p = await page.evaluate((x) => window.argilView.project(x), centre);
        if (area < 6 || p.x < 360 || p.x > 900 || p.y < 20 || p.y > 640) continue;
        // Not seen edge-on: there half a pixel is far along the surface.
        const e1 = [0, 1, 2].map((c) => tri.positions[1][c] - tri.positions[0][c]);
        const e2 = [0, 1, 2].map((c) => tri.positions[2][c] - tri.positions[0][c]);
        const normal = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
        const toEye = [0, 1, 2].map((c) => eye[c] - centre[c]);
        const cosine = Math.abs(normal.reduce((s, x, c) => s + x * toEye[c], 0)) / (Math.hypot(...normal) * Math.hypot(...toEye));
        if (!(cosine > 0.3)) continue;
        await page.mouse.click(p.x, p.y);
        const pick = await page.evaluate(() => window.argilView.lastPick());
        // Another triangle nearer the eye hides this one; the triangle itself
        // must give the centre's (u, v).
        const same = pick && pick.faceIndex === f && pick.triangle === t;
        if (pick && !same && distance(pick.point) < distance(centre) - 1e-4 * size) {
          hidden += 1;
          continue;
        }
        const span = await page.evaluate((f) => window.argilView.uvExtent(f), f);
        const ok = same && pick.face === faces[f].face && pick.model === faces[f].model &&
          Math.hypot(...pick.point.map((x, c) => x - centre[c])) < 1e-3 * size &&
          Math.abs(pick.u - uv[0]) <= 0.01 * span[0] && Math.abs(pick.v - uv[1]) <= 0.01 * span[1];
        if (ok) {
          matched += 1;
          target = target || { pixel: p, pick, uv, face: faces[f] };
        } else {
          mismatches.push(`${faces[f].model} face ${faces[f].face} triangle ${t} at (${uv.join(", ")}): ` +
            (pick ? `picked face ${pick.face} (${pick.u}, ${pick.v}), ${Math.hypot(...pick.point.map((x, c) => x - centre[c])).toPrecision(3)} mm from the centre, ${(distance(pick.point) - distance(centre)).toPrecision(3)} mm farther from the eye; cosine ${cosine.toFixed(2)}, ${area.toFixed(0)} px^2` : "picked nothing"));
        }
      }
    }
    check(matched >= 1 && mismatches.length === 0,
      `a click on a triangle's centre picks its face and (u, v) within 1% of the face's range: ` +
      `${matched} right, ${hidden} hidden behind other faces, ${mismatches.length} wrong ${mismatches.join("; ")}`);
    if (target) {
      console.log(`     e.g. ${target.face.model} face ${target.face.face}: picked (u, v) = (${target.pick.u.toPrecision(6)}, ` +
        `${target.pick.v.toPrecision(6)}), the triangle's centre (${target.uv.map((x) => x.toPrecision(6)).join(", ")})`);
      await page.mouse.click(target.pixel.x, target.pixel.y);
      const text = await page.textContent("#pick-text");
      check(text.includes(`face ${target.pick.face}`) && text.includes("(u, v)"), "the pick panel names the face and (u, v)");
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
      // The tool's glass and the path would tint the dent.
      await page.uncheck("#show-tool");
      await page.uncheck("#show-path");
      const deepest = await page.evaluate(() => window.argilView.deepest());
      check(deepest !== null && deepest.deviation < 0, `a point moved in (${deepest && deepest.deviation.toPrecision(3)} mm)`);
      if (deepest) {
        // Seen from outside along its normal before the run: into the dent.
        await page.evaluate(([p, n]) => window.argilView.lookAt(p, n), [deepest.position, deepest.normal]);
        const p = await page.evaluate((x) => window.argilView.project(x), deepest.position);
        const pixels = await canvasPixels(page, [p]);
        const [r, g, b] = pixels.at[0];
        check(b > r + 20, `the deepest point is drawn blue (rgb ${r}, ${g}, ${b})`);
      }
      await page.check("#show-tool");
      await page.check("#show-path");
      await page.evaluate(() => window.argilView.fit()); // the view the picks were made in
    }

    const pixels = await canvasPixels(page, target ? [target.pixel] : []);
    check(pixels.share > 0.01, `the surfaces cover ${(100 * pixels.share).toFixed(1)}% of the view`);
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
