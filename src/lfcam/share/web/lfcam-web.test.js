// Unit tests of the web page's model (lfcam-web.js), run by node's test runner:
//   node --test src/lfcam/share/web/
// The numbers they check come from lfcam's own model (render/virtual_camera.h,
// render/aperture_weights.h), worked by hand here.
'use strict';
const test = require('node:test');
const assert = require('node:assert');
const W = require('./lfcam-web.js');

// A 10 x 10 array 28 mm apart in the z = 0 plane, the st window 600 x 550 mm at z = -700.
const meta = {
  grid: {rows: 10, cols: 10},
  array: {p_ca: [0, 0, 0], u_ca: [1, 0, 0], v_ca: [0, 1, 0], n_ca: [0, 0, 1], rows: 10, cols: 10,
          pitch_mm: 28, width_mm: 280, height_mm: 280},
  window: {origin: [-160, -135, -700], x_axis: [1, 0, 0], y_axis: [0, 1, 0], width_mm: 600,
           height_mm: 550},
  sampling: {s0: 0, t0: 0, s1: 1, t1: 1, n_s: 624, n_t: 576},
  camera: {width: 640, height: 480, focal_length_mm: 500, focus_distance_mm: 4000,
           aperture_mm: 0, breathing: true},
};

const near = (a, b, tol, what) =>
  assert.ok(Math.abs(a - b) <= tol, `${what || 'value'}: ${a} is not within ${tol} of ${b}`);

test('the film breathes to focus, or stays at f', () => {
  near(W.filmDistance(500, 4000, true), 1 / (1 / 500 - 1 / 4000), 1e-9, 'd_i');
  assert.strictEqual(W.filmDistance(500, 4000, false), 500);
  near(W.minFocusDistance(500, true), 525, 1e-9);
});

test('the camera looks along -n_ca from its eye on the array, 56 mm of film across', () => {
  const view = Object.assign(W.defaultView(meta), {u: 0.25, v: 0.75, f: 500, focus: 4000});
  const frame = W.cameraFrame(meta, view);
  assert.deepStrictEqual(frame.eye, [70, 210, 0]);
  assert.deepStrictEqual(frame.n, [0, 0, 1]);
  assert.deepStrictEqual(frame.u, [1, 0, 0]);
  assert.deepStrictEqual(frame.v, [0, 1, 0]);
  near(frame.tanX, 28 / W.filmDistance(500, 4000, true), 1e-12, 'tan(fov/2)');
  near(frame.tanY, frame.tanX * 480 / 640, 1e-12, 'tan(fov_y/2)');
  // The central pixel's ray runs straight ahead; the right edge's at tan(fov/2).
  const centre = W.directionThrough(frame, view, 320, 240);
  assert.deepStrictEqual(centre, [0, 0, -1]);
  near(W.directionThrough(frame, view, 640, 240)[0], frame.tanX, 1e-12, 'edge');
});

test('a pinhole reads the four cameras around the eye, bilinearly', () => {
  // u = 0.5: grid x = 4.5, between columns 4 and 5; v = 0.05: y = 0, on row 0.
  const weights = W.diskCameraWeights(0, 4.5, 0, 10, 10);
  assert.strictEqual(weights.length, 2);
  for (const w of weights) {
    assert.strictEqual(w.row, 0);
    near(w.w, 0.5, 1e-12);
  }
  // Beyond the outer cameras the lookup clamps: the corner camera holds it all.
  const corner = W.diskCameraWeights(0, -0.4, -0.4, 10, 10);
  assert.deepStrictEqual(corner, [{row: 0, col: 0, w: 1}]);
  // Outside the window: nothing.
  assert.deepStrictEqual(W.diskCameraWeights(0, -0.6, 3, 10, 10), []);
});

test('an aperture shares its disk among the cameras as their hats receive it', () => {
  // A disk of radius 1 on camera (4, 4): symmetric, the centre camera the largest share, the
  // four edge neighbours equal, the weights summing to 1.
  const w = W.diskCameraWeights(1, 4, 4, 10, 10);
  const at = (r, c) => (w.find((x) => x.row === r && x.col === c) || {w: 0}).w;
  near(w.reduce((s, x) => s + x.w, 0), 1, 1e-9, 'sum');
  for (const [r, c] of [[3, 4], [5, 4], [4, 3], [4, 5]]) near(at(r, c), at(4, 5), 1e-3, `${r},${c}`);
  assert.ok(at(4, 4) > at(4, 5) && at(4, 5) > at(3, 3) && at(3, 3) > 0);
  // The centre camera's share, integrated by hand: over the unit disk, (1 - |x|)(1 - |y|) has
  // mean 1 - 2 E|x| + E|x||y| = 1 - 2 (4 / (3 pi)) + 1 / (2 pi).
  near(at(4, 4), 1 - 8 / (3 * Math.PI) + 1 / (2 * Math.PI), 2e-3, 'centre share');
  // A disk half outside the window counts only the part inside.
  const edge = W.diskCameraWeights(2, -0.5, 4, 10, 10);
  assert.ok(edge.every((x) => x.col <= 2));  // x in [-0.5, 1.5] reaches column 2
  near(edge.reduce((s, x) => s + x.w, 0), 1, 1e-9, 'sum at the edge');
});

test('the URL sets the view, and bad values are named, not used', () => {
  const parsed = W.parseView('?eye=0.2,0.7&f=700&focus=4300&aperture=64&size=800x600&ui=0', meta);
  assert.deepStrictEqual([parsed.view.u, parsed.view.v], [0.2, 0.7]);
  assert.strictEqual(parsed.view.f, 700);
  assert.strictEqual(parsed.view.focus, 4300);
  assert.strictEqual(parsed.view.aperture, 64);
  assert.deepStrictEqual(parsed.size, [800, 600]);
  assert.strictEqual(parsed.ui, false);
  assert.deepStrictEqual(parsed.errors, []);
  const bad = W.parseView('?eye=2&f=abc&size=0x10&aperture=', meta);
  assert.deepStrictEqual(bad.errors.sort(), ['aperture', 'eye', 'f', 'size']);
  assert.strictEqual(bad.view.f, 500);
  // Values beyond what the camera allows are brought inside.
  const wild = W.parseView('?eye=-1,5&focus=10&aperture=9999', meta).view;
  assert.deepStrictEqual([wild.u, wild.v], [0, 1]);
  near(wild.focus, 525, 1e-9, 'nearest focus');
  assert.strictEqual(wild.aperture, 280);
  // And the URL the page writes gives the same view back.
  const again = W.parseView(W.viewToSearch(parsed.view, parsed.size), meta);
  assert.deepStrictEqual(again.view, parsed.view);
  assert.deepStrictEqual(again.size, [800, 600]);
});

test('the focus slider spans an eighth to fifteen times the planes\' distance, as the viewer\'s', () => {
  const view = Object.assign(W.defaultView(meta), {breathing: false});
  // The planes 700 mm apart: 87.5 .. 10500 mm.
  assert.deepStrictEqual(W.focusRange(meta, view), {near: 87.5, far: 10500});
  // Breathing at f 500 cannot focus nearer than 525 mm: the range starts there.
  near(W.focusRange(meta, Object.assign({}, view, {breathing: true})).near, 525, 1e-9);
  // An imported rig in its own units, its st-plane 64 units from the cameras: 8 .. 960 units.
  const units = Object.assign({}, meta, {array: Object.assign({}, meta.array, {p_ca: [0, 0, 64]}),
                                         window: Object.assign({}, meta.window,
                                                               {origin: [-32, -32, 0]})});
  assert.deepStrictEqual(W.focusRange(units, view), {near: 8, far: 960});
  // The planes in one (no distance between them): the whole range a click searches.
  const flat = Object.assign({}, units, {array: Object.assign({}, units.array, {p_ca: [0, 0, 0]})});
  assert.deepStrictEqual(W.focusRange(flat, view), {near: 1e-3, far: 100000});
});

test('click-to-focus tries distances from the nearest focus outward, 1% apart', () => {
  const d = W.focusCandidates(525, 100000, 1.01);
  assert.strictEqual(d[0], 525);
  assert.ok(d[d.length - 1] <= 100000 && d[d.length - 1] * 1.01 > 100000);
  near(d[1] / d[0], 1.01, 1e-12);
});

test('the shader reads each camera along its line through the point in focus', () => {
  // The refocus model as the browser test's mutation checks it: p_o on the central ray at the
  // focus distance.
  assert.match(W.FRAGMENT, /vec3 po = u_eye \+ u_focus \* dir;/);
  assert.match(W.FRAGMENT, /stOf\(cameraCentre\(c\), po, st\)/);
});
