// siloscope share: the viewer of a run in one HTML page (docs/share.md). It reads the run packed into the
// page beside it (a JSON header, the frames deflated and base64-encoded), inflates them with the browser's
// own DecompressionStream, and draws them on a canvas as siloscope's movie does: grains by species or on a
// colour scale, the walls and the obstacle where the container is, each clog's arch from its formation to
// the clog's end. No library, no network. Every viewer on a page is one closure over its own container.
(function () {
  "use strict";
  const root = document.currentScript.parentElement;
  const H = JSON.parse(root.querySelector(".ss-header").textContent);
  const ABSENT = 0xffff;
  const ENDED = { rule: "#c0392b", vibration: "#2e86c1", spontaneous: "#95a5a6", run_end: "#7d3c98" };
  const ENDED_TEXT = { rule: "ended by the rule (arch removed)", vibration: "broken by the drive",
    spontaneous: "transient (resumed by itself)", run_end: "clogged at the run's end" };
  const COLORINGS = ["species", "speed", "force", "displacement", "coordination", "id"];
  const NO_VALUE = "#9a9a9a";  // a grain with no value (re-injected since the displacement's reference)
  const SPEEDS = [0.1, 0.25, 0.5, 1, 2, 4, 8];

  // --- the page's parts -----------------------------------------------------------------------------------
  const el = (tag, cls, parent, text) => {
    const e = document.createElement(tag);
    if (cls) e.className = cls;
    if (text !== undefined) e.textContent = text;
    (parent || root).appendChild(e);
    return e;
  };
  const L = H.look;
  root.style.setProperty("--ss-bg", L.background);
  if (L.dark) {
    root.style.setProperty("--ss-fg", "#e6e6ea");
    root.style.setProperty("--ss-panel", "rgba(28,28,34,0.94)");
    root.style.setProperty("--ss-line", "#555");
    root.style.setProperty("--ss-button", "#2a2a32");
  }
  root.tabIndex = 0;
  const title = el("div", "ss-title", root, H.name + ": " + H.title);
  const stage = el("div", "ss-stage");
  const canvas = el("canvas", "", stage);
  const grainBox = el("div", "ss-grain", stage);
  const status = el("div", "ss-status", stage, "loading " + H.frames + " frames...");
  const help = el("div", "ss-help", stage);
  const info = el("div", "ss-info");
  const timeline = el("canvas", "ss-timeline");
  const bar = el("div", "ss-controls");
  const button = (text, tip, fn) => {
    const b = el("button", "", bar, text);
    b.title = tip;
    b.addEventListener("click", (e) => { fn(); root.focus(); e.preventDefault(); });
    return b;
  };
  const select = (options, value, tip, fn) => {
    const s = el("select", "", bar);
    s.title = tip;
    for (const [v, text] of options) {
      const o = el("option", "", s, text);
      o.value = v;
    }
    s.value = value;
    s.addEventListener("change", () => { fn(s.value); root.focus(); });
    return s;
  };
  const prevClogButton = button("< clog", "previous clog (p)", () => prevClog());
  const backButton = button("<", "one frame back (left arrow)", () => seek(frame - 1));
  const playButton = button("play", "play or pause (space)", () => togglePlay());
  const forwardButton = button(">", "one frame forward (right arrow)", () => seek(frame + 1));
  const nextClogButton = button("clog >", "next clog (n)", () => nextClog());
  const speedSelect = select(SPEEDS.map((s) => [String(s), s + "x"]), "1", "playback speed (+ / -)",
    (v) => { speed = Number(v); });
  const colorSelect = select(COLORINGS.filter((c) => c !== "force" || H.fmax > 0).map((c) => [c, c]),
    COLORINGS.includes(L.color) ? L.color : "species", "colour the grains by (k)", (v) => { coloring = v; draw(); });
  const viewSelect = select([["split", "split"], ["hopper", "whole container"], ["outlet", "outlet"]], "split",
    "camera (v); wheel zooms, drag pans, 0 resets", (v) => { setView(v); });
  button("?", "every key (?)", () => toggleHelp());
  const where = el("span", "ss-where", bar);
  help.innerHTML = "<b>Keys</b><table>" + [
    ["space", "play / pause"], ["left / right", "one frame back / forward"],
    ["shift + left / right", "one second back / forward"], ["home / end", "first / last frame"],
    ["p / n", "previous / next clog (its start: the last exit)"],
    ["a", "this clog's arch where it forms"], ["c", "play to the next clog"],
    ["+ / -", "faster / slower"], ["k", "colour by species, speed, force, displacement, coordination, id"],
    ["v", "camera: split, whole container, outlet"], ["0", "reset zoom"],
    ["click a grain", "its id, species, position, velocity, force"], ["esc", "clear the grain"],
    ["timeline", "click or drag to seek; bands are clogs, coloured by how they ended"],
    ["?", "this list"]].map(([k, v]) => "<tr><td><b>" + k + "</b></td><td>" + v + "</td></tr>").join("") +
    "</table><p>siloscope " + H.siloscope + "<br>made by: <code></code></p>";
  help.querySelector("code").textContent = H.command;

  // --- state --------------------------------------------------------------------------------------------------
  let D = null;  // the decoded frames
  let frame = 0, playing = false, speed = 1, coloring = colorSelect.value, picked = -1, stopAt = -1;
  let views = [], viewKind = "split", playClock = 0, lastTick = 0;
  const zoom = {};  // per view name: {s, dx, dy} on top of its fit
  const drawTimes = [];
  const api = { ready: false, error: null, drawTimes, loadMs: 0 };

  // --- decoding -----------------------------------------------------------------------------------------------
  async function decode() {
    const text = root.querySelector(".ss-data").textContent.trim();
    const bin = atob(text);
    const bytes = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; ++i) bytes[i] = bin.charCodeAt(i);
    const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream("deflate"));
    const buf = await new Response(stream).arrayBuffer();
    const n = H.n, nf = H.frames, ns = H.species.length;
    let at = 0;
    const take = (Type, count) => {
      const size = Type.BYTES_PER_ELEMENT * count;
      if (at + size > buf.byteLength) throw new Error("the page's frames are cut short");
      const a = new Type(buf.slice(at, at + size));
      at += size;
      return a;
    };
    const d = {};
    d.radius = take(Float32Array, n);
    d.species = take(Uint8Array, n);
    d.sides = take(Uint8Array, n);
    d.t = take(Float64Array, nf);
    d.since = take(Float32Array, nf);
    d.clogStart = take(Float32Array, nf);
    d.cx = take(Float32Array, nf);
    d.cy = take(Float32Array, nf);
    d.clog = take(Int32Array, nf);
    d.flags = take(Uint8Array, nf);
    d.archCount = take(Uint8Array, nf);
    d.exits = take(Int32Array, nf * ns);
    d.archStart = new Uint32Array(nf + 1);
    for (let k = 0; k < nf; ++k) d.archStart[k + 1] = d.archStart[k] + d.archCount[k];
    d.arch = take(Int32Array, d.archStart[nf]);
    const undelta = (a, mask) => {
      for (let k = 1; k < nf; ++k) {
        const o = k * n, p = o - n;
        for (let i = 0; i < n; ++i) a[o + i] = (a[o + i] + a[p + i]) & mask;
      }
      return a;
    };
    d.x = undelta(take(Uint16Array, nf * n), 0xffff);
    d.y = undelta(take(Uint16Array, nf * n), 0xffff);
    d.vx = new Int16Array(undelta(take(Uint16Array, nf * n), 0xffff).buffer);
    d.vy = new Int16Array(undelta(take(Uint16Array, nf * n), 0xffff).buffer);
    d.angle = H.angles ? undelta(take(Uint8Array, nf * n), 0xff) : null;
    d.force = H.fmax > 0 ? undelta(take(Uint8Array, nf * n), 0xff) : null;
    if (at !== buf.byteLength) throw new Error("the page's frames have " + (buf.byteLength - at) + " bytes too many");
    // The frame each clog starts at and where its arch first shows (formation, or the first frame with it).
    d.clogFrame = H.clogs.map((c) => nearestFrame(d.t, c.start));
    d.archFrame = H.clogs.map((c, j) => {
      for (let k = Math.max(0, nearestFrame(d.t, c.start) - 1); k < nf && d.t[k] <= c.end + 1e-9; ++k)
        if (d.clog[k] === j + 1 && d.archCount[k] > 0 && (d.flags[k] & 5)) return k;
      return -1;
    });
    // The displacement's reference: the first frame at or after the look's displacement_from (-1: none).
    d.displacementRef = d.t.findIndex((t) => t >= L.displacement_from - 1e-9);
    d.idColor = [];
    for (let i = 0; i < n; ++i) d.idColor.push(idColor(i));
    return d;
  }
  function nearestFrame(t, time) {
    let lo = 0, hi = t.length - 1;
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (t[mid] < time) lo = mid + 1; else hi = mid;
    }
    if (lo > 0 && Math.abs(t[lo - 1] - time) <= Math.abs(t[lo] - time)) return lo - 1;
    return lo;
  }

  // --- what a grain is at frame k ------------------------------------------------------------------------------
  const px = (k, i) => H.extent[0] + D.x[k * H.n + i] * H.q[0];
  const py = (k, i) => H.extent[1] + D.y[k * H.n + i] * H.q[1];
  const present = (k, i) => D.x[k * H.n + i] !== ABSENT;
  const vel = (k, i) => [D.vx[k * H.n + i] * H.vq, D.vy[k * H.n + i] * H.vq];
  const force = (k, i) => (D.force ? Math.pow(D.force[k * H.n + i] / 255, 2) * H.fmax : 0);
  const extent = (sides) => (sides >= 3 ? Math.sqrt(2 * Math.PI / (sides * Math.sin(2 * Math.PI / sides))) : 1);
  function idColor(i) {  // hues a golden angle apart at three lightness levels (render::id_color's idea)
    const h = (i * 137.508) % 360, l = [45, 60, 35][i % 3];
    return "hsl(" + h.toFixed(1) + ",70%," + l + "%)";
  }
  function rampColor(u) {
    const r = L.colormap;
    return r[Math.max(0, Math.min(r.length - 1, Math.round(u * (r.length - 1))))];
  }
  // Each grain's colour at frame k as an index into the returned list (-1: not in the frame), in colorIdx.
  let colorIdx = null, sorted = null, sortCount = new Int32Array(64);
  const speciesColors = H.species.map((sp) => sp.color);
  function colorIndices(k) {
    if (!colorIdx) { colorIdx = new Int32Array(H.n); sorted = new Int32Array(H.n); }
    const o = k * H.n;
    if (coloring === "id" || coloring === "species") {
      for (let i = 0; i < H.n; ++i)
        colorIdx[i] = D.x[o + i] === ABSENT ? -1 : coloring === "id" ? i : Math.min(D.species[i], speciesColors.length - 1);
      return coloring === "id" ? D.idColor : speciesColors;
    }
    const values = grainValues(k), lo = scaleBottom(), top = scaleTop(), last = L.colormap.length - 1;
    for (let i = 0; i < H.n; ++i) {
      const v = values[i];
      colorIdx[i] = D.x[o + i] === ABSENT ? -1 : Number.isNaN(v) ? last + 1
        : Math.max(0, Math.min(last, Math.round((v - lo) / Math.max(1e-12, top - lo) * last)));
    }
    return rampWithNoValue;
  }
  const rampWithNoValue = L.colormap.concat([NO_VALUE]);
  // The scaled colourings' values at frame k (render/grain_values.h's rules): speed, the summed contact force,
  // the displacement since the first frame at or after the look's displacement_from (none for a grain more
  // than two diameters higher than it was: re-injected), the coordination (pairs of grains whose equal-area
  // disks are closer than the sum of their radii plus 2% of it).
  let valueBuf = null, frameTop = 0;
  function grainValues(k) {
    if (!valueBuf) valueBuf = new Float32Array(H.n);
    const v = valueBuf, o = k * H.n;
    frameTop = 0;
    if (coloring === "speed") for (let i = 0; i < H.n; ++i) v[i] = Math.hypot(D.vx[o + i], D.vy[o + i]) * H.vq;
    else if (coloring === "force") for (let i = 0; i < H.n; ++i) v[i] = force(k, i);
    else if (coloring === "displacement") {
      const r = D.displacementRef;
      for (let i = 0; i < H.n; ++i) {
        if (r < 0 || k < r || !present(r, i)) { v[i] = r >= 0 && k >= r ? NaN : 0; continue; }
        const dx = px(k, i) - px(r, i), dy = py(k, i) - py(r, i);
        v[i] = dy > 4 * D.radius[i] ? NaN : Math.hypot(dx, dy);
        if (v[i] > frameTop) frameTop = v[i];
      }
    } else if (coloring === "coordination") coordination(k, v);
    return v;
  }
  function coordination(k, out) {
    let rmax = 0;
    for (let i = 0; i < H.n; ++i) rmax = Math.max(rmax, D.radius[i]);
    const cell = 2.04 * rmax, cells = new Map();
    out.fill(0);
    for (let i = 0; i < H.n; ++i) {
      if (!present(k, i)) continue;
      const key = Math.floor(px(k, i) / cell) * 100003 + Math.floor(py(k, i) / cell);
      const list = cells.get(key);
      if (list) list.push(i); else cells.set(key, [i]);
    }
    for (let i = 0; i < H.n; ++i) {
      if (!present(k, i)) continue;
      const cx = Math.floor(px(k, i) / cell), cy = Math.floor(py(k, i) / cell);
      for (let a = -1; a <= 1; ++a) for (let b = -1; b <= 1; ++b) {
        const list = cells.get((cx + a) * 100003 + cy + b);
        if (!list) continue;
        for (const j of list)
          if (j > i && Math.hypot(px(k, i) - px(k, j), py(k, i) - py(k, j)) < 1.02 * (D.radius[i] + D.radius[j])) {
            ++out[i];
            ++out[j];
          }
      }
    }
  }
  // The colour scale: the look's own range for the look's colouring, the defaults for the others.
  function scaleBottom() { return coloring === L.color ? L.color_min : 0; }
  function scaleTop() {
    if (coloring === "speed") return coloring === L.color ? L.speed_max : 0.5;
    if (coloring === "force") return coloring === L.color ? L.force_max : 20;
    if (coloring === "coordination") return L.coordination_max;
    if (coloring === "displacement") return L.displacement_max > 0 ? L.displacement_max : Math.max(frameTop, 1e-9);
    return 0;
  }

  // --- cameras ------------------------------------------------------------------------------------------------
  // A camera fits a box of the container's frame into a pixel rectangle, the container turned by its tilt
  // (render/camera.h's fit). World to pixels: turn, scale, flip y.
  function fit(x0, y0, x1, y1, r) {
    const a = H.geometry.tilt, ca = Math.cos(a), sa = Math.sin(a);
    const w = x1 - x0, h = y1 - y0;
    const bw = Math.abs(ca) * w + Math.abs(sa) * h, bh = Math.abs(sa) * w + Math.abs(ca) * h;
    const s = Math.min(r.w / bw, r.h / bh);
    return { cx: 0.5 * (x0 + x1), cy: 0.5 * (y0 + y1), s, ca, sa, r };
  }
  function layout() {
    const W = canvas.width, Hh = canvas.height, G = H.geometry;
    const margin = 0.04 * G.height;
    const hopper = (r) => ({ name: "hopper", cam: fit(G.x_left - margin, -margin, G.x_right + margin, G.height + margin, r) });
    const outlet = (r) => {
      const k = G.grain_diameter / 0.13, d = G.grain_diameter;
      const flat = G.walls[0][1] === G.walls[0][3];
      const wide = flat ? Math.max(6.5 * d, G.half_aperture + 3 * d) : 0.6 * k;
      const half = Math.min(0.5 * (G.x_right - G.x_left) + 0.05 * k, wide);
      let top = Math.min(1.05 * k, G.height);
      if (G.obstacle) top = Math.max(top, Math.min(G.height, G.obstacle.y + 0.5 * G.obstacle.h + 0.5 * d));
      return { name: "outlet", cam: fit(-half, -0.25 * k, half, top, r) };
    };
    if (viewKind === "hopper") return [hopper({ x: 0, y: 0, w: W, h: Hh })];
    if (viewKind === "outlet") return [outlet({ x: 0, y: 0, w: W, h: Hh })];
    const bw = G.x_right - G.x_left + 2 * margin, bh = G.height + 2 * margin;
    const ca = Math.abs(Math.cos(G.tilt)), sa = Math.abs(Math.sin(G.tilt));
    const left = Math.max(Math.max(1, W / 10), Math.min(W / 2, Math.round(1.15 * (ca * bw + sa * bh) / (sa * bw + ca * bh) * Hh)));
    return [hopper({ x: 0, y: 0, w: left, h: Hh }), outlet({ x: left, y: 0, w: W - left, h: Hh })];
  }
  function camOf(v) {
    const z = zoom[v.name] || { s: 1, dx: 0, dy: 0 };
    return Object.assign({}, v.cam, { s: v.cam.s * z.s, cx: v.cam.cx + z.dx, cy: v.cam.cy + z.dy });
  }
  function toPixels(c, x, y) {
    const u = c.ca * (x - c.cx) - c.sa * (y - c.cy), v = c.sa * (x - c.cx) + c.ca * (y - c.cy);
    return [c.r.x + 0.5 * c.r.w + u * c.s, c.r.y + 0.5 * c.r.h - v * c.s];
  }
  function toWorld(c, X, Y) {
    const u = (X - c.r.x - 0.5 * c.r.w) / c.s, v = -(Y - c.r.y - 0.5 * c.r.h) / c.s;
    return [c.cx + c.ca * u + c.sa * v, c.cy - c.sa * u + c.ca * v];
  }
  function viewAt(X, Y) {
    for (const v of views) if (X >= v.cam.r.x && X < v.cam.r.x + v.cam.r.w && Y >= v.cam.r.y && Y < v.cam.r.y + v.cam.r.h) return v;
    return null;
  }
  function setView(kind) {
    viewKind = kind;
    viewSelect.value = kind;
    for (const k in zoom) delete zoom[k];
    resize();
  }

  // --- drawing ------------------------------------------------------------------------------------------------
  function shapePath(ctx, c, k, i, grow) {
    const [X, Y] = toPixels(c, px(k, i), py(k, i));
    const sides = D.sides[i];
    const R = D.radius[i] * extent(sides) * c.s + grow;
    if (sides < 3) {
      ctx.moveTo(X + R, Y);
      ctx.arc(X, Y, R, 0, 2 * Math.PI);
      return;
    }
    const a0 = (D.angle ? D.angle[k * H.n + i] / 256 : 0) * 2 * Math.PI / sides + H.geometry.tilt;
    for (let m = 0; m <= sides; ++m) {
      const a = a0 + 2 * Math.PI * m / sides;
      const qx = X + R * Math.cos(a), qy = Y - R * Math.sin(a);
      if (m === 0) ctx.moveTo(qx, qy); else ctx.lineTo(qx, qy);
    }
    ctx.closePath();
  }
  function drawView(ctx, v, k) {
    const c = camOf(v), r = c.r, G = H.geometry, dpr = window.devicePixelRatio || 1;
    ctx.save();
    ctx.beginPath();
    ctx.rect(r.x, r.y, r.w, r.h);
    ctx.clip();
    const ox = D.cx[k], oy = D.cy[k];
    // Walls and the obstacle, where the container is now.
    ctx.strokeStyle = L.walls;
    ctx.fillStyle = L.walls;
    ctx.lineCap = "round";
    ctx.lineWidth = Math.max(1.5 * dpr, 0.01 * G.grain_diameter / 0.13 * c.s);
    ctx.beginPath();
    for (const w of G.walls) {
      const [ax, ay] = toPixels(c, w[0] + ox, w[1] + oy), [bx, by] = toPixels(c, w[2] + ox, w[3] + oy);
      ctx.moveTo(ax, ay);
      ctx.lineTo(bx, by);
    }
    ctx.stroke();
    if (G.obstacle) {
      const o = G.obstacle;
      ctx.beginPath();
      if (o.kind === "disk") {
        const [X, Y] = toPixels(c, o.x + ox, o.y + oy);
        ctx.arc(X, Y, 0.5 * o.w * c.s, 0, 2 * Math.PI);
      } else {
        const corners = [[-1, -1], [1, -1], [1, 1], [-1, 1]].map(([sx, sy]) => toPixels(c, o.x + ox + sx * 0.5 * o.w, o.y + oy + sy * 0.5 * o.h));
        corners.forEach(([X, Y], m) => (m ? ctx.lineTo(X, Y) : ctx.moveTo(X, Y)));
        ctx.closePath();
      }
      ctx.fill();
    }
    // The arch: a ring round each member (drawn under the grains: only its outer half shows) and bonds.
    const a0 = D.archStart[k], a1 = D.archStart[k + 1];
    const halo = Math.max(2 * dpr, L.halo_m * c.s);
    let archAlpha = 0;
    if (a1 > a0) {
      const f = D.flags[k];
      archAlpha = (f & 4) || (f & 2) || D.since[k] >= L.fade_below ? 1 : 0.35;
      ctx.globalAlpha = archAlpha;
      ctx.lineJoin = "round";
      ctx.beginPath();
      for (let a = a0; a < a1; ++a) if (D.arch[a] >= 0 && D.arch[a] < H.n && present(k, D.arch[a])) shapePath(ctx, c, k, D.arch[a], 0);
      if (!L.dark) {  // a dark edge outside the ring, as the movies have it: gold alone is 1.6:1 on white
        ctx.strokeStyle = "rgba(31,31,31,0.9)";
        ctx.lineWidth = 2 * (halo + Math.max(dpr, 0.35 * halo));
        ctx.stroke();
      }
      ctx.strokeStyle = L.arch;
      ctx.lineWidth = 2 * halo;
      ctx.stroke();
      ctx.globalAlpha = 1;
    }
    // The grains, one path per colour: a counting sort by colour into arrays kept from frame to frame.
    const palette = colorIndices(k);
    const count = sortCount.length >= palette.length + 1 ? sortCount : (sortCount = new Int32Array(palette.length + 1));
    count.fill(0, 0, palette.length + 1);
    for (let i = 0; i < H.n; ++i) if (colorIdx[i] >= 0) ++count[colorIdx[i] + 1];
    for (let m = 1; m <= palette.length; ++m) count[m] += count[m - 1];
    for (let i = 0; i < H.n; ++i) if (colorIdx[i] >= 0) sorted[count[colorIdx[i]]++] = i;
    for (let m = 0, at = 0; m < palette.length; ++m) {
      const end = count[m];
      if (end === at) continue;
      ctx.fillStyle = palette[m];
      ctx.beginPath();
      for (; at < end; ++at) shapePath(ctx, c, k, sorted[at], 0);
      ctx.fill();
    }
    if (a1 > a0) {  // bonds between neighbours that touch
      ctx.globalAlpha = archAlpha;
      ctx.strokeStyle = "#1a1a1a";
      ctx.lineWidth = halo;
      ctx.beginPath();
      for (let a = a0; a + 1 < a1; ++a) {
        const i = D.arch[a], j = D.arch[a + 1];
        if (i < 0 || j < 0 || i >= H.n || j >= H.n || !present(k, i) || !present(k, j)) continue;
        const reach = 1.05 * (D.radius[i] * extent(D.sides[i]) + D.radius[j] * extent(D.sides[j]));
        if (Math.hypot(px(k, i) - px(k, j), py(k, i) - py(k, j)) > reach) continue;
        const [X1, Y1] = toPixels(c, px(k, i), py(k, i)), [X2, Y2] = toPixels(c, px(k, j), py(k, j));
        ctx.moveTo(X1, Y1);
        ctx.lineTo(X2, Y2);
      }
      ctx.stroke();
      ctx.globalAlpha = 1;
    }
    if (picked >= 0 && present(k, picked)) {  // the picked grain: a ring and its id
      ctx.strokeStyle = L.picked;
      ctx.lineWidth = Math.max(2 * dpr, 0.5 * halo);
      ctx.beginPath();
      shapePath(ctx, c, k, picked, ctx.lineWidth);
      ctx.stroke();
      const [X, Y] = toPixels(c, px(k, picked), py(k, picked));
      ctx.fillStyle = L.dark ? "#fff" : "#000";
      ctx.font = Math.round(12 * dpr * L.font_scale) + "px DejaVu Sans, sans-serif";
      ctx.fillText(String(picked), X + D.radius[picked] * c.s + 3 * dpr, Y - D.radius[picked] * c.s);
    }
    ctx.restore();
  }
  // A scale bar (a round length near a fifth of the view's width) at the bottom left of the last view.
  function drawScale(ctx) {
    const v = views[views.length - 1], c = camOf(v), dpr = window.devicePixelRatio || 1;
    const want = 0.2 * c.r.w / c.s;
    const p = Math.pow(10, Math.floor(Math.log10(want)));
    const len = [5, 2, 1].map((m) => m * p).find((l) => l <= want) || p;
    const X = c.r.x + 14 * dpr, Y = c.r.y + c.r.h - 14 * dpr, Wd = len * c.s;
    ctx.fillStyle = L.dark ? "#e6e6ea" : "#222";
    ctx.fillRect(X, Y - 3 * dpr, Wd, 3 * dpr);
    ctx.font = Math.round(12 * dpr * L.font_scale) + "px DejaVu Sans, sans-serif";
    const [value, unit] = len >= 1 ? [len, " m"] : len >= 0.01 ? [len * 100, " cm"] : [len * 1000, " mm"];
    ctx.fillText(String(Number(value.toPrecision(1))) + unit, X, Y - 7 * dpr);
    if (!["species", "id"].includes(coloring)) {  // the colour bar
      const bw = 120 * dpr, bh = 10 * dpr, bx = c.r.x + c.r.w - bw - 14 * dpr, by = Y - bh;
      for (let m = 0; m < bw; ++m) {
        ctx.fillStyle = rampColor(m / (bw - 1));
        ctx.fillRect(bx + m, by, 1.5, bh);
      }
      ctx.fillStyle = L.dark ? "#e6e6ea" : "#222";
      const unit = { speed: " m/s", force: " N", displacement: " m", coordination: "" }[coloring];
      const top = scaleTop();
      ctx.textAlign = "right";
      ctx.fillText(coloring + " " + scaleBottom() + " to " + Number(top.toPrecision(3)) + unit, bx + bw, by - 5 * dpr);
      ctx.textAlign = "left";
    }
  }
  function draw() {
    if (!D || !views.length) return;
    const t0 = performance.now();
    const ctx = canvas.getContext("2d");
    ctx.fillStyle = L.background;
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    for (const v of views) drawView(ctx, v, frame);
    if (views.length > 1) {
      ctx.fillStyle = L.dark ? "#555" : "#ccc";
      ctx.fillRect(views[1].cam.r.x - 1, 0, 1, canvas.height);
    }
    drawScale(ctx);
    drawTimeline();
    describe();
    drawTimes.push(performance.now() - t0);
    if (drawTimes.length > 10000) drawTimes.shift();
  }

  // --- the information line, the grain panel, the timeline -------------------------------------------------
  function describe() {
    const k = frame, ns = H.species.length, t = D.t[k];
    // Each species' count after a dot of its colour: the legend and the exits at once.
    info.replaceChildren();
    const add = (text, color) => {
      const e = el("span", "", info, text);
      if (color) e.style.color = color;
    };
    add("t = " + D.t[k].toFixed(3) + " s  \u00b7  exits: ");
    H.species.forEach((s, j) => {
      add("\u25cf ", coloring === "species" ? s.color : undefined);
      add(s.name + " " + D.exits[k * ns + j] + (j + 1 < ns ? ", " : ""));
    });
    let state = "flowing";
    const f = D.flags[k], c = D.clog[k], C = H.clogs[c - 1];
    if (f & 1) state = "clog " + c + " of " + H.clogs.length + ", for " + (t - D.clogStart[k]).toFixed(2) + " s" + (f & 2 ? " (arrested)" : "");
    else if ((f & 4) && C) state = "arch forming: clog " + c + " of " + H.clogs.length;
    if (C && (f & 5)) state += ", " + ENDED_TEXT[C.ended_by];
    add("  \u00b7  " + state);
    where.textContent = "frame " + (k + 1) + " / " + H.frames;
    playButton.textContent = playing ? "pause" : "play";
    if (picked >= 0) {
      const i = picked;
      if (!present(k, i)) {
        grainBox.textContent = "grain " + i + "\nnot in this frame";
      } else {
        const [vx, vy] = vel(k, i);
        const lines = ["grain " + i + " (" + (H.species[D.species[i]] || { name: "?" }).name + ")",
          "x, y   " + px(k, i).toFixed(4) + ", " + py(k, i).toFixed(4) + " m",
          "v      " + vx.toFixed(3) + ", " + vy.toFixed(3) + " m/s",
          "speed  " + Math.hypot(vx, vy).toFixed(3) + " m/s",
          "radius " + D.radius[i].toFixed(4) + " m"];
        if (D.force) lines.push("force  " + force(k, i).toFixed(2) + " N (summed contacts)");
        for (let a = D.archStart[k]; a < D.archStart[k + 1]; ++a)
          if (D.arch[a] === i) lines.push("arch member " + (a - D.archStart[k] + 1) + " of " + D.archCount[k]);
        grainBox.textContent = lines.join("\n");
      }
      grainBox.style.display = "block";
    } else {
      grainBox.style.display = "none";
    }
  }
  function timeX(t) {
    const t0 = D.t[0], t1 = D.t[H.frames - 1];
    return (t - t0) / Math.max(1e-12, t1 - t0) * timeline.width;
  }
  function drawTimeline() {
    const ctx = timeline.getContext("2d"), W = timeline.width, Hh = timeline.height;
    ctx.fillStyle = L.dark ? "#1c1c22" : "#f2f2f2";
    ctx.fillRect(0, 0, W, Hh);
    for (const c of H.clogs) {
      const x0 = timeX(c.start), x1 = timeX(c.end);
      if (x1 < 0 || x0 > W) continue;
      ctx.fillStyle = ENDED[c.ended_by] || "#888";
      ctx.fillRect(x0, 0, Math.max(1, x1 - x0), Hh);
    }
    // A time axis: ticks at a round step, labelled, under the bands.
    const span = D.t[H.frames - 1] - D.t[0], dpr = window.devicePixelRatio || 1;
    const want = span / Math.max(1, W / (70 * dpr)), p = Math.pow(10, Math.floor(Math.log10(Math.max(1e-9, want))));
    const step = [1, 2, 5, 10].map((m) => m * p).find((s) => s >= want) || 10 * p;
    ctx.fillStyle = L.dark ? "#1c1c22" : "#f2f2f2";
    ctx.fillRect(0, Hh - 13 * dpr, W, 13 * dpr);
    ctx.fillStyle = L.dark ? "#ccc" : "#333";
    ctx.font = Math.round(10 * dpr) + "px DejaVu Sans, sans-serif";
    for (let s = Math.ceil(D.t[0] / step) * step; s <= D.t[H.frames - 1] + 1e-9; s += step) {
      const X = Math.round(timeX(s));
      ctx.fillRect(X, Hh - 13 * dpr, 1, 3 * dpr);
      ctx.fillText(Number(s.toPrecision(6)) + (s === Math.ceil(D.t[0] / step) * step ? " s" : ""), X + 2 * dpr, Hh - 2 * dpr);
    }
    const x = timeX(D.t[frame]);
    ctx.fillStyle = L.dark ? "#fff" : "#000";
    ctx.fillRect(Math.round(x) - 1, 0, 2, Hh);
  }

  // --- navigation ---------------------------------------------------------------------------------------------
  function seek(k) {
    if (!D) return;
    frame = Math.max(0, Math.min(H.frames - 1, Math.round(k)));
    playClock = D.t[frame];
    draw();
  }
  function stop() { playing = false; stopAt = -1; draw(); }
  function togglePlay() {
    if (!D) return;
    playing = !playing;
    stopAt = -1;
    if (playing && frame >= H.frames - 1) seek(0);
    playClock = D.t[frame];
    lastTick = performance.now();
    draw();
    if (playing) requestAnimationFrame(tick);
  }
  function tick(now) {
    if (!playing) return;
    playClock += Math.min(0.25, (now - lastTick) / 1000) * speed;
    lastTick = now;
    let k = frame;
    while (k + 1 < H.frames && D.t[k + 1] <= playClock + 1e-9) ++k;
    if (stopAt >= 0 && k >= stopAt) { k = stopAt; playing = false; stopAt = -1; }
    if (k >= H.frames - 1) playing = false;
    if (k !== frame) { frame = k; draw(); } else if (!playing) draw();
    if (playing) requestAnimationFrame(tick);
  }
  function clogIndexAfter(k) { return D.clogFrame.findIndex((f) => f > k); }
  function nextClog() {
    const j = clogIndexAfter(frame);
    if (j >= 0) { playing = false; seek(D.clogFrame[j]); }
  }
  function prevClog() {
    let j = -1;
    D.clogFrame.forEach((f, m) => { if (f < frame) j = m; });
    if (j >= 0) { playing = false; seek(D.clogFrame[j]); }
  }
  function clogAt(k) {  // the clog whose start..end holds frame k, or -1
    const t = D.t[k];
    return H.clogs.findIndex((c, j) => k >= D.clogFrame[j] && t <= c.end + 1e-9);
  }
  function archOfClog() {  // this clog's arch where it first shows (the clog under the cursor, or the next)
    let j = clogAt(frame);
    if (j < 0) j = clogIndexAfter(frame);
    while (j >= 0 && j < H.clogs.length && D.archFrame[j] < 0) ++j;
    if (j >= 0 && j < H.clogs.length) { playing = false; seek(D.archFrame[j]); }
  }
  function playToClog() {
    const j = clogIndexAfter(frame);
    if (j < 0) return;
    if (!playing) togglePlay();
    stopAt = D.clogFrame[j];
  }
  function toggleHelp() { help.style.display = help.style.display === "block" ? "none" : "block"; }
  function changeSpeed(step) {
    const m = Math.max(0, Math.min(SPEEDS.length - 1, SPEEDS.indexOf(speed) + step));
    speed = SPEEDS[m];
    speedSelect.value = String(speed);
  }

  // --- input ----------------------------------------------------------------------------------------------------
  root.addEventListener("keydown", (e) => {
    if (!D || e.target.tagName === "SELECT" || e.ctrlKey || e.metaKey || e.altKey) return;
    const one = Math.max(1, Math.round(1 / Math.max(1e-9, H.frame_interval)));
    const keys = {
      " ": () => togglePlay(), ArrowLeft: () => { playing = false; seek(frame - (e.shiftKey ? one : 1)); },
      ArrowRight: () => { playing = false; seek(frame + (e.shiftKey ? one : 1)); },
      Home: () => seek(0), End: () => seek(H.frames - 1), n: () => nextClog(), p: () => prevClog(),
      a: () => archOfClog(), c: () => playToClog(), "+": () => changeSpeed(1), "=": () => changeSpeed(1),
      "-": () => changeSpeed(-1), k: () => {
        const opts = [...colorSelect.options].map((o) => o.value);
        coloring = colorSelect.value = opts[(opts.indexOf(coloring) + 1) % opts.length];
        draw();
      },
      v: () => setView({ split: "hopper", hopper: "outlet", outlet: "split" }[viewKind]),
      0: () => { for (const z in zoom) delete zoom[z]; draw(); },
      "?": () => toggleHelp(), Escape: () => { picked = -1; help.style.display = "none"; draw(); },
    };
    const fn = keys[e.key];
    if (fn) { fn(); e.preventDefault(); }
  });
  function canvasXY(e) {
    const b = canvas.getBoundingClientRect(), dpr = window.devicePixelRatio || 1;
    return [(e.clientX - b.left) * dpr, (e.clientY - b.top) * dpr];
  }
  function pick(X, Y) {
    const v = viewAt(X, Y);
    if (!v) return -1;
    const c = camOf(v), [x, y] = toWorld(c, X, Y);
    let best = -1, bestD = Infinity;
    for (let i = 0; i < H.n; ++i) {
      if (!present(frame, i)) continue;
      const d = Math.hypot(px(frame, i) - x, py(frame, i) - y);
      if (d <= D.radius[i] * extent(D.sides[i]) && d < bestD) { best = i; bestD = d; }
    }
    return best;
  }
  let drag = null;
  canvas.addEventListener("pointerdown", (e) => {
    root.focus();
    const [X, Y] = canvasXY(e), v = viewAt(X, Y);
    drag = { X, Y, v, moved: false, z: v ? Object.assign({ s: 1, dx: 0, dy: 0 }, zoom[v.name]) : null };
    canvas.setPointerCapture(e.pointerId);
  });
  canvas.addEventListener("pointermove", (e) => {
    if (!drag || !drag.v) return;
    const [X, Y] = canvasXY(e);
    if (!drag.moved && Math.hypot(X - drag.X, Y - drag.Y) < 5) return;
    drag.moved = true;
    const c = camOf(drag.v), du = (X - drag.X) / c.s, dv = -(Y - drag.Y) / c.s;
    zoom[drag.v.name] = { s: drag.z.s, dx: drag.z.dx - (c.ca * du + c.sa * dv), dy: drag.z.dy - (-c.sa * du + c.ca * dv) };
    draw();
  });
  canvas.addEventListener("pointerup", (e) => {
    if (drag && !drag.moved && D) {
      const [X, Y] = canvasXY(e);
      picked = pick(X, Y);
      draw();
    }
    drag = null;
  });
  canvas.addEventListener("wheel", (e) => {
    const [X, Y] = canvasXY(e), v = viewAt(X, Y);
    if (!v || !D) return;
    e.preventDefault();
    const before = toWorld(camOf(v), X, Y);
    const z = Object.assign({ s: 1, dx: 0, dy: 0 }, zoom[v.name]);
    z.s = Math.max(0.2, Math.min(50, z.s * Math.exp(-e.deltaY * 0.0015)));
    zoom[v.name] = z;
    const after = toWorld(camOf(v), X, Y);
    z.dx += before[0] - after[0];
    z.dy += before[1] - after[1];
    draw();
  }, { passive: false });
  let scrubbing = false;
  const scrub = (e) => {
    const b = timeline.getBoundingClientRect(), u = (e.clientX - b.left) / Math.max(1, b.width);
    playing = false;
    seek(nearestFrame(D.t, D.t[0] + u * (D.t[H.frames - 1] - D.t[0])));
  };
  timeline.addEventListener("pointerdown", (e) => {
    if (!D) return;
    root.focus();
    scrubbing = true;
    timeline.setPointerCapture(e.pointerId);
    scrub(e);
  });
  timeline.addEventListener("pointermove", (e) => { if (scrubbing) scrub(e); });
  timeline.addEventListener("pointerup", () => { scrubbing = false; });
  function resize() {
    const dpr = window.devicePixelRatio || 1;
    const b = stage.getBoundingClientRect(), tb = timeline.getBoundingClientRect();
    canvas.width = Math.max(1, Math.round(b.width * dpr));
    canvas.height = Math.max(1, Math.round(b.height * dpr));
    timeline.width = Math.max(1, Math.round(tb.width * dpr));
    timeline.height = Math.max(1, Math.round(tb.height * dpr));
    views = layout();
    draw();
  }
  new ResizeObserver(resize).observe(root);

  // --- the test's and the page's handle ----------------------------------------------------------------------
  // window.siloscopeViewers: one entry per viewer on the page (tests drive it; a page may script it).
  // (defineProperties, not Object.assign, which would read each getter once.)
  Object.defineProperties(api, Object.getOwnPropertyDescriptors({
    root, canvas,
    get frame() { return frame; }, get frames() { return H.frames; }, get picked() { return picked; },
    get playing() { return playing; }, get coloring() { return coloring; }, header: H,
    seek: (k) => { playing = false; seek(k); },
    time: (k) => D.t[k], clogFlags: (k) => D.flags[k], arch: (k) => Array.from(D.arch.subarray(D.archStart[k], D.archStart[k + 1])),
    position: (k, i) => [px(k, i), py(k, i)],
    // Where grain i's centre is drawn in the page (CSS pixels from the viewport's corner), in the view named,
    // and its radius there.
    grainOnPage: (i, name) => {
      const v = views.find((w) => w.name === (name || views[views.length - 1].name));
      const [X, Y] = toPixels(camOf(v), px(frame, i), py(frame, i)), b = canvas.getBoundingClientRect(), dpr = window.devicePixelRatio || 1;
      return [b.left + X / dpr, b.top + Y / dpr, D.radius[i] * extent(D.sides[i]) * camOf(v).s / dpr];
    },
    setView, pickedText: () => grainBox.textContent, infoText: () => info.textContent,
  }));
  (window.siloscopeViewers = window.siloscopeViewers || []).push(api);
  const started = performance.now();
  decode().then((d) => {
    D = d;
    status.remove();
    resize();  // the cameras laid out (the ResizeObserver may not have run yet), then the first frame
    seek(0);
    api.loadMs = performance.now() - started;
    api.sinceNavigationMs = performance.now();
    api.ready = true;
  }).catch((err) => {
    api.error = String(err && err.message ? err.message : err);
    status.textContent = "this page cannot show its run: " + api.error +
      (typeof DecompressionStream === "undefined" ? " (this browser has no DecompressionStream: use a current Chrome, Firefox or Safari)" : "");
  });
})();
