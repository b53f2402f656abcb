// triad's replay page: places the bodies from the recorded poses of the payload (no dynamics
// here), draws them with three.js, and offers playback, orbit/pan/zoom, frames, sites, a trace
// and a signal panel synced to the time cursor; with contact, the ground, the collision shapes
// and the contact forces as arrows. The payload's layout is src/viewer/payload.rs.
// For tests and scripts, `window.triad` exposes the time, a projection of world points to page
// pixels, the arrows, and switches; the URL hash sets the start
// (#t=1.5&play=0&ui=0&signals=0&trace=site:S&frames=1&sites=1&ground=0&collision=1&forces=1&fscale=20).
(function () {
  'use strict';

  const T = window.THREE;
  const data = JSON.parse(document.getElementById('triad-data').textContent);
  const hash = new URLSearchParams(window.location.hash.slice(1));

  function fail(text) {
    const m = document.getElementById('message');
    m.textContent = text;
    m.hidden = false;
    window.triad = { ready: false, error: text };
  }
  if (data.format !== 1) {
    fail('This page was made by another version of triad (payload format ' + data.format + ').');
    return;
  }

  // ---- payload decoding (little-endian arrays in base64)
  function bytes(b64) {
    const s = atob(b64);
    const u = new Uint8Array(s.length);
    for (let i = 0; i < s.length; i++) u[i] = s.charCodeAt(i);
    return u.buffer;
  }
  const f64 = (b) => new Float64Array(bytes(b));
  const f32 = (b) => new Float32Array(bytes(b));

  const times = f64(data.time);
  const n = times.length;
  const t0 = times[0];
  const t1 = times[n - 1];
  const L = data.length;
  const bodies = data.bodies.map((b) => ({ name: b.name, r: f64(b.r), q: f32(b.q), shapes: b.shapes }));

  // ---- renderer, scene, camera, lights
  const view = document.getElementById('view');
  let renderer;
  try {
    renderer = new T.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  } catch (e) {
    fail('WebGL is not available in this browser: ' + e.message);
    return;
  }
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setSize(window.innerWidth, window.innerHeight);
  view.appendChild(renderer.domElement);
  const scene = new T.Scene();
  scene.background = new T.Color(0xeef1f5);
  const camera = new T.PerspectiveCamera(40, window.innerWidth / window.innerHeight, L / 1000, L * 1000);
  // up: the ground's normal (against gravity) with a ground, else z; (side1, side2, up) is the
  // frame the home view is set in (x, y, z for a ground normal to z)
  const upAxis = data.ground ? new T.Vector3().fromArray(data.ground.normal).normalize() : new T.Vector3(0, 0, 1);
  const side1 = Math.abs(upAxis.x) < 0.9 ? new T.Vector3(1, 0, 0) : new T.Vector3(0, 1, 0);
  side1.addScaledVector(upAxis, -side1.dot(upAxis)).normalize();
  const side2 = new T.Vector3().crossVectors(upAxis, side1);
  camera.up.copy(upAxis);
  scene.add(camera);
  scene.add(new T.HemisphereLight(0xffffff, 0x9098a4, 1.6));
  const key = new T.DirectionalLight(0xffffff, 1.8);
  key.position.set(0.5, 0.3, 1.0); // relative to the camera: light comes from over its shoulder
  camera.add(key);
  camera.add(key.target);
  key.target.position.set(0, 0, -1);

  // ---- shapes
  const PALETTE = [0x4e79a7, 0xf28e2b, 0x59a14f, 0xe15759, 0x76b7b2, 0xedc948, 0xb07aa1, 0xff9da7, 0x9c755f, 0xbab0ac];
  function material(rgba, fallback, flat, faceted) {
    const c = rgba ? new T.Color(rgba[0], rgba[1], rgba[2]) : new T.Color(fallback);
    const a = rgba && rgba.length > 3 ? rgba[3] : 1;
    const m = new T.MeshStandardMaterial({
      color: c, roughness: 0.55, metalness: 0.05, flatShading: !!(flat || faceted),
      transparent: a < 1, opacity: a,
    });
    if (flat) m.side = T.DoubleSide; // (meshes of unknown winding)
    return m;
  }
  // collision shapes on demand: see-through wireframes over everything
  const WIRE = new T.MeshBasicMaterial({ color: 0x0b6e4f, wireframe: true, transparent: true, opacity: 0.6, depthTest: false });
  const meshGeometries = data.meshes.map((parts) => parts.map((p) => {
    const q = new Uint16Array(bytes(p.positions));
    const pos = new Float32Array(q.length);
    for (let i = 0; i < q.length; i++) {
      const k = i % 3;
      pos[i] = p.min[k] + (q[i] / 65535) * (p.max[k] - p.min[k]);
    }
    const g = new T.BufferGeometry();
    g.setAttribute('position', new T.BufferAttribute(pos, 3));
    g.setIndex(new T.BufferAttribute(p.wide ? new Uint32Array(bytes(p.indices)) : new Uint16Array(bytes(p.indices)), 1));
    g.computeVertexNormals();
    return { geometry: g, rgba: p.rgba };
  }));
  // a shape in its body's frame; `wire`: as a collision shape's wireframe; faceted shapes (a
  // collision shape standing in for a body's look) are coarse and flat so that spin shows
  function shapeObject(s, colour, wire) {
    const o = new T.Group();
    o.position.set(s.xyz[0], s.xyz[1], s.xyz[2]);
    o.quaternion.set(s.q[0], s.q[1], s.q[2], s.q[3]);
    const shade = s.default && s.kind !== 'box' ? new T.Color(colour).multiplyScalar(0.72).getHex() : colour;
    const coarse = wire || s.faceted;
    let g = null;
    if (s.kind === 'box') g = new T.BoxGeometry(s.size[0], s.size[1], s.size[2]);
    else if (s.kind === 'sphere') g = coarse ? new T.SphereGeometry(s.size[0], 16, 10) : new T.SphereGeometry(s.size[0], 32, 16);
    else if (s.kind === 'cylinder') g = new T.CylinderGeometry(s.size[0], s.size[0], s.size[1], coarse ? 16 : 40).rotateX(Math.PI / 2);
    else if (s.kind === 'capsule') g = new T.CapsuleGeometry(s.size[0], s.size[1], coarse ? 4 : 8, coarse ? 12 : 20).rotateX(Math.PI / 2);
    if (g && wire) {
      const m = new T.Mesh(g, WIRE);
      m.renderOrder = 2;
      o.add(m);
    } else if (g) {
      o.add(new T.Mesh(g, material(s.rgba, shade, false, s.faceted)));
    } else if (s.kind === 'mesh') {
      for (const part of meshGeometries[s.mesh]) {
        const m = new T.Mesh(part.geometry, material(part.rgba || s.rgba, colour, true));
        m.scale.set(s.size[0], s.size[1], s.size[2]);
        o.add(m);
      }
    }
    return o;
  }

  const robot = new T.Group(); // everything the recording moves or the model fixes
  scene.add(robot);
  for (const s of data.world) robot.add(shapeObject(s, 0x8c96a3));
  const frameSize = 0.12 * L;
  bodies.forEach((b, i) => {
    b.group = new T.Group();
    b.group.name = b.name;
    const colour = PALETTE[i % PALETTE.length];
    for (const s of b.shapes) b.group.add(shapeObject(s, colour));
    b.axes = new T.AxesHelper(frameSize);
    b.axes.visible = false;
    b.axes.renderOrder = 1;
    b.group.add(b.axes);
    robot.add(b.group);
  });
  const contacts = (data.contacts || []).map((c) => {
    const wire = shapeObject(c.shape, 0, true);
    wire.visible = false;
    bodies[c.body].group.add(wire);
    return {
      name: c.name, body: bodies[c.body], shape: c.shape, wire,
      local: new T.Vector3(c.shape.xyz[0], c.shape.xyz[1], c.shape.xyz[2]),
      rot: new T.Quaternion(c.shape.q[0], c.shape.q[1], c.shape.q[2], c.shape.q[3]),
      f: c.f ? f32(c.f) : null,
    };
  });
  const siteMarks = data.sites.map((s) => {
    const g = new T.Group();
    g.position.set(s.xyz[0], s.xyz[1], s.xyz[2]);
    g.quaternion.set(s.q[0], s.q[1], s.q[2], s.q[3]);
    g.add(new T.Mesh(new T.SphereGeometry(0.012 * L, 16, 8), new T.MeshBasicMaterial({ color: 0x222222 })));
    g.add(new T.AxesHelper(0.6 * frameSize));
    g.visible = false;
    bodies[s.body].group.add(g);
    return g;
  });

  // ---- poses at a time: linear in position, spherical in orientation between frames
  const qa = new T.Quaternion();
  const qb = new T.Quaternion();
  function frameAt(t) {
    let lo = 0;
    let hi = n - 1;
    if (t <= times[0]) return [0, 0];
    if (t >= times[hi]) return [hi, 0];
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (times[mid] <= t) lo = mid; else hi = mid;
    }
    const span = times[lo + 1] - times[lo];
    return [lo, span > 0 ? (t - times[lo]) / span : 0];
  }
  function place(t) {
    const [k, a] = frameAt(t);
    const k2 = Math.min(k + 1, n - 1);
    for (const b of bodies) {
      const r = b.r;
      const q = b.q;
      b.group.position.set(
        r[3 * k] + a * (r[3 * k2] - r[3 * k]),
        r[3 * k + 1] + a * (r[3 * k2 + 1] - r[3 * k + 1]),
        r[3 * k + 2] + a * (r[3 * k2 + 2] - r[3 * k + 2]));
      qa.set(q[4 * k], q[4 * k + 1], q[4 * k + 2], q[4 * k + 3]);
      qb.set(q[4 * k2], q[4 * k2 + 1], q[4 * k2 + 2], q[4 * k2 + 3]);
      b.group.quaternion.slerpQuaternions(qa, qb, a).normalize();
    }
    return k;
  }

  // ---- where things go over the run: camera, grid
  const box = new T.Box3();
  const samples = Math.min(n, 40);
  for (let i = 0; i < samples; i++) {
    place(times[Math.round((i * (n - 1)) / Math.max(samples - 1, 1))]);
    robot.updateMatrixWorld(true);
    box.expandByObject(robot);
  }
  if (box.isEmpty()) box.set(new T.Vector3(-L / 2, -L / 2, -L / 2), new T.Vector3(L / 2, L / 2, L / 2));
  // with a ground not far off, the view takes in the ground under the model (a dropped body)
  const groundNormal = data.ground ? upAxis : null;
  if (groundNormal) {
    const corners = [];
    for (let i = 0; i < 8; i++) {
      corners.push(new T.Vector3(i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y, i & 4 ? box.max.z : box.min.z));
    }
    const above = corners.map((p) => p.dot(groundNormal) - data.ground.height);
    if (Math.min(...above.map(Math.abs)) <= 10 * L) {
      corners.forEach((p, i) => box.expandByPoint(p.addScaledVector(groundNormal, -above[i])));
    }
  }
  const centre = box.getCenter(new T.Vector3());
  const radius = Math.max(box.getSize(new T.Vector3()).length() / 2, 0.05 * L);
  function niceStep(x) {
    const e = Math.pow(10, Math.floor(Math.log10(x)));
    const m = x / e;
    return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * e;
  }
  const cell = niceStep(radius / 4);
  const floorZ = box.min.z >= -0.1 * L ? 0 : box.min.z;
  // the spec's [ground] replaces the helper grid
  const grid = data.ground ? null : new T.GridHelper(cell * 24, 24, 0x9aa4b0, 0xc9d0d8);
  if (grid) {
    grid.rotation.x = Math.PI / 2;
    grid.position.set(Math.round(centre.x / cell) * cell, Math.round(centre.y / cell) * cell, floorZ);
    scene.add(grid);
  }

  // ---- the ground: the plane n.x = h of the spec's [ground], a checker fixed in the world (so
  // that sliding shows) of the helper grid's cells, covering the motion seen along n and a margin
  let ground = null;
  if (data.ground) {
    const nrm = groundNormal;
    const h = data.ground.height;
    const e1 = side1;
    const e2 = side2;
    let u0 = Infinity;
    let u1 = -Infinity;
    let v0 = Infinity;
    let v1 = -Infinity;
    const p = new T.Vector3();
    for (let i = 0; i < 8; i++) {
      p.set(i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y, i & 4 ? box.max.z : box.min.z);
      u0 = Math.min(u0, p.dot(e1)); u1 = Math.max(u1, p.dot(e1));
      v0 = Math.min(v0, p.dot(e2)); v1 = Math.max(v1, p.dot(e2));
    }
    const half = Math.max(u1 - u0, v1 - v0) / 2 + Math.max(radius, 4 * cell);
    let size = cell;
    while (half / size > 60) size *= 2; // at most 120 x 120 cells
    const cells = Math.max(Math.ceil(half / size), 12);
    const uc = Math.round((u0 + u1) / 2 / size);
    const vc = Math.round((v0 + v1) / 2 / size);
    const side = 2 * cells;
    const pos = new Float32Array(side * side * 12);
    const col = new Float32Array(side * side * 12);
    const index = new Uint32Array(side * side * 6);
    const light = new T.Color(0xd6dce3);
    const dark = new T.Color(0xbcc4ce);
    const at = (u, v, out) => out.copy(nrm).multiplyScalar(h).addScaledVector(e1, u * size).addScaledVector(e2, v * size);
    let c = 0;
    for (let i = 0; i < side; i++) {
      for (let j = 0; j < side; j++) {
        const iu = uc - cells + i;
        const iv = vc - cells + j;
        const tone = (iu + iv) & 1 ? dark : light;
        const corners = [[iu, iv], [iu + 1, iv], [iu + 1, iv + 1], [iu, iv + 1]];
        corners.forEach(([a, b], k) => {
          at(a, b, p).toArray(pos, 12 * c + 3 * k);
          tone.toArray(col, 12 * c + 3 * k);
        });
        index.set([4 * c, 4 * c + 1, 4 * c + 2, 4 * c, 4 * c + 2, 4 * c + 3], 6 * c);
        c += 1;
      }
    }
    const g = new T.BufferGeometry();
    g.setAttribute('position', new T.BufferAttribute(pos, 3));
    g.setAttribute('color', new T.BufferAttribute(col, 3));
    g.setIndex(new T.BufferAttribute(index, 1));
    const mesh = new T.Mesh(g, new T.MeshBasicMaterial({
      vertexColors: true, side: T.DoubleSide, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
    }));
    mesh.name = 'ground';
    scene.add(mesh);
    const corner = (a, b) => at(a, b, new T.Vector3()).toArray();
    ground = {
      mesh, normal: nrm, height: h,
      info: {
        normal: nrm.toArray(), height: h, cell: size,
        corners: [corner(uc - cells, vc - cells), corner(uc + cells, vc - cells), corner(uc + cells, vc + cells), corner(uc - cells, vc + cells)],
      },
    };
  }

  const worldAxes = new T.AxesHelper(0.25 * L);
  scene.add(worldAxes);

  const controls = new T.OrbitControls(camera, renderer.domElement);
  function home() {
    const dir = new T.Vector3().addScaledVector(side1, 0.55).addScaledVector(side2, -1.0).addScaledVector(upAxis, 0.42).normalize();
    const fov = (camera.fov * Math.PI) / 180;
    const aspect = Math.min(camera.aspect, 1);
    const dist = (radius / Math.sin(fov / 2)) * 1.2 / Math.max(aspect, 0.5);
    camera.position.copy(centre).addScaledVector(dir, dist);
    controls.target.copy(centre);
    camera.near = dist / 1000;
    camera.far = dist * 100;
    camera.updateProjectionMatrix();
    controls.update();
  }
  home();

  // ---- trace of a body origin or a site
  const traceSelect = document.getElementById('opt-trace');
  const traceChoices = [];
  bodies.forEach((b, i) => traceChoices.push({ id: 'body:' + b.name, label: 'origin of ' + b.name, body: i, local: null }));
  data.sites.forEach((s) => traceChoices.push({ id: 'site:' + s.name, label: 'site ' + s.name, body: s.body, local: new T.Vector3(s.xyz[0], s.xyz[1], s.xyz[2]) }));
  for (const c of traceChoices) {
    const o = document.createElement('option');
    o.value = c.id;
    o.textContent = c.label;
    traceSelect.appendChild(o);
  }
  let trace = null;
  function setTrace(id) {
    if (trace) {
      scene.remove(trace.group);
      trace = null;
    }
    const c = traceChoices.find((x) => x.id === id);
    traceSelect.value = c ? id : '';
    if (!c) return;
    const b = bodies[c.body];
    const pts = new Float32Array(3 * n);
    const p = new T.Vector3();
    const q = new T.Quaternion();
    for (let k = 0; k < n; k++) {
      p.set(0, 0, 0);
      if (c.local) {
        q.set(b.q[4 * k], b.q[4 * k + 1], b.q[4 * k + 2], b.q[4 * k + 3]);
        p.copy(c.local).applyQuaternion(q);
      }
      pts[3 * k] = p.x + b.r[3 * k];
      pts[3 * k + 1] = p.y + b.r[3 * k + 1];
      pts[3 * k + 2] = p.z + b.r[3 * k + 2];
    }
    const geometry = new T.BufferGeometry();
    geometry.setAttribute('position', new T.BufferAttribute(pts, 3));
    const done = new T.BufferGeometry();
    done.setAttribute('position', new T.BufferAttribute(pts, 3));
    const group = new T.Group();
    group.add(new T.Line(geometry, new T.LineBasicMaterial({ color: 0x7a2e8f, transparent: true, opacity: 0.3 })));
    const travelled = new T.Line(done, new T.LineBasicMaterial({ color: 0x7a2e8f }));
    group.add(travelled);
    scene.add(group);
    trace = { group, travelled };
  }
  traceSelect.addEventListener('change', () => setTrace(traceSelect.value));

  // ---- contact forces: an arrow per collision shape from its contact point along the force on
  // its body, |f| / scale long (cut, and darker, beyond 2 L); none where the force is zero (or
  // its arrow shorter than L / 1000). The contact point (src/viewer/contact.rs): in the ground,
  // the centre of pressure of the shape's ground points (as the mechanics places them), each
  // weighted by its depth (the law is linear); just clear of the ground, its lowest point; on
  // the ground in both cases. Farther from the ground (a force from another shape), the shape's
  // point farthest along -f.
  const withForces = contacts.filter((c) => c.f);
  let forceScale = data.forces && data.forces.scale > 0 ? data.forces.scale : 1;
  const CUT = 2 * L;
  const EDGE = 0.02; // ~1 degree: a face's centre blends into an edge's middle, then a corner
  const arrowPaint = new T.MeshBasicMaterial({ color: 0xe8590c, depthTest: false, transparent: true, opacity: 0.95 });
  const arrowCutPaint = new T.MeshBasicMaterial({ color: 0x8f1d0b, depthTest: false, transparent: true, opacity: 0.95 });
  const shaftGeometry = new T.CylinderGeometry(1, 1, 1, 12).translate(0, 0.5, 0);
  const headGeometry = new T.CylinderGeometry(0, 1, 1, 18).translate(0, 0.5, 0);
  const arrows = new T.Group();
  arrows.visible = false;
  scene.add(arrows);
  for (const c of withForces) {
    c.arrow = new T.Group();
    c.shaft = new T.Mesh(shaftGeometry, arrowPaint);
    c.head = new T.Mesh(headGeometry, arrowPaint);
    c.shaft.renderOrder = 3;
    c.head.renderOrder = 3;
    c.arrow.add(c.shaft, c.head);
    arrows.add(c.arrow);
    c.state = { visible: false, base: [0, 0, 0], tip: [0, 0, 0], force: [0, 0, 0], cut: false };
  }
  const clampEdge = (x) => Math.max(-1, Math.min(1, x / EDGE));
  // the points through which a shape touches the ground, in its frame, with their radii
  // (src/mechanics/model/contact.rs: a sphere's centre, a capsule's segment ends, a box's
  // corners, 12 points on each rim of a cylinder)
  function groundPoints(s) {
    const z = s.size;
    if (s.kind === 'sphere') return [[new T.Vector3(), z[0]]];
    if (s.kind === 'capsule') return [-0.5, 0.5].map((h) => [new T.Vector3(0, 0, h * z[1]), z[0]]);
    if (s.kind === 'box') {
      const out = [];
      for (let k = 0; k < 8; k++) out.push([new T.Vector3((k & 1 ? 0.5 : -0.5) * z[0], (k & 2 ? 0.5 : -0.5) * z[1], (k & 4 ? 0.5 : -0.5) * z[2]), 0]);
      return out;
    }
    if (s.kind === 'cylinder') {
      const out = [];
      for (let k = 0; k < 24; k++) {
        const a = (2 * Math.PI * (k % 12)) / 12;
        out.push([new T.Vector3(z[0] * Math.cos(a), z[0] * Math.sin(a), (k < 12 ? -0.5 : 0.5) * z[1]), 0]);
      }
      return out;
    }
    return [];
  }
  for (const c of withForces) c.points = groundPoints(c.shape);
  const pw = new T.Vector3();
  const pressure = new T.Vector3();
  // the point of shape s farthest along the unit direction d (both in the shape's frame)
  function support(s, d, out) {
    const z = s.size;
    if (s.kind === 'sphere') return out.copy(d).multiplyScalar(z[0]);
    if (s.kind === 'capsule') { out.copy(d).multiplyScalar(z[0]); out.z += (z[1] / 2) * clampEdge(d.z); return out; }
    if (s.kind === 'box') return out.set((z[0] / 2) * clampEdge(d.x), (z[1] / 2) * clampEdge(d.y), (z[2] / 2) * clampEdge(d.z));
    if (s.kind === 'cylinder') {
      const w = z[0] / Math.max(Math.hypot(d.x, d.y), EDGE);
      return out.set(d.x * w, d.y * w, (z[1] / 2) * clampEdge(d.z));
    }
    return out.set(0, 0, 0);
  }
  const Y = new T.Vector3(0, 1, 0);
  const fv = new T.Vector3();
  const dir = new T.Vector3();
  const centreW = new T.Vector3();
  const qW = new T.Quaternion();
  const qInv = new T.Quaternion();
  const dl = new T.Vector3();
  const base = new T.Vector3();
  function placeArrows(t) {
    if (!withForces.length) return;
    const [k, a] = frameAt(t);
    const k2 = Math.min(k + 1, n - 1);
    for (const c of withForces) {
      const f = c.f;
      fv.set(
        f[3 * k] + a * (f[3 * k2] - f[3 * k]),
        f[3 * k + 1] + a * (f[3 * k2 + 1] - f[3 * k + 1]),
        f[3 * k + 2] + a * (f[3 * k2 + 2] - f[3 * k + 2]));
      const size = fv.length();
      const st = c.state;
      st.force = fv.toArray();
      // (a force too small to draw, e.g. a zero one met by interpolation, is none)
      st.visible = size / forceScale > 1e-3 * L && Number.isFinite(size);
      c.arrow.visible = st.visible;
      if (!st.visible) continue;
      // the shape's pose from its body's (placed for this time)
      qW.copy(c.body.group.quaternion).multiply(c.rot);
      centreW.copy(c.local).applyQuaternion(c.body.group.quaternion).add(c.body.group.position);
      qInv.copy(qW).invert();
      let onGround = false;
      if (ground) {
        let weight = 0;
        pressure.set(0, 0, 0);
        for (const [p, radius] of c.points) {
          pw.copy(p).applyQuaternion(qW).add(centreW).addScaledVector(ground.normal, -radius);
          const depth = ground.height - pw.dot(ground.normal);
          if (depth > 0) {
            pressure.addScaledVector(pw, depth);
            weight += depth;
          }
        }
        if (weight > 0) {
          base.copy(pressure).divideScalar(weight);
        } else {
          dl.copy(ground.normal).negate().applyQuaternion(qInv);
          support(c.shape, dl, base).applyQuaternion(qW).add(centreW);
        }
        const gap = base.dot(ground.normal) - ground.height;
        if (weight > 0 || gap <= 0.01 * L) {
          onGround = true;
          base.addScaledVector(ground.normal, -gap);
        }
      }
      if (!onGround) {
        dl.copy(fv).divideScalar(-size).applyQuaternion(qInv);
        support(c.shape, dl, base).applyQuaternion(qW).add(centreW);
      }
      let len = size / forceScale;
      st.cut = len > CUT;
      if (st.cut) len = CUT;
      dir.copy(fv).divideScalar(size);
      const rho = 0.006 * L;
      const headLen = Math.min(0.4 * len, 0.05 * L);
      const headR = Math.min(2.5 * rho, 0.6 * headLen + rho);
      c.arrow.position.copy(base);
      c.arrow.quaternion.setFromUnitVectors(Y, dir);
      c.shaft.scale.set(rho, Math.max(len - headLen, 1e-9), rho);
      c.head.position.set(0, len - headLen, 0);
      c.head.scale.set(headR, headLen, headR);
      c.shaft.material = c.head.material = st.cut ? arrowCutPaint : arrowPaint;
      st.base = base.toArray();
      st.tip = base.clone().addScaledVector(dir, len).toArray();
    }
  }

  // ---- signals panel
  const plot = document.getElementById('plot');
  const legend = document.getElementById('legend');
  const signalsPanel = document.getElementById('signals');
  const LINE = ['#4e79a7', '#f28e2b', '#59a14f', '#e15759', '#76b7b2', '#edc948', '#b07aa1', '#ff9da7', '#9c755f'];
  const signals = data.signals.map((s) => ({ name: s.name, unit: s.unit, kind: s.kind, scale: s.scale, v: f32(s.values) }));
  const coords = signals.filter((s) => s.kind === 'coordinate');
  const balance = signals.find((s) => s.kind === 'balance');
  function range(list) {
    let lo = Infinity;
    let hi = -Infinity;
    for (const s of list) for (const x of s.v) { if (x < lo) lo = x; if (x > hi) hi = x; }
    if (!(hi >= lo)) return [-1, 1];
    const pad = Math.max((hi - lo) * 0.08, 1e-6);
    return [lo - pad, hi + pad];
  }
  const coordRange = range(coords);
  let balanceRange = [-1, 1];
  let balanceMax = 0;
  if (balance) {
    for (const x of balance.v) balanceMax = Math.max(balanceMax, Math.abs(x));
    const least = Math.max(1e-6 * Math.max(balance.scale, 1), 1e-12);
    const h = Math.max(balanceMax * 1.15, least);
    balanceRange = [-h, h];
  }
  const short = (name) => name.replace(/^joint\./, '').replace(/\.q(\[\d+\])?$/, (m, k) => (k || ''));
  coords.forEach((s, i) => {
    s.colour = LINE[i % LINE.length];
    const e = document.createElement('span');
    e.innerHTML = '<i style="background:' + s.colour + '"></i>';
    e.appendChild(document.createTextNode(short(s.name) + ' [' + s.unit + ']'));
    legend.appendChild(e);
  });
  if (balance) {
    const e = document.createElement('span');
    e.innerHTML = '<i style="background:#333"></i>';
    e.appendChild(document.createTextNode('energy \u2212 work, change [J]: max ' + balanceMax.toExponential(1)));
    legend.appendChild(e);
  }
  if (!signals.length || n < 2) signalsPanel.classList.add('empty');
  function drawPlot(t) {
    if (signalsPanel.style.display === 'none' || !signals.length || n < 2) return;
    const dpr = window.devicePixelRatio || 1;
    const w = plot.clientWidth;
    const h = plot.clientHeight;
    if (plot.width !== Math.round(w * dpr)) { plot.width = Math.round(w * dpr); plot.height = Math.round(h * dpr); }
    const g = plot.getContext('2d');
    g.setTransform(dpr, 0, 0, dpr, 0, 0);
    g.clearRect(0, 0, w, h);
    const left = 44;
    const right = w - 6;
    const split = balance && coords.length ? h * 0.68 : balance ? 0 : h;
    const X = (tt) => left + ((tt - t0) / (t1 - t0)) * (right - left);
    g.font = '10px sans-serif';
    g.fillStyle = '#5b6675';
    function band(list, yr, top, bottom, colourOf) {
      const Y = (y) => bottom - ((y - yr[0]) / (yr[1] - yr[0])) * (bottom - top);
      g.strokeStyle = '#d5dae0';
      g.lineWidth = 1;
      g.strokeRect(left, top + 0.5, right - left, bottom - top - 1);
      g.fillText(Number(yr[1].toPrecision(3)).toString(), 2, top + 9);
      g.fillText(Number(yr[0].toPrecision(3)).toString(), 2, bottom - 2);
      for (const s of list) {
        g.strokeStyle = colourOf(s);
        g.lineWidth = 1.3;
        g.beginPath();
        for (let k = 0; k < n; k++) {
          const x = X(times[k]);
          const y = Y(s.v[k]);
          if (k === 0) g.moveTo(x, y); else g.lineTo(x, y);
        }
        g.stroke();
      }
    }
    if (coords.length) band(coords, coordRange, 2, split - 4, (s) => s.colour);
    if (balance) band([balance], balanceRange, split + 2, h - 12, () => '#333');
    g.fillText(t0.toFixed(2) + ' s', left, h - 1);
    g.fillText(t1.toFixed(2) + ' s', right - 34, h - 1);
    g.strokeStyle = '#c0392b';
    g.lineWidth = 1.5;
    g.beginPath();
    g.moveTo(X(t), 0);
    g.lineTo(X(t), h - 11);
    g.stroke();
  }
  function seekFromPlot(ev) {
    const rect = plot.getBoundingClientRect();
    const left = 44;
    const frac = (ev.clientX - rect.left - left) / (rect.width - left - 6);
    setTime(t0 + Math.min(Math.max(frac, 0), 1) * (t1 - t0));
  }
  let dragging = false;
  plot.addEventListener('pointerdown', (ev) => { dragging = true; seekFromPlot(ev); });
  window.addEventListener('pointerup', () => { dragging = false; });
  plot.addEventListener('pointermove', (ev) => { if (dragging) seekFromPlot(ev); });

  // ---- playback
  const slider = document.getElementById('slider');
  const playButton = document.getElementById('play');
  const timeLabel = document.getElementById('time');
  const clock = document.getElementById('clock');
  const speed = document.getElementById('speed');
  const loop = document.getElementById('loop');
  document.getElementById('title').textContent = data.name;
  slider.min = t0;
  slider.max = t1 > t0 ? t1 : t0 + 1;
  if (n < 2) document.getElementById('controls').classList.add('single');
  const digits = t1 - t0 < 10 ? 3 : 2;
  let time = t0;
  let playing = false;
  let dirty = true;
  function setTime(t) {
    time = Math.min(Math.max(t, t0), t1);
    dirty = true;
  }
  function setPlaying(p) {
    playing = p && n > 1;
    playButton.innerHTML = playing ? '&#10074;&#10074;' : '&#9654;';
  }
  playButton.addEventListener('click', () => {
    if (!playing && time >= t1) time = t0;
    setPlaying(!playing);
  });
  slider.addEventListener('input', () => setTime(Number(slider.value)));
  window.addEventListener('keydown', (ev) => {
    if (ev.target && (ev.target.tagName === 'SELECT' || (ev.target.tagName === 'INPUT' && ev.target.type === 'number'))) return;
    if (ev.code === 'Space') { ev.preventDefault(); playButton.click(); }
    if (ev.code === 'ArrowRight' || ev.code === 'ArrowLeft') {
      const [k] = frameAt(time);
      const next = ev.code === 'ArrowRight' ? Math.min(k + 1, n - 1) : Math.max(times[k] < time ? k : k - 1, 0);
      setPlaying(false);
      setTime(times[next]);
    }
  });
  const optFrames = document.getElementById('opt-frames');
  const optSites = document.getElementById('opt-sites');
  const optSignals = document.getElementById('opt-signals');
  function showFrames(on) { optFrames.checked = on; for (const b of bodies) b.axes.visible = on; }
  function showSites(on) { optSites.checked = on; for (const s of siteMarks) s.visible = on; }
  function showSignals(on) { optSignals.checked = on; signalsPanel.style.display = on && signals.length && n > 1 ? '' : 'none'; dirty = true; }
  const optGround = document.getElementById('opt-ground');
  const optCollision = document.getElementById('opt-collision');
  const optForces = document.getElementById('opt-forces');
  const optScale = document.getElementById('opt-fscale');
  const forceNote = document.getElementById('force-note');
  function setGroundVisible(on) { optGround.checked = on; if (ground) ground.mesh.visible = on; dirty = true; }
  function showCollision(on) { optCollision.checked = on; for (const c of contacts) c.wire.visible = on; dirty = true; }
  function showForces(on) { optForces.checked = on; arrows.visible = on && withForces.length > 0; dirty = true; }
  function describeScale() {
    const ref = data.forces ? data.forces.reference : 0;
    const what = data.forces && data.forces.basis === 'weight' ? 'weight' : data.forces && data.forces.basis === 'largest' ? 'largest force' : '';
    forceNote.textContent = (what ? what + ' ' + Number(ref.toPrecision(3)) + ' N: ' + Number((ref / forceScale).toPrecision(2)) + ' m; ' : '')
      + 'cut at ' + Number(CUT.toPrecision(2)) + ' m (dark)';
  }
  function setForceScale(x) {
    if (x > 0 && Number.isFinite(x)) forceScale = x;
    optScale.value = forceScale;
    describeScale();
    dirty = true;
  }
  optGround.addEventListener('change', () => setGroundVisible(optGround.checked));
  optCollision.addEventListener('change', () => showCollision(optCollision.checked));
  optForces.addEventListener('change', () => showForces(optForces.checked));
  optScale.addEventListener('change', () => setForceScale(Number(optScale.value)));
  if (!ground) optGround.parentElement.style.display = 'none';
  if (!contacts.length) optCollision.parentElement.style.display = 'none';
  if (!withForces.length) document.getElementById('forces-row').style.display = 'none';
  optFrames.addEventListener('change', () => showFrames(optFrames.checked));
  optSites.addEventListener('change', () => showSites(optSites.checked));
  optSignals.addEventListener('change', () => showSignals(optSignals.checked));
  if (!data.sites.length) optSites.parentElement.style.display = 'none';
  if (!signals.length || n < 2) optSignals.parentElement.style.display = 'none';

  window.addEventListener('resize', () => {
    camera.aspect = window.innerWidth / window.innerHeight;
    camera.updateProjectionMatrix();
    renderer.setSize(window.innerWidth, window.innerHeight);
    dirty = true;
  });

  // ---- the URL hash: start time, playing, switches
  showFrames(hash.get('frames') === '1');
  showSites(hash.get('sites') === '1');
  showSignals(hash.get('signals') !== '0');
  setGroundVisible(hash.get('ground') !== '0');
  showCollision(hash.get('collision') === '1');
  showForces(hash.get('forces') === '1');
  setForceScale(hash.has('fscale') ? Number(hash.get('fscale')) : forceScale);
  if (hash.get('ui') === '0') document.body.classList.add('hidden-ui');
  if (hash.has('trace')) setTrace(hash.get('trace'));
  if (hash.has('speed')) speed.value = hash.get('speed');
  if (hash.has('t')) setTime(Number(hash.get('t')));
  setPlaying(hash.get('play') !== '0');

  // ---- the loop
  const api = {
    ready: false,
    rendered: 0,
    frames: n,
    start: t0,
    stop: t1,
    bodies: bodies.map((b) => b.name),
    times: Array.from(times),
    time: () => time,
    setTime: (t) => { setPlaying(false); setTime(t); },
    play: () => setPlaying(true),
    pause: () => setPlaying(false),
    // world point (m) -> page pixels (CSS) in the canvas, as the camera now shows it
    project: (x, y, z) => {
      const v = new T.Vector3(x, y, z).project(camera);
      const rect = renderer.domElement.getBoundingClientRect();
      return [rect.left + ((v.x + 1) / 2) * rect.width, rect.top + ((1 - v.y) / 2) * rect.height, v.z];
    },
    setRobotVisible: (on) => { robot.visible = on; dirty = true; },
    setHelpersVisible: (on) => { if (grid) grid.visible = on; worldAxes.visible = on; dirty = true; },
    // the ground: normal, height, cell and the drawn square's corners (world, m), or null
    ground: ground ? ground.info : null,
    setGroundVisible,
    contacts: contacts.map((c) => c.name),
    showCollision,
    showForces,
    setForceScale,
    forceScale: () => forceScale,
    // per shape with recorded forces, as now drawn: force (N), base and tip (world, m), whether
    // shown (a zero force is not) and cut (longer than 2 L)
    arrows: () => withForces.map((c) => Object.assign({ name: c.name }, c.state)),
    setUi: (on) => { document.body.classList.toggle('hidden-ui', !on); dirty = true; },
    setTrace,
    showFrames,
    showSites,
    home,
  };
  window.triad = api;
  let last = performance.now();
  controls.addEventListener('change', () => { dirty = true; });
  function tick(now) {
    const dt = Math.min((now - last) / 1000, 0.25);
    last = now;
    if (playing) {
      let t = time + dt * Number(speed.value);
      if (t >= t1) {
        if (loop.checked) t = t0 + ((t - t0) % Math.max(t1 - t0, 1e-9));
        else { t = t1; setPlaying(false); }
      }
      setTime(t);
    }
    if (dirty) {
      const k = place(time);
      placeArrows(time);
      if (trace) trace.travelled.geometry.setDrawRange(0, k + 1);
      slider.value = time;
      const text = 't = ' + time.toFixed(digits) + ' s';
      clock.textContent = text;
      timeLabel.textContent = time.toFixed(digits) + ' / ' + t1.toFixed(digits) + ' s';
      drawPlot(time);
      renderer.render(scene, camera);
      api.rendered += 1;
      api.ready = true;
      document.body.dataset.ready = '1';
      dirty = false;
    }
    requestAnimationFrame(tick);
  }
  requestAnimationFrame(tick);
})();
