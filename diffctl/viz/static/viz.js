// diffctl viz: connection to the visualizer process and the top-down view (grid, robot, TF, odometry, scan).
// No libraries: Canvas 2D and a WebSocket. Everything the tests and panels need lives on window.diffviz.
"use strict";
(() => {
  const token = new URLSearchParams(location.search).get("token") || "";
  const V = window.diffviz = {
    connected: false, authorized: false, hello: null, config: null, fixed: "odom",
    robot: null, frame: null, scans: {}, paths: {}, status: null, graph: null,
    hidden: new Set(),          // display names switched off in this page
    stats: { messages: 0, frames: 0, draws: 0, robotPolygonsDrawn: 0, scanPointsDrawn: 0, pathPointsDrawn: 0 },
    notices: [], refused: [],
    handlers: {},
    ws: null,
    on(type, fn) { (this.handlers[type] = this.handlers[type] || []).push(fn); },
    send(obj) {
      if (this.ws && this.ws.readyState === WebSocket.OPEN) { this.ws.send(JSON.stringify(obj)); return true; }
      return false;
    },
    notice(text, level = "info", sticky = false) {
      this.notices.push({ text, level });
      const box = document.getElementById("notices");
      if (Array.from(box.children).some(c => c.textContent === text)) return;  // once on screen is enough
      const el = document.createElement("div");
      el.className = "notice " + level;
      el.textContent = text;
      box.appendChild(el);
      while (box.children.length > 4) box.removeChild(box.firstChild);
      if (!sticky) setTimeout(() => el.remove(), 5000);
    },
    shown(d) { return d && d.enabled && !this.hidden.has(d.name); },
    displays(kind) { return (this.config ? this.config.displays : []).filter(d => d.kind === kind); },
    dirty: true,
  };

  // ---------------------------------------------------------------- connection
  function connect() {
    const proto = location.protocol === "https:" ? "wss" : "ws";
    const ws = new WebSocket(`${proto}://${location.host}/ws` + (token ? `?token=${encodeURIComponent(token)}` : ""));
    V.ws = ws;
    ws.onopen = () => { V.connected = true; setConn(); };
    ws.onclose = () => { V.connected = false; setConn(); setTimeout(connect, 1000); };
    ws.onmessage = (ev) => {
      let msg;
      try { msg = JSON.parse(ev.data); } catch (e) { return; }
      V.stats.messages++;
      const fn = builtin[msg.type];
      if (fn) fn(msg);
      for (const h of V.handlers[msg.type] || []) h(msg);
      V.dirty = true;
    };
  }

  function setConn() {
    const el = document.getElementById("conn");
    el.textContent = V.connected ? "connected" : "disconnected";
    el.className = "pill " + (V.connected ? "on" : "off");
  }

  function setAuth() {
    const el = document.getElementById("auth");
    el.textContent = V.authorized ? "can drive" : "view only";
    el.className = "pill " + (V.authorized ? "on" : "off");
    el.title = V.authorized ? "this page holds the token: teleop and publishing work"
      : "open the URL printed by `diffctl viz` (it carries ?token=…) to drive";
    document.getElementById("auth-form").hidden = V.authorized;
  }

  const builtin = {
    hello(m) {
      V.hello = m; V.config = m.config; V.authorized = m.authorized; V.fixed = m.fixed_frame;
      V.scans = {}; V.paths = {};
      document.body.style.setProperty("--bg", m.config.background);
      setAuth();
      setFixedOptions([]);
      if (!token) V.notice("view only: open the URL with ?token=… printed by `diffctl viz` to drive", "warn");
    },
    auth(m) { V.authorized = m.authorized; setAuth(); if (m.text) { V.refused.push(m.text); V.notice(m.text, "refused", true); } },
    robot(m) {
      V.robot = m;
      const name = document.getElementById("robot-name");
      name.textContent = m.name ? `robot ${m.name}` : "";
      name.title = m.skipped.length ? "not drawn (no outline): " + m.skipped.join(", ") : "";
      if (m.error) V.notice(m.error, "error", true);
    },
    frame(m) {
      V.frame = m; V.stats.frames++;
      const el = document.getElementById("fixed-missing");
      el.hidden = m.fixed_known;
      el.textContent = `Fixed Frame [${m.fixed}] does not exist`;
    },
    scan(m) { V.scans = m.scans; },
    paths(m) { V.paths = m.paths; },
    status(m) {
      V.status = m;
      document.getElementById("sim-time").textContent = m.sim_time == null ? "—" : m.sim_time.toFixed(2) + " s";
      document.getElementById("rtf").textContent = m.rtf == null ? "—" : m.rtf.toFixed(2) + "×";
      const sim = m.sim || {};
      document.getElementById("rtf").title = (m.rtf_source ? `from ${m.rtf_source}` : "")
        + (sim.step_time_us != null ? `, ${sim.step_time_us.toFixed(1)} µs/step` : "")
        + (sim.iterations != null ? `, ${sim.iterations} iterations` : "");
      const state = document.getElementById("sim-state");
      const parts = [];
      if (sim.paused) parts.push("paused");
      if (sim.lockstep_overruns) parts.push(`${sim.lockstep_overruns} lockstep overruns`);
      state.hidden = !parts.length;
      state.textContent = parts.join(", ");
    },
    graph(m) { V.graph = m; setFixedOptions(m.frames || []); },
    refused(m) { V.refused.push(m.text); V.notice(m.text, "refused", true); },
    notice(m) { V.notice(m.text, m.level || "info"); },
    error(m) { if (m.op !== "publish" && m.op !== "template") V.notice(m.text, "error"); },
  };

  function setFixedOptions(frames) {
    const sel = document.getElementById("fixed-frame");
    const names = Array.from(new Set([V.fixed, ...frames])).sort();
    if (sel.options.length === names.length && Array.from(sel.options).every((o, i) => o.value === names[i])) return;
    sel.innerHTML = "";
    for (const n of names) sel.add(new Option(n, n, false, n === V.fixed));
  }
  document.getElementById("fixed-frame").addEventListener("change", (e) => {
    V.fixed = e.target.value; V.scans = {}; V.paths = {}; V.frame = null;
    V.send({ op: "fixed_frame", frame: V.fixed });
  });
  document.getElementById("token-send").addEventListener("click", () => {
    V.send({ op: "auth", token: document.getElementById("token-input").value.trim() });
  });

  // ---------------------------------------------------------------- view: pan, zoom, follow
  const canvas = document.getElementById("canvas");
  const ctx = canvas.getContext("2d");
  const view = { cx: 0, cy: 0, scale: 80 };  // centre in fixed-frame metres, pixels per metre
  V.view = view;
  let drag = null;

  function resize() {
    const dpr = window.devicePixelRatio || 1;
    canvas.width = Math.max(1, Math.round(canvas.clientWidth * dpr));
    canvas.height = Math.max(1, Math.round(canvas.clientHeight * dpr));
    V.dirty = true;
  }
  window.addEventListener("resize", resize);
  const W = () => canvas.width, H = () => canvas.height;
  const sx = (x) => W() / 2 + (x - view.cx) * view.scale;
  const sy = (y) => H() / 2 - (y - view.cy) * view.scale;
  V.toScreen = (x, y) => [sx(x) / (window.devicePixelRatio || 1), sy(y) / (window.devicePixelRatio || 1)];

  canvas.addEventListener("pointerdown", (e) => { drag = { x: e.clientX, y: e.clientY, cx: view.cx, cy: view.cy }; canvas.focus(); });
  window.addEventListener("pointerup", () => { drag = null; });
  window.addEventListener("pointermove", (e) => {
    if (!drag) return;
    const dpr = window.devicePixelRatio || 1;
    view.cx = drag.cx - (e.clientX - drag.x) * dpr / view.scale;
    view.cy = drag.cy + (e.clientY - drag.y) * dpr / view.scale;
    document.getElementById("follow").checked = false;
    V.dirty = true;
  });
  canvas.addEventListener("wheel", (e) => {
    e.preventDefault();
    const dpr = window.devicePixelRatio || 1;
    const r = canvas.getBoundingClientRect();
    const px = (e.clientX - r.left) * dpr, py = (e.clientY - r.top) * dpr;
    const wx = view.cx + (px - W() / 2) / view.scale, wy = view.cy - (py - H() / 2) / view.scale;
    view.scale = Math.min(5000, Math.max(2, view.scale * Math.exp(-e.deltaY * 0.0015)));
    view.cx = wx - (px - W() / 2) / view.scale;
    view.cy = wy + (py - H() / 2) / view.scale;
    V.dirty = true;
  }, { passive: false });
  const resetView = () => { view.cx = 0; view.cy = 0; view.scale = Math.min(W(), H()) / 5; V.dirty = true; };
  canvas.addEventListener("dblclick", resetView);
  document.getElementById("reset-view").addEventListener("click", resetView);

  // ---------------------------------------------------------------- drawing
  function poly(pts) {
    ctx.beginPath();
    for (let i = 0; i < pts.length; i += 2) (i ? ctx.lineTo : ctx.moveTo).call(ctx, sx(pts[i]), sy(pts[i + 1]));
    ctx.closePath();
  }

  function arrow(x, y, yaw, len, color, width = 2) {
    const hx = x + Math.cos(yaw) * len, hy = y + Math.sin(yaw) * len;
    ctx.strokeStyle = color; ctx.fillStyle = color; ctx.lineWidth = width;
    ctx.beginPath(); ctx.moveTo(sx(x), sy(y)); ctx.lineTo(sx(hx), sy(hy)); ctx.stroke();
    const h = Math.max(6, len * view.scale * 0.3);
    ctx.beginPath();
    ctx.moveTo(sx(hx), sy(hy));
    ctx.lineTo(sx(hx) - h * Math.cos(yaw - 0.4), sy(hy) + h * Math.sin(yaw - 0.4));
    ctx.lineTo(sx(hx) - h * Math.cos(yaw + 0.4), sy(hy) + h * Math.sin(yaw + 0.4));
    ctx.closePath(); ctx.fill();
  }

  function drawGrid(d) {
    const n = d.cell_count, c = d.cell_size, half = n * c / 2;
    ctx.strokeStyle = d.color || "#a0a0a4"; ctx.globalAlpha = 0.5; ctx.lineWidth = 1;
    ctx.beginPath();
    for (let i = 0; i <= n; i++) {
      const v = -half + i * c;
      ctx.moveTo(sx(v), sy(-half)); ctx.lineTo(sx(v), sy(half));
      ctx.moveTo(sx(-half), sy(v)); ctx.lineTo(sx(half), sy(v));
    }
    ctx.stroke(); ctx.globalAlpha = 1;
  }

  function drawAxes(x, y, yaw, len, name) {
    const dpr = window.devicePixelRatio || 1;
    ctx.lineWidth = 2 * dpr;
    ctx.strokeStyle = "#ff3b30"; ctx.beginPath(); ctx.moveTo(sx(x), sy(y));
    ctx.lineTo(sx(x + Math.cos(yaw) * len), sy(y + Math.sin(yaw) * len)); ctx.stroke();
    ctx.strokeStyle = "#34c759"; ctx.beginPath(); ctx.moveTo(sx(x), sy(y));
    ctx.lineTo(sx(x - Math.sin(yaw) * len), sy(y + Math.cos(yaw) * len)); ctx.stroke();
    if (name) {
      ctx.fillStyle = "#e6e6e6"; ctx.font = `${11 * dpr}px sans-serif`;
      ctx.fillText(name, sx(x) + 4 * dpr, sy(y) - 4 * dpr);
    }
  }

  function draw() {
    const dpr = window.devicePixelRatio || 1;
    const st = V.stats;
    ctx.fillStyle = (V.config && V.config.background) || "#303030";
    ctx.fillRect(0, 0, W(), H());
    if (!V.config) return;
    const f = V.frame;
    if (document.getElementById("follow").checked && f) {
      const base = f.odom.find(o => o.pose);
      if (base) { view.cx = base.pose[0]; view.cy = base.pose[1]; }
    }
    for (const d of V.displays("grid")) if (V.shown(d)) drawGrid(d);
    // odometry trails (RViz's Odometry arrows, kept `Keep` deep)
    st.pathPointsDrawn = 0;
    for (const d of V.displays("odometry")) {
      const pts = V.paths[d.topic];
      if (!V.shown(d) || !pts) continue;
      ctx.strokeStyle = d.color || "#ff1900"; ctx.lineWidth = 1.5 * dpr; ctx.globalAlpha = 0.8;
      ctx.beginPath();
      for (let i = 0; i < pts.length; i += 3) (i ? ctx.lineTo : ctx.moveTo).call(ctx, sx(pts[i]), sy(pts[i + 1]));
      ctx.stroke(); ctx.globalAlpha = 1;
      const step = Math.max(3, 3 * Math.floor(pts.length / 3 / 60));
      for (let i = 0; i < pts.length; i += step) arrow(pts[i], pts[i + 1], pts[i + 2], 0.12, d.color || "#ff1900", dpr);
      st.pathPointsDrawn += pts.length / 3;
    }
    if (f && f.gt) {   // ground truth from the simulator, Gazebo's view of where the robot really is
      ctx.setLineDash([6 * dpr, 4 * dpr]);
      arrow(f.gt[0], f.gt[1], f.gt[2], 0.35, "#37d67a", 2 * dpr);
      ctx.setLineDash([]);
    }
    st.scanPointsDrawn = 0;
    for (const d of V.displays("laser_scan")) {
      const s = V.scans[d.topic];
      if (!V.shown(d) || !s || !s.ok) continue;
      const size = Math.max(2 * dpr, d.point_size * view.scale);
      ctx.fillStyle = d.color || "#ff0000";
      for (let i = 0; i < s.pts.length; i += 2) ctx.fillRect(sx(s.pts[i]) - size / 2, sy(s.pts[i + 1]) - size / 2, size, size);
      st.scanPointsDrawn += s.pts.length / 2;
    }
    st.robotPolygonsDrawn = 0;
    const rm = V.displays("robot_model")[0];
    if (f && f.robot && (!rm || V.shown(rm))) {
      for (const p of f.robot) {
        poly(p.pts); ctx.fillStyle = p.color; ctx.fill();
        ctx.strokeStyle = "#000000aa"; ctx.lineWidth = dpr; ctx.stroke();
        st.robotPolygonsDrawn++;
      }
    }
    const tfd = V.displays("tf")[0];
    if (f && tfd && V.shown(tfd)) {
      const len = Math.max(0.1 * tfd.marker_scale, 14 * dpr / view.scale);
      const labels = [];
      for (const [name, t] of Object.entries(f.frames)) {
        // A name is written only where it does not overprint another one (frames of a small robot crowd).
        const free = tfd.show_names && labels.every(([lx, ly]) => Math.abs(lx - sx(t[0])) > 70 * dpr || Math.abs(ly - sy(t[1])) > 14 * dpr);
        if (free) labels.push([sx(t[0]), sy(t[1])]);
        drawAxes(t[0], t[1], t[3], len, free ? name : "");
      }
    }
    for (const d of V.displays("odometry")) {
      const o = f && f.odom.find(e => e.topic === d.topic);
      if (V.shown(d) && o && o.pose) arrow(o.pose[0], o.pose[1], o.pose[2], 0.3, d.color || "#ff1900", 3 * dpr);
    }
    drawScaleBar(dpr);
    st.draws++;
  }

  function drawScaleBar(dpr) {
    const target = 120 * dpr / view.scale;
    const p = Math.pow(10, Math.floor(Math.log10(target)));
    const m = [1, 2, 5, 10].map(k => k * p).filter(v => v <= target).pop() || p;
    const x0 = W() - 20 * dpr - m * view.scale, y0 = H() - 20 * dpr;
    ctx.strokeStyle = "#e6e6e6"; ctx.lineWidth = 2 * dpr;
    ctx.beginPath(); ctx.moveTo(x0, y0); ctx.lineTo(x0 + m * view.scale, y0); ctx.stroke();
    ctx.fillStyle = "#e6e6e6"; ctx.font = `${11 * dpr}px sans-serif`;
    ctx.fillText(`${m >= 1 ? m : m.toFixed(2)} m`, x0, y0 - 6 * dpr);
  }

  let legendKey = "";
  function legend() {
    const items = [];
    for (const d of V.config ? V.config.displays : []) {
      if (d.color && d.kind !== "grid" && V.shown(d)) items.push([d.color, d.name + (d.topic ? " " + d.topic : "")]);
    }
    if (V.frame && V.frame.gt) items.push(["#37d67a", "ground truth"]);
    const key = JSON.stringify(items);
    if (key === legendKey) return;
    legendKey = key;
    const el = document.getElementById("legend");
    el.replaceChildren();
    for (const [color, text] of items) {
      const sw = document.createElement("span");
      sw.style.background = color;
      el.append(sw, document.createTextNode(text));
    }
  }

  function loop() {
    if (V.dirty) { V.dirty = false; draw(); legend(); }
    requestAnimationFrame(loop);
  }

  resize();
  resetView();
  setConn();
  setAuth();
  connect();
  requestAnimationFrame(loop);
})();
