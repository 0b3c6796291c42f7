// The mocapsolve page viewer (inlined into every page by viewer/view_page.cc).
//
// Reads the page's data (the JSON header #mv-meta and the base64 arrays #mv-blob-N, see
// view_page.h), builds one three.js scene in the page's world (metres, +Y up): markers
// as points coloured by state, skeletons as bones, characters (glTF, skinned, animated
// by three.js' GLTFLoader/AnimationMixer) beside the source; a timeline below.
//
// For tests and scripts: window.mocapsolveView = {ready, frames, frame, setFrame(i),
// play(), pause(), playing, renders, stateNames, stateColors, markerScreen(label), error}:
// ready turns true once everything is loaded and frame 0 is drawn; setFrame(i) draws
// frame i before it returns.
(function () {
  'use strict';
  const view = (window.mocapsolveView = {
    ready: false, frames: 0, frame: 0, playing: false, renders: 0, error: null,
    setFrame: function () {}, play: function () {}, pause: function () {},
  });
  const STATE_COLORS = ['#4cc9f0', '#7b8794', '#ffb703', '#ff4d6d', '#c77dff', '#80ed99', '#f8f9fa'];
  const SKELETON_COLORS = ['#e9ecef', '#f4a261', '#90be6d'];
  const GHOST_COLOR = '#7aa7ff';
  const CURVE_COLORS = ['#f72585', '#4cc9f0', '#b5e48c', '#ffd166'];
  view.stateColors = STATE_COLORS.slice();

  const info = document.getElementById('mv-info');
  function fail(error) {
    view.error = String(error && error.stack ? error.stack : error);
    console.error('mocapsolve view:', error);
    info.textContent = 'mocapsolve view: ' + (error && error.message ? error.message : error);
  }

  try {
    start();
  } catch (error) {
    fail(error);
  }

  function start() {
    const THREE = window.MOCAPSOLVE_THREE;
    if (!THREE) throw new Error('three.js runtime missing from the page');
    const t0 = performance.now();
    view.timings = { script_start_ms: t0 };  // Since navigation started.
    const meta = JSON.parse(document.getElementById('mv-meta').textContent);
    inflateBlobs(meta).then(function (blobs) {
      view.timings.inflated_ms = performance.now() - t0;
      show(THREE, meta, blobs, t0);
    }).catch(fail);
  }

  // Every array the header references, base64-decoded and inflated (gzip, natively by
  // DecompressionStream, all at once): blob index -> Uint8Array.
  function inflateBlobs(meta) {
    const refs = [];
    meta.markers.forEach(function (m) { refs.push(m.positions, m.states); });
    meta.skeletons.forEach(function (s) { refs.push(s.positions); });
    meta.curves.forEach(function (c) { refs.push(c.values); });
    meta.characters.forEach(function (c) { refs.push(c.glb); });
    const blobs = new Map();
    return Promise.all(refs.map(function (ref) {
      const text = document.getElementById('mv-blob-' + ref.blob).textContent.trim();
      let bytes;
      if (typeof Uint8Array.fromBase64 === 'function') {
        bytes = Uint8Array.fromBase64(text);
      } else {
        const binary = atob(text);
        bytes = new Uint8Array(binary.length);
        for (let i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
      }
      if (!ref.compression) return blobs.set(ref.blob, bytes);
      if (ref.compression !== 'gzip') throw new Error('array ' + ref.blob + ': unknown compression ' + ref.compression);
      const stream = new Response(bytes).body.pipeThrough(new DecompressionStream('gzip'));
      return new Response(stream).arrayBuffer().then(function (buffer) { blobs.set(ref.blob, new Uint8Array(buffer)); });
    })).then(function () { return blobs; });
  }

  function show(THREE, meta, blobs, t0) {
    const fps = meta.frame_rate;
    view.stateNames = meta.state_names.slice();

    // ---- data --------------------------------------------------------------------
    function blobBytes(ref) {
      return blobs.get(ref.blob);
    }
    // Positions: int16 steps from the previous frame (ref.delta values back), summed in
    // place (Int16Array wraps as the writer did), then scaled; -32768 = NaN.
    function positions(ref) {
      const bytes = blobBytes(ref);
      const q = new Int16Array(bytes.buffer, bytes.byteOffset, bytes.byteLength >> 1);
      const delta = ref.delta || 0;
      if (delta > 0) for (let i = delta; i < q.length; ++i) q[i] += q[i - delta];
      const out = new Float32Array(q.length);
      const o = ref.origin, s = ref.step;
      for (let i = 0; i < q.length; i += 3) {
        for (let k = 0; k < 3; ++k) {
          const v = q[i + k];
          out[i + k] = v === -32768 ? NaN : o[k] + s[k] * v;
        }
      }
      return out;
    }
    function floats(ref) {
      const bytes = blobBytes(ref);
      return new Float32Array(bytes.slice().buffer);
    }

    // Marker sets: positions with missing samples held at the nearest valid one (drawn
    // in the missing colour), states.
    const markerSets = meta.markers.map(function (m) {
      const xyz = positions(m.positions);
      const states = blobBytes(m.states);
      const count = m.labels.length;
      const shown = new Float32Array(xyz);
      const visible = new Uint8Array(m.frames * count);
      for (let j = 0; j < count; ++j) {
        let last = -1;
        for (let f = 0; f < m.frames; ++f) {
          const i = f * count + j;
          if (!isNaN(xyz[3 * i])) last = f;
          else if (last >= 0) shown.copyWithin(3 * i, 3 * (last * count + j), 3 * (last * count + j) + 3);
        }
        let next = -1;
        for (let f = m.frames - 1; f >= 0; --f) {
          const i = f * count + j;
          if (!isNaN(xyz[3 * i])) next = f;
          else if (isNaN(shown[3 * i]) && next >= 0) shown.copyWithin(3 * i, 3 * (next * count + j), 3 * (next * count + j) + 3);
          visible[i] = isNaN(shown[3 * i]) ? 0 : 1;
        }
      }
      return { name: m.name, labels: m.labels, frames: m.frames, count: count, xyz: xyz, shown: shown,
               visible: visible, states: states };
    });
    const skeletons = meta.skeletons.map(function (s) {
      return { name: s.name, joints: s.joints, parents: s.parents, frames: s.frames, ghost: s.ghost,
               xyz: positions(s.positions) };
    });
    const curves = meta.curves.map(function (c) {
      const values = floats(c.values);
      let max = 0;
      for (const v of values) if (isFinite(v)) max = Math.max(max, Math.abs(v));
      return { name: c.name, unit: c.unit, values: values, max: max > 0 ? max : 1 };
    });

    // ---- scene -------------------------------------------------------------------
    const canvas = document.getElementById('mv-canvas');
    // A software WebGL (SwiftShader, llvmpipe: no GPU, or a headless browser) gets no
    // multisampling, one pixel per CSS pixel, and characters skinned and lit (Lambert, per
    // vertex) on the CPU (makeCpuSkin): several times the frame rate, for a little less polish.
    const software = (function () {
      try {
        const probe = document.createElement('canvas').getContext('webgl2') ||
                      document.createElement('canvas').getContext('webgl');
        const debug = probe && probe.getExtension('WEBGL_debug_renderer_info');
        const name = debug ? String(probe.getParameter(debug.UNMASKED_RENDERER_WEBGL)) : '';
        const lose = probe && probe.getExtension('WEBGL_lose_context');
        if (lose) lose.loseContext();
        return /swiftshader|llvmpipe|software/i.test(name);
      } catch (e) {
        return false;
      }
    })();
    view.softwareRendering = software;
    view.three = { THREE: THREE };  // renderer, scene, camera, characters: for scripts.
    const renderer = new THREE.WebGLRenderer({ canvas: canvas, antialias: !software, preserveDrawingBuffer: true });
    renderer.setPixelRatio(software ? 1 : Math.min(window.devicePixelRatio || 1, 2));
    const scene = new THREE.Scene();
    scene.background = new THREE.Color('#1d2127');
    const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 2000);
    const hemisphere = new THREE.HemisphereLight(0xffffff, 0x445566, 2.0);
    scene.add(hemisphere);
    const sun = new THREE.DirectionalLight(0xffffff, 2.0);
    sun.position.set(3, 6, 4);
    scene.add(sun);

    // The source's box over the whole take (subsampled), for the grid, camera and layout.
    const box = new THREE.Box3();
    const first = new THREE.Box3();  // Frame 0 only: where characters stand beside it.
    function addPoints(xyz, stride, frames, perFrame) {
      const step = Math.max(1, Math.floor(frames / 300));
      for (let f = 0; f < frames; f += step) {
        for (let j = 0; j < perFrame; ++j) {
          const i = 3 * (f * perFrame + j);
          if (isNaN(xyz[i])) continue;
          const p = new THREE.Vector3(xyz[i], xyz[i + 1], xyz[i + 2]);
          box.expandByPoint(p);
          if (f === 0) first.expandByPoint(p);
        }
      }
    }
    markerSets.forEach(function (m) { addPoints(m.xyz, 3, m.frames, m.count); });
    skeletons.forEach(function (s) { addPoints(s.xyz, 3, s.frames, s.joints.length); });

    // Round point sprites: white disc, the vertex colour shows unchanged at its centre.
    function discTexture() {
      const c = document.createElement('canvas');
      c.width = c.height = 64;
      const g = c.getContext('2d');
      g.fillStyle = '#fff';
      g.beginPath();
      g.arc(32, 32, 30, 0, 2 * Math.PI);
      g.fill();
      return new THREE.CanvasTexture(c);
    }
    const disc = discTexture();
    const stateColors = STATE_COLORS.map(function (c) { return new THREE.Color(c); });

    const markerObjects = markerSets.map(function (m, index) {
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(3 * m.count), 3));
      geometry.setAttribute('color', new THREE.BufferAttribute(new Float32Array(3 * m.count), 3));
      const ghost = index > 0;
      const material = new THREE.PointsMaterial({
        size: ghost ? 7 : 10, sizeAttenuation: false, vertexColors: true, map: disc, alphaTest: 0.5,
        // All in the transparent pass, which orders by renderOrder: the take's markers are
        // drawn last, over the bones and over the ghosted ones.
        depthTest: false, transparent: true, opacity: ghost ? 0.55 : 1.0,
      });
      const points = new THREE.Points(geometry, material);
      points.renderOrder = ghost ? 5 : 10;
      points.frustumCulled = false;
      scene.add(points);
      return points;
    });

    // Bones: one unit cylinder per joint with a parent, stretched between the two.
    const unitBone = new THREE.CylinderGeometry(1, 1, 1, 8, 1);
    unitBone.translate(0, 0.5, 0);
    const skeletonObjects = skeletons.map(function (s, index) {
      const color = s.ghost ? GHOST_COLOR : SKELETON_COLORS[index % SKELETON_COLORS.length];
      const material = new THREE.MeshLambertMaterial({
        color: color, transparent: s.ghost, opacity: s.ghost ? 0.4 : 1.0, depthWrite: !s.ghost,
      });
      const bones = new THREE.InstancedMesh(unitBone, material, Math.max(1, s.joints.length));
      bones.frustumCulled = false;
      scene.add(bones);
      return bones;
    });
    const extent = box.isEmpty() ? 1.8 : Math.max(0.5, box.max.y - box.min.y);
    const boneRadius = 0.012 * Math.max(1, extent / 1.8);

    const floorY = box.isEmpty() ? 0 : box.min.y;
    const characters = [];

    // ---- frame update ------------------------------------------------------------
    const up = new THREE.Vector3(0, 1, 0);
    const a = new THREE.Vector3(), b = new THREE.Vector3(), d = new THREE.Vector3();
    const q = new THREE.Quaternion(), s3 = new THREE.Vector3(), matrix = new THREE.Matrix4();
    const hidden = new THREE.Matrix4().makeScale(0, 0, 0);

    // Points are written observed first, then the others (repaired, missing), so that a
    // marker in a notable state is drawn over its observed neighbours; slot[k] is the
    // marker in point k (for picking).
    markerSets.forEach(function (m) { m.slot = new Int32Array(m.count); });
    function updateFrame(frame) {
      markerSets.forEach(function (m, index) {
        const f = Math.min(frame, m.frames - 1);
        const geometry = markerObjects[index].geometry;
        const pos = geometry.attributes.position.array, col = geometry.attributes.color.array;
        let k = 0;
        for (let pass = 0; pass < 2; ++pass) {
          for (let j = 0; j < m.count; ++j) {
            const i = f * m.count + j;
            const observed = f < 0 || m.states[i] === 0;
            if (observed !== (pass === 0)) continue;
            m.slot[k] = j;
            if (f < 0 || !m.visible[i]) {
              pos[3 * k] = pos[3 * k + 1] = pos[3 * k + 2] = 1e9;  // Outside the view.
              ++k;
              continue;
            }
            pos[3 * k] = m.shown[3 * i]; pos[3 * k + 1] = m.shown[3 * i + 1]; pos[3 * k + 2] = m.shown[3 * i + 2];
            const c = stateColors[Math.min(m.states[i], stateColors.length - 1)];
            col[3 * k] = c.r; col[3 * k + 1] = c.g; col[3 * k + 2] = c.b;
            ++k;
          }
        }
        geometry.attributes.position.needsUpdate = true;
        geometry.attributes.color.needsUpdate = true;
      });
      skeletons.forEach(function (s, index) {
        const f = Math.min(frame, s.frames - 1);
        const bones = skeletonObjects[index];
        const count = s.joints.length;
        for (let j = 0; j < count; ++j) {
          const p = s.parents[j];
          if (p < 0 || f < 0) { bones.setMatrixAt(j, hidden); continue; }
          const i = 3 * (f * count + j), k = 3 * (f * count + p);
          a.set(s.xyz[k], s.xyz[k + 1], s.xyz[k + 2]);
          b.set(s.xyz[i], s.xyz[i + 1], s.xyz[i + 2]);
          d.subVectors(b, a);
          const length = d.length();
          if (!(length > 1e-6)) { bones.setMatrixAt(j, hidden); continue; }
          q.setFromUnitVectors(up, d.divideScalar(length));
          s3.set(boneRadius, length, boneRadius);
          matrix.compose(a, q, s3);
          bones.setMatrixAt(j, matrix);
        }
        bones.instanceMatrix.needsUpdate = true;
      });
      const t = frame / fps;
      characters.forEach(function (c) {
        // Held at its last pose after the clip's end (a looping action would wrap to 0 there).
        c.mixer.setTime(Math.min(t, c.clip.duration * (1 - 1e-7)));
        if (c.skins.length) {
          c.root.updateMatrixWorld(true);
          c.skins.forEach(cpuSkin);
        }
      });
    }

    Object.assign(view.three, { renderer: renderer, scene: scene, camera: camera, characters: characters });
    function render() {
      renderer.render(scene, camera);
      view.renders++;
    }

    // ---- layout, camera ----------------------------------------------------------
    function resize() {
      const main = document.getElementById('mv-main');
      const w = Math.max(1, main.clientWidth), h = Math.max(1, main.clientHeight);
      renderer.setSize(w, h, false);
      camera.aspect = w / h;
      camera.updateProjectionMatrix();
      drawTimeline();
    }

    function frameCamera(content) {
      const center = content.getCenter(new THREE.Vector3());
      const size = content.getSize(new THREE.Vector3());
      const radius = Math.max(0.5, 0.5 * size.length());
      const distance = radius / Math.sin(THREE.MathUtils.degToRad(camera.fov / 2)) * 0.9;
      camera.position.set(center.x + 0.35 * distance, center.y + 0.3 * distance, center.z + 0.9 * distance);
      camera.near = Math.max(0.01, distance / 1000);
      camera.far = distance * 20 + 100;
      camera.updateProjectionMatrix();
      controls.target.copy(center);
      controls.update();
    }

    const controls = new THREE.OrbitControls(camera, canvas);
    controls.enableDamping = false;
    controls.addEventListener('change', function () { if (!view.playing) render(); });

    // ---- UI ----------------------------------------------------------------------
    const slider = document.getElementById('mv-slider');
    const frameText = document.getElementById('mv-frame');
    const playButton = document.getElementById('mv-play');
    const timeline = document.getElementById('mv-timeline');
    const tip = document.getElementById('mv-tip');
    let selected = -1;  // Marker of markerSets[0] picked by a click.

    const intervalRows = [];  // Markers of markerSets[0] with repaired intervals, in order.
    (function () {
      const seen = new Set();
      meta.intervals.forEach(function (i) { seen.add(i[0]); });
      Array.from(seen).sort(function (x, y) { return x - y; }).forEach(function (m) { intervalRows.push(m); });
    })();
    const rowPixels = intervalRows.length <= 16 ? 10 : 6;  // Rows of 10 px carry their label.
    timeline.style.height = Math.max(24, Math.min(260, (curves.length ? 70 : 8) + rowPixels * intervalRows.length)) + 'px';

    function legend() {
      const used = new Uint8Array(256);  // A histogram: a Set over 10^6 states takes tens of ms.
      markerSets.forEach(function (m) { for (let i = 0; i < m.states.length; ++i) used[m.states[i]] = 1; });
      let html = '';
      meta.state_names.forEach(function (name, s) {
        if (used[s]) html += '<span class="sw" style="background:' + STATE_COLORS[s] + '"></span>' + name;
      });
      skeletons.forEach(function (s, index) {
        const color = s.ghost ? GHOST_COLOR : SKELETON_COLORS[index % SKELETON_COLORS.length];
        html += '<br><span class="sw" style="background:' + color + '"></span>' + escapeHtml(s.name) + (s.ghost ? ' (compare)' : '');
      });
      characters.forEach(function (c) { html += '<br>' + escapeHtml(c.name) + ': ' + escapeHtml(c.clip.name || 'clip'); });
      document.getElementById('mv-legend').innerHTML = html;
    }
    function escapeHtml(text) {
      return String(text).replace(/[&<>"]/g, function (c) { return { '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' }[c]; });
    }
    function updateInfo() {
      let text = '<b>' + escapeHtml(meta.title || 'mocapsolve view') + '</b>';
      meta.notes.forEach(function (n) { text += '\n' + escapeHtml(n); });
      if (selected >= 0 && markerSets.length) {
        const m = markerSets[0], i = view.frame * m.count + selected;
        const state = view.frame < m.frames ? meta.state_names[m.states[i]] : 'no sample';
        text += '\nselected: ' + escapeHtml(m.labels[selected]) + ' (' + state + ')';
      }
      info.innerHTML = text;
    }

    // The timeline: curves and interval bars drawn once into `background` (again on a
    // resize, a selection or a change of the frame count), then per frame copied with the
    // playhead and the curves' current values over it.
    let background = null, backgroundKey = '';
    function drawTimelineBackground(w, h, ratio) {
      const layer = document.createElement('canvas');
      layer.width = Math.round(w * ratio);
      layer.height = Math.round(h * ratio);
      const g = layer.getContext('2d');
      g.setTransform(ratio, 0, 0, ratio, 0, 0);
      const x = timelineX(w);
      // Curves, each scaled to its own maximum, in the top lane.
      curves.forEach(function (c, index) {
        g.strokeStyle = CURVE_COLORS[index % CURVE_COLORS.length];
        g.beginPath();
        let pen = false;
        const step = Math.max(1, Math.floor(c.values.length / (2 * w)));
        for (let f = 0; f < c.values.length; f += step) {
          const v = c.values[f];
          if (!isFinite(v)) { pen = false; continue; }
          const y = 4 + CURVE_LANE * (1 - Math.abs(v) / c.max);
          if (pen) g.lineTo(x(f), y); else g.moveTo(x(f), y);
          pen = true;
        }
        g.stroke();
      });
      // Repaired intervals: one row per marker, bars in the reason's colour.
      const top = curves.length ? CURVE_LANE + 22 : 4;
      const rowHeight = intervalRows.length ? Math.max(2, Math.min(rowPixels, (h - top - 2) / intervalRows.length)) : 0;
      const row = new Map();
      intervalRows.forEach(function (m, r) { row.set(m, r); });
      g.font = '9px system-ui, sans-serif';
      intervalRows.forEach(function (m, r) {
        if (rowHeight >= 9 && markerSets.length) {
          g.fillStyle = m === selected ? '#fff' : '#8d99ae';
          g.fillText(markerSets[0].labels[m] || String(m), 2, top + r * rowHeight + rowHeight);
        }
      });
      meta.intervals.forEach(function (i) {
        const r = row.get(i[0]);
        g.fillStyle = STATE_COLORS[i[3]] || STATE_COLORS[2];
        g.fillRect(x(i[1]), top + r * rowHeight, Math.max(1.5, x(i[2] + 1) - x(i[1])), Math.max(1, rowHeight - 1));
      });
      return layer;
    }
    const CURVE_LANE = 44;
    function timelineX(w) {
      const n = Math.max(1, view.frames - 1), left = 70, width = Math.max(1, w - left - 8);
      return function (f) { return left + width * f / n; };
    }
    function drawTimeline() {
      const w = timeline.clientWidth, h = timeline.clientHeight;
      if (w < 1 || h < 1) return;  // Hidden, or a window of no size.
      const ratio = window.devicePixelRatio || 1;
      if (timeline.width !== Math.round(w * ratio) || timeline.height !== Math.round(h * ratio)) {
        timeline.width = Math.round(w * ratio);
        timeline.height = Math.round(h * ratio);
      }
      const key = [w, h, ratio, view.frames, selected].join(',');
      if (key !== backgroundKey) {
        background = drawTimelineBackground(w, h, ratio);
        backgroundKey = key;
      }
      const g = timeline.getContext('2d');
      g.setTransform(1, 0, 0, 1, 0, 0);
      g.clearRect(0, 0, timeline.width, timeline.height);
      g.drawImage(background, 0, 0);
      g.setTransform(ratio, 0, 0, ratio, 0, 0);
      g.font = '11px system-ui, sans-serif';
      curves.forEach(function (c, index) {
        const now = c.values[Math.min(view.frame, c.values.length - 1)];
        g.fillStyle = CURVE_COLORS[index % CURVE_COLORS.length];
        g.fillText(c.name + ' ' + (isFinite(now) ? now.toPrecision(3) : '-') + (c.unit ? ' ' + c.unit : ''),
                   70 + 4 + 170 * index, CURVE_LANE + 16);
      });
      g.fillStyle = '#ffffff';  // Playhead.
      g.fillRect(timelineX(w)(view.frame) - 0.5, 0, 1.5, h);
    }

    function showFrameText() {
      const total = Math.max(0, view.frames - 1);
      frameText.textContent = 'frame ' + view.frame + ' / ' + total + '   ' + (view.frame / fps).toFixed(3) + ' s';
      slider.value = String(view.frame);
    }

    // Follow: the camera keeps its offset from the take's centre (the first skeleton's
    // root, else the mean of the visible markers), so a long walk stays in view. The
    // offset is path-independent: a frame looks the same however it was reached.
    const followBox = document.getElementById('mv-follow');
    let followed = null;  // The centre the camera was last placed for.
    function takeCentre(frame) {
      if (skeletons.length && skeletons[0].frames > 0) {
        const s = skeletons[0], f = Math.min(frame, s.frames - 1), i = 3 * f * s.joints.length;
        return new THREE.Vector3(s.xyz[i], 0, s.xyz[i + 2]);
      }
      if (markerSets.length && markerSets[0].frames > 0) {
        const m = markerSets[0], f = Math.min(frame, m.frames - 1), c = new THREE.Vector3();
        let n = 0;
        for (let j = 0; j < m.count; ++j) {
          const i = 3 * (f * m.count + j);
          if (!m.visible[f * m.count + j]) continue;
          c.x += m.shown[i]; c.z += m.shown[i + 2]; ++n;
        }
        return n ? c.divideScalar(n) : null;
      }
      return null;
    }
    function follow(frame) {
      const centre = takeCentre(frame);
      if (!centre) return;
      if (followed && followBox.checked) {
        const delta = centre.clone().sub(followed);
        camera.position.add(delta);
        controls.target.add(delta);
        controls.update();
      }
      followed = centre;
    }
    followBox.addEventListener('change', function () { followed = takeCentre(view.frame); canvas.focus(); });

    function setFrame(i) {
      const frame = Math.max(0, Math.min(view.frames - 1, Math.round(Number(i) || 0)));
      view.frame = frame;
      updateFrame(frame);
      follow(frame);
      render();
      drawTimeline();  // Before the text changes: its size read then needs no new layout.
      showFrameText();
      updateInfo();
      return frame;
    }
    view.setFrame = setFrame;

    let playStart = 0, playFrom = 0;
    function tick(now) {
      if (!view.playing) return;
      const frame = (playFrom + Math.floor((now - playStart) * fps / 1000)) % Math.max(1, view.frames);
      view.frame = frame;
      updateFrame(frame);
      follow(frame);
      render();
      drawTimeline();
      showFrameText();
      requestAnimationFrame(tick);
    }
    view.play = function () {
      if (view.playing || view.frames < 2) return;
      view.playing = true;
      playButton.innerHTML = '&#10074;&#10074;';
      playStart = performance.now();
      playFrom = view.frame;
      requestAnimationFrame(tick);
    };
    view.pause = function () {
      view.playing = false;
      playButton.innerHTML = '&#9654;';
      setFrame(view.frame);
    };
    playButton.addEventListener('click', function () { view.playing ? view.pause() : view.play(); });
    document.getElementById('mv-prev').addEventListener('click', function () { view.pause(); setFrame(view.frame - 1); });
    document.getElementById('mv-next').addEventListener('click', function () { view.pause(); setFrame(view.frame + 1); });
    slider.addEventListener('input', function () {
      if (view.playing) view.pause();
      setFrame(slider.value);
    });
    window.addEventListener('keydown', function (e) {
      if (e.target && e.target.tagName === 'INPUT' && e.target.type !== 'range') return;
      if (e.key === ' ') { view.playing ? view.pause() : view.play(); e.preventDefault(); }
      else if (e.key === 'ArrowLeft') { view.pause(); setFrame(view.frame - (e.shiftKey ? 10 : 1)); }
      else if (e.key === 'ArrowRight') { view.pause(); setFrame(view.frame + (e.shiftKey ? 10 : 1)); }
      else if (e.key === 'f') { followBox.checked = !followBox.checked; followed = takeCentre(view.frame); }
    });
    function scrub(e) {
      const rect = timeline.getBoundingClientRect();
      const left = 70, width = Math.max(1, rect.width - left - 8);
      if (view.playing) view.pause();
      setFrame((e.clientX - rect.left - left) / width * Math.max(1, view.frames - 1));
    }
    timeline.addEventListener('pointerdown', function (e) {
      scrub(e);
      timeline.setPointerCapture(e.pointerId);
      timeline.onpointermove = scrub;
    });
    timeline.addEventListener('pointerup', function () { timeline.onpointermove = null; });

    // Hover names a marker; a click keeps it selected.
    const raycaster = new THREE.Raycaster();
    const pointer = new THREE.Vector2();
    function pick(e) {
      if (!markerObjects.length) return -1;
      const rect = canvas.getBoundingClientRect();
      pointer.set((e.clientX - rect.left) / rect.width * 2 - 1, -(e.clientY - rect.top) / rect.height * 2 + 1);
      raycaster.setFromCamera(pointer, camera);
      raycaster.params.Points.threshold = 0.02 * camera.position.distanceTo(controls.target);
      const hits = raycaster.intersectObject(markerObjects[0]);
      return hits.length ? markerSets[0].slot[hits[0].index] : -1;
    }
    canvas.addEventListener('pointermove', function (e) {
      const j = pick(e);
      if (j < 0) { tip.style.display = 'none'; return; }
      const m = markerSets[0], f = Math.min(view.frame, m.frames - 1);
      tip.textContent = m.labels[j] + ' (' + meta.state_names[m.states[f * m.count + j]] + ')';
      const rect = canvas.getBoundingClientRect();
      tip.style.left = (e.clientX - rect.left + 12) + 'px';
      tip.style.top = (e.clientY - rect.top + 12) + 'px';
      tip.style.display = 'block';
    });
    canvas.addEventListener('click', function (e) {
      selected = pick(e);
      updateInfo();
      drawTimeline();
    });

    // Screen position (CSS pixels in the canvas) of a marker of markerSets[0] at the
    // current frame, or null when it is not drawn.
    view.markerScreen = function (label) {
      if (!markerSets.length) return null;
      const m = markerSets[0];
      const j = typeof label === 'number' ? label : m.labels.indexOf(label);
      const f = Math.min(view.frame, m.frames - 1);
      if (j < 0 || !m.visible[f * m.count + j]) return null;
      const p = new THREE.Vector3().fromArray(m.shown, 3 * (f * m.count + j)).project(camera);
      return { x: (p.x + 1) / 2 * canvas.clientWidth, y: (1 - p.y) / 2 * canvas.clientHeight,
               state: meta.state_names[m.states[f * m.count + j]] };
    };

    // ---- characters, then the first frame ----------------------------------------
    const loader = new THREE.GLTFLoader();
    view.timings.data_ms = performance.now() - t0;
    const loads = meta.characters.map(function (c) {
      const bytes = blobBytes(c.glb);
      return loader.parseAsync(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength), '')
        .then(function (gltf) {
          const clips = gltf.animations;
          if (!clips.length) throw new Error(c.name + ': the character has no animation');
          let clip = clips[0];  // The clip retarget/pipeline/convert added (io/gltf_writer.h).
          if (c.animation) {
            clip = clips.find(function (k) { return k.name === c.animation; });
            if (!clip) throw new Error(c.name + ': no animation named "' + c.animation + '"');
          }
          const root = gltf.scene;
          const mixer = new THREE.AnimationMixer(root);
          mixer.clipAction(clip).play();
          scene.add(root);
          root.traverse(function (o) {
            if (!o.isMesh) return;
            o.frustumCulled = false;
            if (software && o.material && o.material.isMeshStandardMaterial) {
              const m = o.material;
              o.material = new THREE.MeshLambertMaterial({ color: m.color, map: m.map, transparent: m.transparent,
                                                           opacity: m.opacity, side: m.side, alphaTest: m.alphaTest,
                                                           vertexColors: m.vertexColors });
            }
          });
          const skins = [];
          if (software) {
            const skinned = [];
            root.traverse(function (o) { if (o.isSkinnedMesh) skinned.push(o); });
            skinned.forEach(function (o) { skins.push(makeCpuSkin(o)); });
          }
          characters.push({ name: c.name, root: root, mixer: mixer, clip: clip, skins: skins });
        });
    });

    // Skinning and lighting on the CPU, for software renderers. SwiftShader runs three.js'
    // skinning shader (four bone matrices fetched from a texture per vertex) several times
    // slower than this loop, which writes a plain mesh's positions each frame:
    //   x = bindMatrix^-1 * sum_k w_k * B_k * bindMatrix * x0,  B_k = bone_k.matrixWorld * boneInverse_k
    // (three.js' own formula), the plain mesh carrying matrixWorld * bindMatrix^-1; and
    // per-pixel lighting was 40 % of the time it took to draw Xbot, so the loop also
    // lights each vertex as MeshLambertMaterial lights a pixel (linear colour, the page's
    // hemisphere and sun, n the skinned normal):
    //   c = (mix(ground, sky, 0.5 n.up + 0.5) + max(0, n.sun) * sun) / pi,
    // the vertex colours of a MeshBasicMaterial that multiplies them by the material's
    // colour and map (Gouraud shading: on a 28k-vertex character it looks the same).
    const lightColors = (function () {
      const sky = hemisphere.color.clone().multiplyScalar(hemisphere.intensity / Math.PI);
      const ground = hemisphere.groundColor.clone().multiplyScalar(hemisphere.intensity / Math.PI);
      const direct = sun.color.clone().multiplyScalar(sun.intensity / Math.PI);
      return { sky: sky, ground: ground, sun: direct, sunDirection: sun.position.clone().normalize() };
    })();
    function basicMaterial(m) {
      if (Array.isArray(m)) return m.map(basicMaterial);
      return new THREE.MeshBasicMaterial({ color: m.color, map: m.map || null, vertexColors: true,
                                           transparent: m.transparent, opacity: m.opacity, side: m.side,
                                           alphaTest: m.alphaTest || 0 });
    }
    function makeCpuSkin(skinned) {
      const g = skinned.geometry, position = g.attributes.position, normal = g.attributes.normal;
      const vertexColor = g.attributes.color;  // COLOR_0: multiplies the light.
      const skinIndex = g.attributes.skinIndex, skinWeight = g.attributes.skinWeight;
      const n = position.count, bind = skinned.bindMatrix.elements;
      const rest = new Float32Array(3 * n), restNormal = new Float32Array(3 * n);
      const index = new Uint16Array(4 * n), weight = new Float32Array(4 * n);
      for (let i = 0; i < n; ++i) {
        const x = position.getX(i), y = position.getY(i), z = position.getZ(i);
        rest[3 * i] = bind[0] * x + bind[4] * y + bind[8] * z + bind[12];
        rest[3 * i + 1] = bind[1] * x + bind[5] * y + bind[9] * z + bind[13];
        rest[3 * i + 2] = bind[2] * x + bind[6] * y + bind[10] * z + bind[14];
        if (normal) {
          const a = normal.getX(i), b = normal.getY(i), c = normal.getZ(i);
          restNormal[3 * i] = bind[0] * a + bind[4] * b + bind[8] * c;
          restNormal[3 * i + 1] = bind[1] * a + bind[5] * b + bind[9] * c;
          restNormal[3 * i + 2] = bind[2] * a + bind[6] * b + bind[10] * c;
        }
        index[4 * i] = skinIndex.getX(i); index[4 * i + 1] = skinIndex.getY(i);
        index[4 * i + 2] = skinIndex.getZ(i); index[4 * i + 3] = skinIndex.getW(i);
        weight[4 * i] = skinWeight.getX(i); weight[4 * i + 1] = skinWeight.getY(i);
        weight[4 * i + 2] = skinWeight.getZ(i); weight[4 * i + 3] = skinWeight.getW(i);
      }
      let restColor = null;
      if (normal && vertexColor) {
        restColor = new Float32Array(3 * n);
        for (let i = 0; i < n; ++i) {
          restColor[3 * i] = vertexColor.getX(i);
          restColor[3 * i + 1] = vertexColor.getY(i);
          restColor[3 * i + 2] = vertexColor.getZ(i);
        }
      }
      const geometry = new THREE.BufferGeometry();
      if (g.index) geometry.setIndex(g.index);
      for (const name in g.attributes) {
        if (!/^(position|normal|color|skinIndex|skinWeight)$/.test(name)) geometry.setAttribute(name, g.attributes[name]);
      }
      const outPosition = new THREE.BufferAttribute(new Float32Array(3 * n), 3).setUsage(THREE.DynamicDrawUsage);
      const outColor = new THREE.BufferAttribute(new Float32Array(3 * n), 3).setUsage(THREE.DynamicDrawUsage);
      geometry.setAttribute('position', outPosition);
      // Without normals (rare) the mesh keeps its (Lambert) material, lit by three.js.
      if (normal) geometry.setAttribute('color', outColor);
      else if (vertexColor) geometry.setAttribute('color', vertexColor);
      g.groups.forEach(function (group) { geometry.addGroup(group.start, group.count, group.materialIndex); });
      const mesh = new THREE.Mesh(geometry, normal ? basicMaterial(skinned.material) : skinned.material);
      const materials = [].concat(mesh.material);
      // (Opaque materials only: through a transparent or cut-out surface its back shows.)
      const opaque = materials.every(function (m) { return !m.transparent && m.opacity === 1 && !(m.alphaTest > 0); });
      if (normal && opaque && materials.some(function (m) { return m.side === THREE.DoubleSide; }) &&
          closedOutward(rest, g.index, n)) {
        materials.forEach(function (m) { m.side = THREE.FrontSide; });
      }
      mesh.matrixAutoUpdate = false;
      mesh.frustumCulled = false;
      skinned.visible = false;
      scene.add(mesh);
      return { skinned: skinned, mesh: mesh, rest: rest, restNormal: normal ? restNormal : null, restColor: restColor,
               index: index, weight: weight, position: outPosition, color: outColor, count: n };
    }
    // True if the triangles (index, or consecutive vertices) make closed surfaces facing
    // outwards: with vertices welded by position, every edge a->b of a triangle is an
    // edge b->a of another, and the signed volume is positive. Such a mesh, if opaque,
    // shows no back face, so drawing it single-sided gives the same picture for half the
    // triangles rasterized (exporters mark meshes double-sided by default: Blender does,
    // Xbot is).
    function closedOutward(xyz, index, n) {
      const corners = index ? index.count : n, triangles = Math.floor(corners / 3);
      if (triangles === 0) return false;
      // Weld: open addressing on the coordinates' bits.
      const bits = new Uint32Array(xyz.buffer, xyz.byteOffset, 3 * n);
      const size = 1 << Math.ceil(Math.log2(2 * n + 2));
      const table = new Int32Array(size).fill(-1), weld = new Int32Array(n);
      for (let i = 0; i < n; ++i) {
        const x = bits[3 * i], y = bits[3 * i + 1], z = bits[3 * i + 2];
        let h = (Math.imul(x ^ Math.imul(y, 0x9e3779b1) ^ Math.imul(z, 0x85ebca77), 0xc2b2ae3d) >>> 7) & (size - 1);
        for (;;) {
          const j = table[h];
          if (j < 0) { table[h] = i; weld[i] = i; break; }
          if (bits[3 * j] === x && bits[3 * j + 1] === y && bits[3 * j + 2] === z) { weld[i] = j; break; }
          h = (h + 1) & (size - 1);
        }
      }
      // Edges: per undirected edge {lo, hi}, +1 for each lo->hi and -1 for each hi->lo;
      // closed and consistently wound iff every sum is 0.
      const slots = 1 << Math.ceil(Math.log2(4 * triangles + 4));
      const low = new Int32Array(slots).fill(-1), high = new Int32Array(slots), sum = new Int32Array(slots);
      function edge(a, b) {
        if (a === b) return;
        const lo = a < b ? a : b, hi = a < b ? b : a;
        let h = (Math.imul(lo ^ Math.imul(hi, 0x9e3779b1), 0x85ebca77) >>> 9) & (slots - 1);
        while (low[h] >= 0 && (low[h] !== lo || high[h] !== hi)) h = (h + 1) & (slots - 1);
        low[h] = lo;
        high[h] = hi;
        sum[h] += a < b ? 1 : -1;
      }
      let volume = 0;
      for (let t = 0; t < triangles; ++t) {
        const i0 = index ? index.getX(3 * t) : 3 * t, i1 = index ? index.getX(3 * t + 1) : 3 * t + 1;
        const i2 = index ? index.getX(3 * t + 2) : 3 * t + 2;
        const a = weld[i0], b = weld[i1], c = weld[i2];
        edge(a, b);
        edge(b, c);
        edge(c, a);
        const ax = xyz[3 * i0], ay = xyz[3 * i0 + 1], az = xyz[3 * i0 + 2];
        const bx = xyz[3 * i1], by = xyz[3 * i1 + 1], bz = xyz[3 * i1 + 2];
        const cx = xyz[3 * i2], cy = xyz[3 * i2 + 1], cz = xyz[3 * i2 + 2];
        volume += ax * (by * cz - bz * cy) + ay * (bz * cx - bx * cz) + az * (bx * cy - by * cx);
      }
      for (let k = 0; k < slots; ++k) if (sum[k] !== 0) return false;
      return volume > 0;
    }
    function cpuSkin(s) {
      s.skinned.skeleton.update();
      s.mesh.matrix.multiplyMatrices(s.skinned.matrixWorld, s.skinned.bindMatrixInverse);
      s.mesh.matrixWorldNeedsUpdate = true;
      // The lights' directions in the mesh's space: R^T v, R = the matrix's rotation (times
      // a uniform scale, normalized away).
      const e = s.mesh.matrix.elements, L = lightColors, d = L.sunDirection;
      let ux = e[1], uy = e[5], uz = e[9];
      let sx = e[0] * d.x + e[1] * d.y + e[2] * d.z, sy = e[4] * d.x + e[5] * d.y + e[6] * d.z;
      let sz = e[8] * d.x + e[9] * d.y + e[10] * d.z;
      const ul = 1 / (Math.hypot(ux, uy, uz) || 1), sl = 1 / (Math.hypot(sx, sy, sz) || 1);
      ux *= ul; uy *= ul; uz *= ul; sx *= sl; sy *= sl; sz *= sl;
      const gr = L.ground.r, gg = L.ground.g, gb = L.ground.b;
      const kr = L.sky.r - gr, kg = L.sky.g - gg, kb = L.sky.b - gb;
      const dr = L.sun.r, dg = L.sun.g, db = L.sun.b;
      const B = s.skinned.skeleton.boneMatrices, rest = s.rest, restNormal = s.restNormal, restColor = s.restColor;
      const index = s.index, weight = s.weight, out = s.position.array, color = s.color.array;
      for (let i = 0; i < s.count; ++i) {
        let m0 = 0, m1 = 0, m2 = 0, m3 = 0, m4 = 0, m5 = 0, m6 = 0, m7 = 0, m8 = 0, m9 = 0, m10 = 0, m11 = 0;
        for (let k = 4 * i; k < 4 * i + 4; ++k) {
          const w = weight[k];
          if (w === 0) continue;
          const b = 16 * index[k];
          m0 += w * B[b]; m1 += w * B[b + 1]; m2 += w * B[b + 2];
          m3 += w * B[b + 4]; m4 += w * B[b + 5]; m5 += w * B[b + 6];
          m6 += w * B[b + 8]; m7 += w * B[b + 9]; m8 += w * B[b + 10];
          m9 += w * B[b + 12]; m10 += w * B[b + 13]; m11 += w * B[b + 14];
        }
        const x = rest[3 * i], y = rest[3 * i + 1], z = rest[3 * i + 2];
        out[3 * i] = m0 * x + m3 * y + m6 * z + m9;
        out[3 * i + 1] = m1 * x + m4 * y + m7 * z + m10;
        out[3 * i + 2] = m2 * x + m5 * y + m8 * z + m11;
        if (restNormal) {
          const a = restNormal[3 * i], b = restNormal[3 * i + 1], c = restNormal[3 * i + 2];
          const nx = m0 * a + m3 * b + m6 * c, ny = m1 * a + m4 * b + m7 * c, nz = m2 * a + m5 * b + m8 * c;
          const inverse = 1 / (Math.sqrt(nx * nx + ny * ny + nz * nz) || 1);
          const w = 0.5 * (nx * ux + ny * uy + nz * uz) * inverse + 0.5;
          const lit = Math.max(0, (nx * sx + ny * sy + nz * sz) * inverse);
          let r = gr + kr * w + dr * lit, g = gg + kg * w + dg * lit, b2 = gb + kb * w + db * lit;
          if (restColor) { r *= restColor[3 * i]; g *= restColor[3 * i + 1]; b2 *= restColor[3 * i + 2]; }
          color[3 * i] = r; color[3 * i + 1] = g; color[3 * i + 2] = b2;
        }
      }
      s.position.needsUpdate = true;
      if (restNormal) s.color.needsUpdate = true;
    }

    // A character's box from its bones' world positions (skinning every vertex on the CPU
    // to get the exact box costs seconds for a 28k-vertex mesh in a software renderer),
    // padded for the flesh around them.
    function characterBox(root) {
      root.updateMatrixWorld(true);
      const b = new THREE.Box3(), p = new THREE.Vector3();
      root.traverse(function (o) { if (o.isBone) b.expandByPoint(o.getWorldPosition(p)); });
      if (b.isEmpty()) return new THREE.Box3().setFromObject(root);
      const pad = 0.1 * Math.max(0.2, b.max.y - b.min.y);
      b.min.x -= pad; b.min.z -= pad; b.max.x += pad; b.max.z += pad;
      b.max.y += pad;  // The head above its bone.
      b.min.y -= 0.2 * pad;  // Soles just below the toe bones.
      return b;
    }

    Promise.all(loads).then(function () {
      view.timings.characters_ms = performance.now() - t0;
      // Frames: the longest of the data and of the characters' clips.
      let frames = meta.frames;
      characters.forEach(function (c) { frames = Math.max(frames, Math.round(c.clip.duration * fps) + 1); });
      view.frames = Math.max(1, frames);
      slider.max = String(view.frames - 1);
      // Characters stand beside the source, to its +x, each at its frame-0 root.
      const source = first.isEmpty() ? new THREE.Box3(new THREE.Vector3(-0.5, 0, 0), new THREE.Vector3(0.5, 1.8, 0)) : first;
      let x = source.max.x + 0.4;
      const content = box.clone();
      characters.forEach(function (c) {
        c.mixer.setTime(0);
        c.root.updateMatrixWorld(true);
        const own = characterBox(c.root);
        if (own.isEmpty()) own.set(new THREE.Vector3(-0.4, 0, -0.2), new THREE.Vector3(0.4, 1.8, 0.2));
        const center = own.getCenter(new THREE.Vector3());
        const width = own.max.x - own.min.x;
        c.root.position.x += x + 0.5 * width - center.x;
        c.root.position.z += 0.5 * (source.min.z + source.max.z) - center.z;
        c.root.position.y += (box.isEmpty() ? 0 : floorY) - own.min.y;
        x += width + 0.4;
        // Where it stands at the start, the middle and the end of its clip.
        [0, 0.5, 1].forEach(function (u) {
          c.mixer.setTime(u * c.clip.duration * (1 - 1e-7));
          c.root.updateMatrixWorld(true);
          content.union(characterBox(c.root));
        });
      });
      if (content.isEmpty()) content.set(new THREE.Vector3(-1, 0, -1), new THREE.Vector3(1, 1.8, 1));

      // Ground grid: 1 m cells (10 cm for small scenes) under everything, at the lowest point.
      const size = content.getSize(new THREE.Vector3());
      const span = Math.max(size.x, size.z) + 2;
      const cell = span > 4 ? 1 : 0.1;
      const cells = Math.min(400, Math.ceil(span / cell / 2) * 2);
      const grid = new THREE.GridHelper(cells * cell, cells, 0x56606e, 0x363d47);
      const center = content.getCenter(new THREE.Vector3());
      grid.position.set(Math.round(center.x / cell) * cell, content.min.y, Math.round(center.z / cell) * cell);
      scene.add(grid);
      const axes = new THREE.AxesHelper(Math.max(0.2, 0.1 * extent));
      axes.position.set(0, content.min.y + 0.001, 0);
      scene.add(axes);
      meta.notes.push('grid: ' + (cell === 1 ? '1 m' : '10 cm') + ' cells; axes x red, y (up) green, z blue');
      legend();
      resize();
      // The camera frames the first frame (source and characters, at least 2.4 m wide) and
      // follows the take from there; the grid covers the whole take.
      const start = first.isEmpty() ? content.clone() : first.clone();
      characters.forEach(function (c) {
        c.mixer.setTime(0);
        start.union(characterBox(c.root));
      });
      const middle = start.getCenter(new THREE.Vector3());
      start.expandByPoint(middle.clone().add(new THREE.Vector3(1.2, 0, 0)));
      start.expandByPoint(middle.clone().add(new THREE.Vector3(-1.2, 0, 0)));
      frameCamera(start);
      followed = takeCentre(0);
      view.timings.layout_ms = performance.now() - t0;
      setFrame(0);
      view.timings.first_frame_ms = performance.now() - t0;
      view.ready = true;
    }).catch(fail);
    window.addEventListener('resize', function () { resize(); render(); });
  }
})();
