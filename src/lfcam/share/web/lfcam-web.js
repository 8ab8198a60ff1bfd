// lfcam's light field page (`lfcam export FILE --format web`): the paper's virtual camera in
// WebGL2, over the light field in lightfield.js (window.LFCAM_LIGHTFIELD). A classic script, so
// that the page opens from disk (file://) as well as from any static server; node's test runner
// loads the same file for the unit tests of its model (lfcam-web.test.js).
//
// The model is `lfcam render --integrator cameras` (docs/sharing.md): the eye on the array's
// plane looking along -n_ca (drag moves it within the array), the film at d_i (focus breathing)
// or f, each pixel's central ray through its point in focus p_o, and every camera under the
// aperture's footprint on the uv-plane (the lens disk itself, as the eye is on that plane) read
// along its own ray through p_o, weighted by the share of the disk its bilinear hat receives;
// a pinhole reads the four cameras around the eye, bilinearly weighted.
(function (root) {
  'use strict';

  // ---- vectors (arrays of three numbers) ----
  const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
  const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
  const scale = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                           a[0] * b[1] - a[1] * b[0]];
  const normalize = (a) => scale(a, 1 / Math.sqrt(dot(a, a)));

  const FILM_MM = 56;  // the film's width (the paper's)

  // The film's distance from the lens: d_i (1/d_i + 1/d_o = 1/f) with focus breathing, f without.
  function filmDistance(f, d, breathing) {
    return breathing ? 1 / (1 / f - 1 / d) : f;
  }

  // The nearest focus distance the camera allows (as lfcam's MinFocusDistance).
  function minFocusDistance(f, breathing) {
    return breathing ? 1.05 * f : 1e-3;
  }

  // The eye at array window coordinates (u, v) in [0, 1]^2 (the array's PRP window).
  function eyeAt(meta, u, v) {
    const a = meta.array;
    return add(a.p_ca, add(scale(a.u_ca, u * a.width_mm), scale(a.v_ca, v * a.height_mm)));
  }

  // The camera frame of a view: looking along -n_ca, up v_ca, as VirtualCamera builds it from
  // eye, look-at and up.
  function cameraFrame(meta, view) {
    const a = meta.array;
    const n = normalize(a.n_ca);
    const u = normalize(cross(a.v_ca, n));
    const v = cross(n, u);
    const tanX = 0.5 * FILM_MM / filmDistance(view.f, view.focus, view.breathing);
    return {eye: eyeAt(meta, view.u, view.v), n, u, v, tanX,
            tanY: tanX * view.height / view.width};
  }

  // The direction of the central ray through film position (x, y) (pixels, bottom-left origin;
  // its component along -n is 1), as VirtualCamera::direction_through.
  function directionThrough(frame, view, x, y) {
    return add(scale(frame.n, -1),
               add(scale(frame.u, frame.tanX * (2 * x / view.width - 1)),
                   scale(frame.v, frame.tanY * (2 * y / view.height - 1))));
  }

  // One axis of a clamped bilinear lookup (lfcam's AxisLerp).
  function axisLerp(x, n) {
    if (n === 1) return {i0: 0, i1: 0, w1: 0};
    x = Math.min(Math.max(x, 0), n - 1);
    const i = Math.min(Math.floor(x), n - 2);
    return {i0: i, i1: i + 1, w1: x - i};
  }

  // A camera's weight along one axis at grid position x (cameras at integers, window
  // [-0.5, n - 0.5]): the clamped bilinear lookup's tent, held at 1 out to the window's edge for
  // the outermost cameras, nothing outside the window.
  function hat(x, i, n) {
    if (x < -0.5 || x > n - 0.5) return 0;
    const l = axisLerp(x, n);
    return (l.i0 === i ? 1 - l.w1 : 0) + (l.i1 === i ? l.w1 : 0);
  }

  // Every camera's share of the disk of `radius` centred at (cx, cy) (grid units), normalised
  // to sum to 1: lfcam's DiskCameraWeights, integrated numerically on a `steps` x `steps`
  // lattice of cells over the disk's bounding square (the integrand is piecewise linear, so the
  // error is what the lattice misses at the disk's rim and the hats' kinks: about 1e-3 at the
  // default). A radius of 0 gives the bilinear weights at (cx, cy). Returns [{row, col, w}].
  function diskCameraWeights(radius, cx, cy, cols, rows, steps) {
    steps = steps || 256;
    const weights = new Float64Array(rows * cols);
    const addAt = (x, y, w) => {
      if (x < -0.5 || x > cols - 0.5 || y < -0.5 || y > rows - 0.5) return;
      const c = axisLerp(x, cols), r = axisLerp(y, rows);
      const wc = [1 - c.w1, c.w1], wr = [1 - r.w1, r.w1], ic = [c.i0, c.i1], ir = [r.i0, r.i1];
      for (let a = 0; a < 2; ++a)
        for (let b = 0; b < 2; ++b) weights[ir[a] * cols + ic[b]] += w * wr[a] * wc[b];
    };
    if (!(radius > 0)) {
      addAt(cx, cy, 1);
    } else {
      const h = 2 * radius / steps;
      for (let a = 0; a < steps; ++a) {
        const y = cy - radius + (a + 0.5) * h;
        for (let b = 0; b < steps; ++b) {
          const x = cx - radius + (b + 0.5) * h;
          if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= radius * radius) addAt(x, y, 1);
        }
      }
    }
    let total = 0;
    for (const w of weights) total += w;
    const out = [];
    if (!(total > 0)) return out;
    for (let i = 0; i < weights.length; ++i)
      if (weights[i] > 1e-9) out.push({row: Math.floor(i / cols), col: i % cols,
                                       w: weights[i] / total});
    return out;
  }

  // The cameras a view reads and their weights: the aperture's footprint on the uv-plane is the
  // lens disk (radius d_l / 2) centred on the eye, in grid units.
  function cameraWeights(meta, view) {
    const a = meta.array;
    const cx = view.u * a.cols - 0.5, cy = view.v * a.rows - 0.5;
    return diskCameraWeights(0.5 * view.aperture / a.pitch_mm, cx, cy, a.cols, a.rows);
  }

  // ---- the view: defaults, URL parameters, limits ----
  function defaultView(meta) {
    const c = meta.camera;
    return {u: 0.5, v: 0.5, f: c.focal_length_mm, focus: c.focus_distance_mm,
            aperture: c.aperture_mm, breathing: c.breathing !== false,
            width: c.width, height: c.height};
  }

  // The focus slider's range, as the viewer's (viewer/control_windows.cpp): an eighth to fifteen
  // times the distance between the light field's planes, never nearer than the camera can focus.
  // Over the 0.001 .. 100000 a click searches, a scene's depths (3 .. 7 m, or 48 .. 105 units)
  // took a twenty-fifth of the slider; here a fifth.
  function focusRange(meta, view) {
    const nearest = minFocusDistance(view.f, view.breathing);
    const a = meta.array;
    const separation = Math.abs(dot(sub(meta.window.origin, a.p_ca), a.n_ca));
    if (!(separation > 0)) return {near: nearest, far: 100000};
    return {near: Math.max(nearest, separation / 8), far: Math.max(15 * separation, 2 * nearest)};
  }

  // The largest aperture offered: the array's width.
  function maxAperture(meta) { return meta.array.width_mm; }

  // A view with every value brought inside what the camera allows (eye in the array's window,
  // focus beyond the film, aperture and focal length positive).
  function clampView(meta, view) {
    const out = Object.assign({}, view);
    out.u = Math.min(Math.max(out.u, 0), 1);
    out.v = Math.min(Math.max(out.v, 0), 1);
    out.f = Math.min(Math.max(out.f, 1), 100000);
    out.aperture = Math.min(Math.max(out.aperture, 0), maxAperture(meta));
    const near = minFocusDistance(out.f, out.breathing);
    out.focus = Math.min(Math.max(out.focus, near), 1e7);
    return out;
  }

  // The view the page's URL asks for: ?eye=U,V (the array window, 0..1), &f=MM, &focus=MM,
  // &aperture=MM, &breathing=0|1, &size=WxH (the canvas; otherwise the window's). Values that
  // do not parse are named in `errors` and left at their defaults.
  function parseView(search, meta, fallback) {
    const params = new URLSearchParams(search);
    const view = Object.assign({}, fallback || defaultView(meta));
    const errors = [];
    const number = (name, key) => {
      if (!params.has(name)) return;
      const x = Number(params.get(name));
      if (params.get(name).trim() === '' || !Number.isFinite(x)) errors.push(name);
      else view[key] = x;
    };
    number('f', 'f');
    number('focus', 'focus');
    number('aperture', 'aperture');
    if (params.has('eye')) {
      const parts = params.get('eye').split(',').map(Number);
      if (parts.length !== 2 || !parts.every(Number.isFinite)) errors.push('eye');
      else [view.u, view.v] = parts;
    }
    if (params.has('breathing')) view.breathing = params.get('breathing') !== '0';
    let size = null;
    if (params.has('size')) {
      const m = /^(\d+)(?:x(\d+))?$/.exec(params.get('size'));
      const w = m ? Number(m[1]) : 0, h = m ? Number(m[2] || m[1]) : 0;
      if (!(w >= 1 && h >= 1 && w <= 4096 && h <= 4096)) errors.push('size');
      else size = [w, h];
    }
    return {view: clampView(meta, view), size, errors, ui: params.get('ui') !== '0'};
  }

  // The URL parameters that give `view` back.
  function viewToSearch(view, size) {
    const r = (x) => String(Math.round(x * 1000) / 1000);
    let s = `?eye=${r(view.u)},${r(view.v)}&f=${r(view.f)}&focus=${r(view.focus)}` +
            `&aperture=${r(view.aperture)}&breathing=${view.breathing ? 1 : 0}`;
    if (size) s += `&size=${size[0]}x${size[1]}`;
    return s;
  }

  // Focus distances a click tries: from the nearest the camera allows to `far`, each `ratio`
  // beyond the last.
  function focusCandidates(near, far, ratio) {
    const out = [];
    for (let d = near; d <= far && out.length < 4096; d *= ratio) out.push(d);
    return out;
  }

  function megabytes(bytes) { return (bytes / 1e6).toFixed(1) + ' MB'; }

  // The uniforms one frame's draw takes, computed on the CPU from the view.
  function frameUniforms(meta, view) {
    const frame = cameraFrame(meta, view);
    const weights = cameraWeights(meta, view);
    return {frame, weights, pinhole: !(view.aperture > 0)};
  }

  // ---- WebGL2 ----
  const VERTEX = `#version 300 es
void main() {
  vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);
  gl_Position = vec4(p, 0.0, 1.0);
}`;

  // Shared by the frame and the focus probe: reading camera i along its line to a point.
  const LOOKUP = `
precision highp float;
precision highp int;
precision highp sampler2DArray;
uniform sampler2DArray u_views;
// Per camera i: texel (i, 0) its centre (world mm) and layer, (i, 1) its window's offset k, l.
uniform highp sampler2D u_cameras;
uniform vec3 u_stOrigin, u_stNormal, u_sScaled, u_tScaled;
uniform vec4 u_ref;    // s0, t0, samples per window unit along s, t
uniform vec4 u_union;  // the sampled domain: s0, t0, s1, t1
uniform vec2 u_n;      // samples per view, s and t
uniform bool u_windows;

// Window coordinates (s, t) where the line from c through p meets the st-plane; false when it
// runs parallel to it.
bool stOf(vec3 c, vec3 p, out vec2 st) {
  vec3 d = p - c;
  float nst = dot(u_stNormal, d);
  if (nst == 0.0) return false;
  vec3 at = c + (dot(u_stNormal, u_stOrigin - c) / nst) * d - u_stOrigin;
  st = vec2(dot(at, u_sScaled), dot(at, u_tScaled));
  return true;
}
bool inDomain(vec2 st) {
  return st.x >= u_union.x && st.x <= u_union.z && st.y >= u_union.y && st.y <= u_union.w;
}
vec3 cameraCentre(int i) { return texelFetch(u_cameras, ivec2(i, 0), 0).xyz; }
// Camera i read bilinearly (linear light) at window coordinates st; false outside its own window.
bool readCamera(int i, vec2 st, out vec3 rgb) {
  vec2 kl = (st - u_ref.xy) * u_ref.zw - 0.5 - texelFetch(u_cameras, ivec2(i, 1), 0).xy;
  if (u_windows && (any(lessThan(kl, vec2(-0.5))) || any(greaterThan(kl, u_n - 0.5))))
    return false;
  kl = clamp(kl, vec2(0.0), u_n - 1.0);
  // Image rows run top-down: sample row l is texture row n_t - 1 - l.
  vec2 uv = vec2((kl.x + 0.5) / u_n.x, 1.0 - (kl.y + 0.5) / u_n.y);
  rgb = texture(u_views, vec3(uv, texelFetch(u_cameras, ivec2(i, 0), 0).w)).rgb;
  return true;
}`;

  const FRAGMENT = `#version 300 es
${LOOKUP}
uniform vec2 u_size;
uniform vec3 u_eye, u_uc, u_vc, u_nc;
uniform vec2 u_tan;
uniform float u_focus;
uniform int u_count;
uniform vec4 u_weights[MAX_PAIRS];  // (camera, weight) pairs, two a vector
uniform bool u_pinhole;
out vec4 outColor;

float encode(float c) {
  c = clamp(c, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1.0 / 2.4) - 0.055;
}

void main() {
  vec2 px = gl_FragCoord.xy;  // pixel centres at +0.5, bottom-left origin: lfcam's film
  vec3 dir = -u_nc + u_tan.x * (2.0 * px.x / u_size.x - 1.0) * u_uc +
             u_tan.y * (2.0 * px.y / u_size.y - 1.0) * u_vc;
  vec3 po = u_eye + u_focus * dir;  // the pixel's point in focus
  vec2 st;
  // A pinhole's ray must meet the sampled st domain.
  if (u_pinhole && (!stOf(u_eye, po, st) || !inDomain(st))) {
    outColor = vec4(0.0, 0.0, 0.0, 1.0);
    return;
  }
  vec3 sum = vec3(0.0);
  float held = 0.0;
  for (int i = 0; i < u_count; ++i) {
    vec4 pair = u_weights[i / 2];
    int c = int((i % 2 == 0 ? pair.x : pair.z) + 0.5);
    float w = i % 2 == 0 ? pair.y : pair.w;
    if (!stOf(cameraCentre(c), po, st)) continue;
    // With an aperture, a camera whose line to p_o misses the domain does not count.
    if (!u_pinhole && !inDomain(st)) continue;
    vec3 rgb;
    if (!readCamera(c, st, rgb)) continue;
    sum += w * rgb;
    held += w;
  }
  vec3 linear = held > 0.0 ? sum / held : vec3(0.0);
  outColor = vec4(encode(linear.r), encode(linear.g), encode(linear.b), 1.0);
}`;

  // The focus probe (click to focus; lfcam's render/focus_probe.h): for candidate distance x
  // (one per output pixel), a patch of the plane of focus around the clicked pixel's ray is read
  // from every camera along its own ray; the cost is the spread of their colours there.
  const PROBE = `#version 300 es
${LOOKUP}
uniform int u_count;
uniform vec3 u_eye, u_dir, u_uc, u_vc;
uniform float u_near, u_logRatio, u_step;
out vec4 outCost;
void main() {
  float d = u_near * exp(u_logRatio * floor(gl_FragCoord.x));
  vec3 po = u_eye + d * u_dir;
  float cost = 0.0, seen = 0.0, points = 0.0;
  for (int a = -2; a <= 2; ++a)
    for (int b = -2; b <= 2; ++b) {
      vec3 p = po + (float(a) * u_step * d) * u_uc + (float(b) * u_step * d) * u_vc;
      vec3 sum = vec3(0.0), sum2 = vec3(0.0);
      float n = 0.0;
      for (int i = 0; i < u_count; ++i) {
        vec2 st;
        if (!stOf(cameraCentre(i), p, st) || !inDomain(st)) continue;
        vec3 rgb;
        if (!readCamera(i, st, rgb)) continue;
        rgb = sqrt(rgb);  // closer to what the eye compares
        sum += rgb;
        sum2 += rgb * rgb;
        n += 1.0;
      }
      if (n >= 2.0) {
        vec3 mean = sum / n;
        cost += dot(sum2 / n - mean * mean, vec3(1.0));
        points += 1.0;
        seen += n;
      }
    }
  outCost = vec4(points > 0.0 ? cost / points : 1e9, seen / max(points, 1.0), 0.0, 1.0);
}`;

  function compile(gl, source, type) {
    const shader = gl.createShader(type);
    gl.shaderSource(shader, source);
    gl.compileShader(shader);
    if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS))
      throw new Error('shader: ' + gl.getShaderInfoLog(shader));
    return shader;
  }

  function program(gl, fragment, cameras) {
    const p = gl.createProgram();
    gl.attachShader(p, compile(gl, VERTEX, gl.VERTEX_SHADER));
    gl.attachShader(p, compile(gl, fragment.replace(/MAX_PAIRS/g, String(Math.ceil(cameras / 2))),
                               gl.FRAGMENT_SHADER));
    gl.linkProgram(p);
    if (!gl.getProgramParameter(p, gl.LINK_STATUS))
      throw new Error('program: ' + gl.getProgramInfoLog(p));
    return p;
  }

  // The views' JPEGs (data URLs) decoded, in parallel, into layers of a texture array whose
  // texels the GPU decodes from sRGB before it filters (linear light, as lfcam blends).
  async function uploadViews(gl, meta) {
    const [w, h] = meta.view_size;
    const texture = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, texture);
    gl.texStorage3D(gl.TEXTURE_2D_ARRAY, 1, gl.SRGB8_ALPHA8, w, h, meta.views.length);
    gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_MIN_FILTER, gl.LINEAR);
    gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
    gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
    gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
    gl.pixelStorei(gl.UNPACK_COLORSPACE_CONVERSION_WEBGL, gl.NONE);
    const decode = async (url) => {
      const bytes = Uint8Array.from(atob(url.slice(url.indexOf(',') + 1)), (c) => c.charCodeAt(0));
      return createImageBitmap(new Blob([bytes], {type: 'image/jpeg'}),
                               {colorSpaceConversion: 'none', premultiplyAlpha: 'none'});
    };
    const bitmaps = await Promise.all(meta.views.map(decode));
    bitmaps.forEach((bitmap, layer) => {
      gl.texSubImage3D(gl.TEXTURE_2D_ARRAY, 0, 0, 0, layer, w, h, 1, gl.RGBA, gl.UNSIGNED_BYTE,
                       bitmap);
      bitmap.close();
    });
    return texture;
  }

  // The cameras' data texture (texture unit 1): per camera its centre and layer, its offset.
  function cameraTexture(gl, meta) {
    const count = meta.grid.rows * meta.grid.cols;
    const data = new Float32Array(8 * count);
    for (let i = 0; i < count; ++i) {
      data.set([...meta.centers[i], i], 4 * i);
      data.set(meta.offsets ? [meta.offsets[i][0], meta.offsets[i][1], 0, 0] : [0, 0, 0, 0],
               4 * (count + i));
    }
    const texture = gl.createTexture();
    gl.activeTexture(gl.TEXTURE1);
    gl.bindTexture(gl.TEXTURE_2D, texture);
    gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA32F, count, 2);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, count, 2, gl.RGBA, gl.FLOAT, data);
    gl.activeTexture(gl.TEXTURE0);
    return texture;
  }

  // The uniforms that depend on the light field alone.
  function setLightFieldUniforms(gl, p, meta) {
    const loc = (name) => gl.getUniformLocation(p, name);
    gl.useProgram(p);
    gl.uniform1i(loc('u_views'), 0);
    gl.uniform1i(loc('u_cameras'), 1);
    const win = meta.window, s = meta.sampling;
    gl.uniform3fv(loc('u_stOrigin'), win.origin);
    gl.uniform3fv(loc('u_stNormal'), normalize(cross(win.x_axis, win.y_axis)));
    gl.uniform3fv(loc('u_sScaled'), scale(win.x_axis, 1 / win.width_mm));
    gl.uniform3fv(loc('u_tScaled'), scale(win.y_axis, 1 / win.height_mm));
    gl.uniform4f(loc('u_ref'), s.s0, s.t0, s.n_s / (s.s1 - s.s0), s.n_t / (s.t1 - s.t0));
    gl.uniform4fv(loc('u_union'), meta.union);
    gl.uniform2f(loc('u_n'), s.n_s, s.n_t);
    gl.uniform1i(loc('u_windows'), meta.offsets ? 1 : 0);
  }

  // Starts the page's renderer on `canvas`. Returns the controller (also window.lfcam):
  // {ready: Promise, setView(partial), getView(), focusAt(x, y), draw()}.
  function start(meta, canvas, options) {
    options = options || {};
    const gl = canvas.getContext('webgl2', {preserveDrawingBuffer: true, antialias: false,
                                            alpha: false});
    if (!gl) throw new Error('this browser has no WebGL2');
    const cameras = meta.grid.rows * meta.grid.cols;
    const frameProgram = program(gl, FRAGMENT, cameras);
    const probeProgram = program(gl, PROBE, cameras);
    setLightFieldUniforms(gl, frameProgram, meta);
    setLightFieldUniforms(gl, probeProgram, meta);
    cameraTexture(gl, meta);
    gl.bindVertexArray(gl.createVertexArray());
    let view = clampView(meta, options.view || defaultView(meta));
    let texture = null;
    const listeners = [];
    const state = {frames: 0, lastFrameMs: 0, firstPictureMs: null};

    function draw() {
      if (!texture) return;
      const t0 = performance.now();
      view.width = canvas.width;
      view.height = canvas.height;
      const u = frameUniforms(meta, view);
      const loc = (name) => gl.getUniformLocation(frameProgram, name);
      gl.useProgram(frameProgram);
      gl.viewport(0, 0, canvas.width, canvas.height);
      gl.uniform2f(loc('u_size'), canvas.width, canvas.height);
      gl.uniform3fv(loc('u_eye'), u.frame.eye);
      gl.uniform3fv(loc('u_uc'), u.frame.u);
      gl.uniform3fv(loc('u_vc'), u.frame.v);
      gl.uniform3fv(loc('u_nc'), u.frame.n);
      gl.uniform2f(loc('u_tan'), u.frame.tanX, u.frame.tanY);
      gl.uniform1f(loc('u_focus'), view.focus);
      gl.uniform1i(loc('u_pinhole'), u.pinhole ? 1 : 0);
      gl.uniform1i(loc('u_count'), u.weights.length);
      const pairs = new Float32Array(4 * Math.ceil(cameras / 2));
      u.weights.forEach((c, i) => pairs.set([c.row * meta.grid.cols + c.col, c.w], 2 * i));
      gl.uniform4fv(loc('u_weights'), pairs);
      gl.drawArrays(gl.TRIANGLES, 0, 3);
      gl.finish();  // frames are drawn on demand: waiting for each says what it cost
      state.frames += 1;
      state.lastFrameMs = performance.now() - t0;
      if (state.firstPictureMs === null) state.firstPictureMs = performance.now();
      listeners.forEach((f) => f(view, state));
    }

    let pending = false;
    function requestDraw() {
      if (pending) return;
      pending = true;
      requestAnimationFrame(() => { pending = false; draw(); });
    }

    // The focus distance at canvas pixel (x, y) (CSS pixels from the top-left), or null.
    function focusAt(x, y) {
      if (!texture || !gl.getExtension('EXT_color_buffer_float')) return null;
      const frame = cameraFrame(meta, view);
      const fx = x * canvas.width / canvas.clientWidth;
      const fy = canvas.height - y * canvas.height / canvas.clientHeight;
      const dir = directionThrough(frame, view, fx, fy);
      const loc = (name) => gl.getUniformLocation(probeProgram, name);
      // The patch: 5 x 5 points 3 st samples' spacing apart at the st-plane's distance, the
      // same angle at every candidate.
      const stDistance = Math.abs(dot(sub(meta.window.origin, frame.eye), frame.n));
      const sample = meta.window.width_mm * (meta.sampling.s1 - meta.sampling.s0) /
                     meta.sampling.n_s;
      const run = (near, ratio, count) => {
        const target = gl.createTexture();
        gl.bindTexture(gl.TEXTURE_2D, target);
        gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA32F, count, 1);
        const fb = gl.createFramebuffer();
        gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
        gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, target, 0);
        gl.useProgram(probeProgram);
        gl.activeTexture(gl.TEXTURE0);
        gl.bindTexture(gl.TEXTURE_2D_ARRAY, texture);
        gl.viewport(0, 0, count, 1);
        gl.uniform1i(loc('u_count'), cameras);
        gl.uniform3fv(loc('u_eye'), frame.eye);
        gl.uniform3fv(loc('u_dir'), dir);
        gl.uniform3fv(loc('u_uc'), frame.u);
        gl.uniform3fv(loc('u_vc'), frame.v);
        gl.uniform1f(loc('u_near'), near);
        gl.uniform1f(loc('u_logRatio'), Math.log(ratio));
        gl.uniform1f(loc('u_step'), 3 * sample / stDistance);
        gl.drawArrays(gl.TRIANGLES, 0, 3);
        const out = new Float32Array(4 * count);
        gl.readPixels(0, 0, count, 1, gl.RGBA, gl.FLOAT, out);
        gl.bindFramebuffer(gl.FRAMEBUFFER, null);
        gl.deleteFramebuffer(fb);
        gl.deleteTexture(target);
        let best = -1;
        for (let i = 0; i < count; ++i)
          if (out[4 * i + 1] >= 2 && (best < 0 || out[4 * i] < out[4 * best])) best = i;
        return best < 0 ? null : near * Math.pow(ratio, best);
      };
      const near = minFocusDistance(view.f, view.breathing);
      const coarse = run(near, 1.01, focusCandidates(near, 100000, 1.01).length);
      if (coarse === null) return null;
      const fine = run(coarse / 1.01, 1.0005, 41);
      return fine === null ? coarse : fine;
    }

    const controller = {
      meta,
      state,
      getView: () => Object.assign({}, view),
      setView(partial) {
        view = clampView(meta, Object.assign({}, view, partial));
        requestDraw();
        return controller.getView();
      },
      focusAt(x, y) {
        const d = focusAt(x, y);
        if (d !== null) controller.setView({focus: d});
        return d;
      },
      draw,
      onDraw: (f) => listeners.push(f),
      ready: null,
    };
    controller.ready = uploadViews(gl, meta).then((t) => {
      texture = t;
      gl.activeTexture(gl.TEXTURE0);
      gl.bindTexture(gl.TEXTURE_2D_ARRAY, texture);
      draw();
      return controller;
    });
    return controller;
  }

  const api = {
    add, sub, scale, dot, cross, normalize, filmDistance, minFocusDistance, eyeAt, cameraFrame,
    directionThrough, axisLerp, hat, diskCameraWeights, cameraWeights, defaultView, clampView,
    focusRange, maxAperture, parseView, viewToSearch, focusCandidates, megabytes, frameUniforms, start,
    FRAGMENT, PROBE,
  };
  if (typeof module !== 'undefined' && module.exports) module.exports = api;
  else root.LfcamWeb = api;
})(typeof window !== 'undefined' ? window : globalThis);
