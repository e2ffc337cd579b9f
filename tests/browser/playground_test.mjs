// The playground page (web/playground) in a real browser: Debian's chromium,
// headless, driven by playwright-core (web/package.json) against the real
// freeformd on free ports. Checks what the page drew against the server's
// own answers, asked for directly by this test:
//   - after dragging a control point, the drawn polyline (the SVG's points)
//     lies on a direct Evaluate of the new control points at the drawn
//     parameters, and within the tolerance between them;
//   - the de Casteljau triangle's last point is the Evaluate at t;
//   - the 3D view drew the teapot mesh with the vertex and triangle counts
//     of a direct Tessellate of examples/teapot.json, and its pixels show it;
//   - the console has no errors and the page asked nothing of any other
//     origin (it works offline).
// Saves a screenshot (--screenshot). Exit status 77 (ctest's skip) only
// when chromium is not installed (scripts/setup.sh installs it).
//   node playground_test.mjs --freeformd PATH --source-dir DIR --screenshot PNG
import assert from 'node:assert/strict';
import {spawn} from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import readline from 'node:readline';
import {parseArgs} from 'node:util';

const CHROMIUM = '/usr/bin/chromium';
// The tolerance the page meshes the curve with (its default).
const CURVE_TOLERANCE = 0.001;
// The teapot's tolerance on the page (its default).
const TEAPOT_TOLERANCE = 0.01;
// Where the test drags the second control point (world coordinates).
const DRAG_TARGET = [1.5, 2.4];
// A pixel of the curve view is about 0.008 in world units.
const PIXEL = 0.02;

const {values: args} = parseArgs({options: {
  'freeformd': {type: 'string'},
  'source-dir': {type: 'string'},
  'screenshot': {type: 'string'},
}});

// The server's log, printed when the test fails.
let serverLog = '';

// startServer runs freeformd on free ports; resolves with the process and
// the base URL of its HTTP listener.
function startServer() {
  const server = spawn(args.freeformd, ['--listen=127.0.0.1:0', '--http_listen=127.0.0.1:0'],
      {stdio: ['ignore', 'pipe', 'pipe']});
  server.stderr.on('data', (bytes) => {
    serverLog += bytes;
  });
  return new Promise((resolve, reject) => {
    server.on('exit', (code) => reject(new Error(`freeformd exited with ${code}`)));
    readline.createInterface({input: server.stdout}).on('line', (line) => {
      const match = line.match(/^freeformd http listening on (\S+)$/);
      if (match) resolve({server, base: `http://${match[1]}`});
    });
  });
}

async function rpc(base, service, method, request) {
  const answer = await fetch(`${base}/freeform.v1.${service}/${method}`, {
    method: 'POST', headers: {'Content-Type': 'application/json'}, body: JSON.stringify(request),
  });
  const body = await answer.json();
  assert.equal(answer.status, 200, `${method}: ${JSON.stringify(body)}`);
  return body;
}

function pairs(coordinates) {
  const points = [];
  for (let i = 0; i < coordinates.length; i += 2) points.push([coordinates[i], coordinates[i + 1]]);
  return points;
}

function distance([ax, ay], [bx, by]) {
  return Math.hypot(ax - bx, ay - by);
}

// distanceToSegment returns the distance from p to the segment ab.
function distanceToSegment(p, a, b) {
  const [dx, dy] = [b[0] - a[0], b[1] - a[1]];
  const length2 = dx * dx + dy * dy;
  const s = length2 === 0 ? 0 :
    Math.max(0, Math.min(1, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / length2));
  return distance(p, [a[0] + s * dx, a[1] + s * dy]);
}

async function dragControlPoint(page, index, target) {
  const [from, to] = await page.evaluate(([i, world]) => {
    const view = window.playground.curves;
    return [view.toScreen(view.state.points[i]), view.toScreen(world)];
  }, [index, target]);
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  await page.mouse.move(to.x, to.y, {steps: 8});
  await page.mouse.up();
  await page.evaluate(() => window.playground.idle());
}

async function checkDraggedCurve(page, base) {
  const before = await page.evaluate(() => window.playground.curves.state.points);
  await dragControlPoint(page, 1, DRAG_TARGET);
  const {points, parameters, drawn} = await page.evaluate(() => ({
    points: window.playground.curves.state.points,
    parameters: window.playground.curves.drawn.parameters,
    drawn: document.querySelector('#curve-line').getAttribute('points'),
  }));
  assert.ok(distance(points[1], DRAG_TARGET) < PIXEL, `dragged to ${points[1]}`);
  for (const i of [0, 2, 3]) assert.deepEqual(points[i], before[i]);
  const polyline = pairs(drawn.split(/[\s,]+/).map(Number));
  assert.equal(polyline.length, parameters.length);
  assert.ok(polyline.length >= 8, `${polyline.length} drawn points`);

  // The test's own curve: the first curve with the dragged point moved.
  const curve = {bezier: {controlPoints: {dimension: 2, coordinates: points.flat()}}};
  const evaluated = await rpc(base, 'CurveService', 'Evaluate',
      {curve, parameters: {list: {values: parameters}}});
  pairs(evaluated.derivatives[0].coordinates).forEach((point, i) => {
    assert.ok(distance(point, polyline[i]) < 1e-12, `drawn point ${i}: ${polyline[i]} vs ${point}`);
  });
  // Between its vertices the drawn polyline stays within the tolerance.
  const middles = parameters.slice(1).map((t, i) => (parameters[i] + t) / 2);
  const between = await rpc(base, 'CurveService', 'Evaluate',
      {curve, parameters: {list: {values: middles}}});
  pairs(between.derivatives[0].coordinates).forEach((point, i) => {
    const gap = distanceToSegment(point, polyline[i], polyline[i + 1]);
    assert.ok(gap <= CURVE_TOLERANCE, `chord ${i} is ${gap} from the curve`);
  });
  return curve;
}

async function checkConstruction(page, base, curve) {
  const {t, levels} = await page.evaluate(() => ({
    t: window.playground.curves.state.t,
    levels: [...document.querySelectorAll('.construction polyline')].map((line) => line.getAttribute('points')),
  }));
  assert.equal(levels.length, 3, 'a cubic has three de Casteljau levels');
  const last = pairs(levels[2].split(/[\s,]+/).map(Number));
  assert.equal(last.length, 1);
  const atT = await rpc(base, 'CurveService', 'Evaluate', {curve, parameters: {list: {values: [t]}}});
  assert.ok(distance(last[0], atT.derivatives[0].coordinates) < 1e-12, `C(${t}) = ${last[0]}`);
}

async function checkTeapot(page, base) {
  const teapot = JSON.parse(fs.readFileSync(path.join(args['source-dir'], 'examples', 'teapot.json')));
  const surfaces = teapot.patches.map((patch) => ({bezier: {controlNet: {
    dimension: 3, countU: 4, countV: 4, coordinates: patch.control_points.flat()}}}));
  const mesh = await rpc(base, 'SurfaceService', 'Tessellate',
      {surfaces, tolerance: TEAPOT_TOLERANCE, normals: true});
  const vertices = mesh.vertices.coordinates.length / 3;
  const triangles = mesh.triangles.length / 3;
  const shown = await page.evaluate(() => {
    const view = window.playground.surfaces;
    // The share of the canvas's pixels that are not the background.
    const canvas = view.renderer.domElement;
    const copy = document.createElement('canvas');
    copy.width = canvas.width;
    copy.height = canvas.height;
    const context = copy.getContext('2d');
    context.drawImage(canvas, 0, 0);
    const pixels = context.getImageData(0, 0, copy.width, copy.height).data;
    let drawn = 0;
    for (let i = 0; i < pixels.length; i += 4) {
      if (Math.abs(pixels[i] - pixels[0]) + Math.abs(pixels[i + 1] - pixels[1]) +
          Math.abs(pixels[i + 2] - pixels[2]) > 24) drawn++;
    }
    return {
      model: view.controls.model.value,
      tolerance: view.drawn.request.tolerance,
      vertexCount: view.drawn.vertexCount,
      triangleCount: view.drawn.triangleCount,
      text: view.controls.vertexCount.textContent,
      drawnShare: drawn / (pixels.length / 4),
    };
  });
  assert.equal(shown.model, 'teapot');
  assert.equal(shown.tolerance, TEAPOT_TOLERANCE);
  assert.equal(shown.vertexCount, vertices);
  assert.equal(shown.text, String(vertices));
  assert.equal(shown.triangleCount, triangles);
  assert.ok(shown.drawnShare > 0.05, `the mesh covers ${shown.drawnShare} of the canvas`);
  return {vertices, triangles};
}

async function main() {
  if (!fs.existsSync(CHROMIUM)) {
    console.log(`SKIP: ${CHROMIUM} is not installed (scripts/setup.sh installs chromium)`);
    process.exit(77);
  }
  const {chromium} = await import(path.join(args['source-dir'], 'web', 'node_modules',
      'playwright-core', 'index.mjs'));
  const {server, base} = await startServer();
  const browser = await chromium.launch({
    executablePath: CHROMIUM,
    // --no-sandbox: chromium refuses to run as root with its sandbox.
    // SwiftShader renders WebGL without a GPU.
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
  });
  try {
    const page = await browser.newPage({viewport: {width: 1400, height: 760}});
    const errors = [];
    const foreign = [];
    page.on('console', (message) => {
      if (message.type() === 'error') errors.push(message.text());
    });
    page.on('pageerror', (error) => errors.push(String(error)));
    page.on('request', (request) => {
      if (!request.url().startsWith(base) && !request.url().startsWith('data:')) foreign.push(request.url());
    });
    await page.goto(`${base}/`);
    await page.waitForFunction(() => window.playground !== undefined);
    await page.evaluate(() => window.playground.idle());

    const curve = await checkDraggedCurve(page, base);
    console.log('ok: the drawn curve is a direct Evaluate of the dragged control points');
    await checkConstruction(page, base, curve);
    console.log('ok: the de Casteljau construction ends at C(t)');
    const {vertices, triangles} = await checkTeapot(page, base);
    console.log(`ok: the teapot drawn with the server's ${vertices} vertices, ${triangles} triangles`);
    if (args.screenshot) await page.screenshot({path: args.screenshot});
    assert.deepEqual(errors, [], 'console errors');
    assert.deepEqual(foreign, [], 'requests to other origins');
    console.log('ok: no console errors, no request left the server');
  } finally {
    await browser.close();
    server.kill('SIGTERM');
  }
}

main().then(() => process.exit(0), (error) => {
  console.error(`freeformd's log:\n${serverLog}`);
  console.error(error);
  process.exit(1);
});
