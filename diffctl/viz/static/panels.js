// diffctl viz side panels: displays, teleop (keys, joystick, game pad), message publisher, camera, tables.
"use strict";
(() => {
  const V = window.diffviz;
  const $ = (id) => document.getElementById(id);
  const fmt = (v, n = 3) => (v == null ? "—" : Number(v).toFixed(n));

  function fillTable(id, rows) {
    const body = $(id).tBodies[0];
    body.replaceChildren();
    for (const row of rows) {
      const tr = document.createElement("tr");
      for (const cell of row) {
        const td = document.createElement("td");
        if (typeof cell === "object" && cell !== null) {
          td.textContent = cell.text; if (cell.cls) td.className = cell.cls;
        } else {
          td.textContent = cell;
          if (typeof cell === "number" || /^-?[\d.]+$/.test(String(cell))) td.className = "num";
        }
        tr.append(td);
      }
      body.append(tr);
    }
  }

  // ---------------------------------------------------------------- displays
  V.on("hello", (m) => {
    const box = $("displays");
    box.replaceChildren();
    for (const d of m.config.displays) {
      const label = document.createElement("label");
      label.className = "disp";
      const cb = document.createElement("input");
      cb.type = "checkbox"; cb.checked = d.enabled && !V.hidden.has(d.name);
      cb.addEventListener("change", () => { cb.checked ? V.hidden.delete(d.name) : V.hidden.add(d.name); V.dirty = true; });
      d.enabled = true;  // the checkbox now decides; a display disabled in the file starts unchecked
      if (!cb.checked) V.hidden.add(d.name);
      const sw = document.createElement("span");
      sw.className = "swatch"; if (d.color) sw.style.background = d.color;
      label.append(cb, sw, document.createTextNode(`${d.name}${d.topic ? " — " + d.topic : ""}`));
      box.append(label);
    }
    $("ignored").textContent = m.config.ignored.length ? "not shown: " + m.config.ignored.join(", ") : "";
    const cams = m.config.displays.filter(d => d.kind === "image" && d.topic);
    const sel = $("camera-topic");
    sel.replaceChildren();
    for (const d of cams) sel.add(new Option(d.topic, d.topic));
    if (!cams.length) sel.add(new Option("/camera/image_raw", "/camera/image_raw"));
    const types = $("type-list");
    types.replaceChildren();
    for (const t of m.types) types.append(new Option(t));
    setupTeleop(m.teleop);
    if ($("panel-camera").open) V.send({ op: "image", topic: sel.value });
  });

  // ---------------------------------------------------------------- joint sliders (joint_state_publisher_gui)
  const SLIDER_TOPIC = "/joint_sliders";
  let sliderTimer = null;
  function sliderValues() {
    const inputs = Array.from(document.querySelectorAll("#sliders input"));
    // rounded to 1e-6: the body is read as YAML, where an exponent without a dot ("5e-16") is a string
    return { name: inputs.map(i => i.dataset.joint), position: inputs.map(i => Math.round(Number(i.value) * 1e6) / 1e6) };
  }
  function sendSliders() {
    sliderTimer = null;
    const v = sliderValues();
    if (!v.name.length) return;
    V.send({ op: "publish", id: "sliders", topic: SLIDER_TOPIC, type: "sensor_msgs/msg/JointState",
             body: JSON.stringify({ header: "auto", name: v.name, position: v.position }), rate: 0 });
  }
  function slidersChanged() { if (!sliderTimer) sliderTimer = setTimeout(sendSliders, 100); }
  V.on("robot", (m) => {
    const box = $("sliders");
    const joints = m.joints || [];
    const have = Array.from(box.querySelectorAll("input")).map(i => i.dataset.joint).join(",");
    if (have === joints.map(j => j.name).join(",")) return;
    box.replaceChildren();
    for (const j of joints) {
      const row = document.createElement("div");
      row.className = "row";
      const label = document.createElement("label");
      const input = document.createElement("input");
      const value = document.createElement("span");
      input.type = "range"; input.min = j.lower; input.max = j.upper; input.step = (j.upper - j.lower) / 1000;
      input.value = Math.min(Math.max(0, j.lower), j.upper);  // as the GUI starts: 0 within the limits
      input.dataset.joint = j.name; input.dataset.center = input.value;
      value.textContent = Number(input.value).toFixed(3);
      input.addEventListener("input", () => { value.textContent = Number(input.value).toFixed(3); slidersChanged(); });
      label.append(j.name + " ", input, " ", value);
      row.append(label);
      box.append(row);
    }
  });
  $("sliders-center").addEventListener("click", () => {
    for (const i of document.querySelectorAll("#sliders input")) {
      i.value = i.dataset.center;
      i.dispatchEvent(new Event("input"));
    }
  });
  V.on("error", (m) => { if (m.op === "publish" && m.id === "sliders") $("sliders-status").textContent = m.text; });

  // ---------------------------------------------------------------- tables
  V.on("status", (m) => {
    if (!$("panel-joints").open) return;
    fillTable("joints", m.joints.map(j => [j.name, fmt(j.position), fmt(j.velocity), fmt(j.effort)]));
  });
  V.on("graph", (m) => {
    const list = $("topic-list");
    const names = m.topics.map(t => t.name);
    if (list.options.length !== names.length) { list.replaceChildren(); for (const n of names) list.append(new Option(n)); }
    V.topicTypes = Object.fromEntries(m.topics.map(t => [t.name, t.types]));
    if ($("panel-topics").open) {
      fillTable("topics", m.topics.map(t => [t.name, { text: t.types.join(", "), cls: t.types.length > 1 ? "err" : "" },
        t.publishers, t.subscribers, t.hz == null ? "—" : t.hz.toFixed(1)]));
    }
    teleopTopics(m.topics);
    teleopTopicInfo(m.topics);
    const ctl = m.controllers;
    $("controllers-none").hidden = !!ctl;
    fillTable("controllers", (ctl || []).map(c => [c.name, c.type, { text: c.state, cls: "state-" + c.state }]));
  });
  V.on("frame", (m) => {
    if (!$("panel-tf").open) return;
    fillTable("tf", Object.entries(m.frames).sort().map(([n, t]) =>
      [n, m.parents[n] || "", fmt(t[0]), fmt(t[1]), fmt(t[3] * 180 / Math.PI, 1)]));
  });

  // ---------------------------------------------------------------- camera (subscribed only while open)
  $("panel-camera").addEventListener("toggle", () => {
    V.send({ op: "image", topic: $("panel-camera").open ? $("camera-topic").value : null });
  });
  $("camera-topic").addEventListener("change", () => { if ($("panel-camera").open) V.send({ op: "image", topic: $("camera-topic").value }); });
  V.on("image", (m) => {
    if (m.error) { $("camera-info").textContent = m.error; return; }
    $("camera-img").src = m.url;
    $("camera-info").textContent = `${m.topic} ${m.width}×${m.height} (${m.encoding})`;
  });

  // ---------------------------------------------------------------- teleop
  // A command is sent on every change and repeated at 10 Hz while non-zero; releasing sends one zero.
  const T = V.teleop = { linear: 0, angular: 0, keys: new Set(), joy: null, pad: null, sent: 0, zeroSent: true, timer: null };
  const KEYS = { ArrowUp: [1, 0], KeyW: [1, 0], ArrowDown: [-1, 0], KeyS: [-1, 0],
                 ArrowLeft: [0, 1], KeyA: [0, 1], ArrowRight: [0, -1], KeyD: [0, -1] };

  // Who listens on the teleop topic, and with which type; with nobody there, offer a topic that has a
  // velocity subscriber (the earlier tutorial variant drives /cmd_vel with an unstamped Twist).
  const TWIST = "geometry_msgs/msg/Twist", STAMPED = "geometry_msgs/msg/TwistStamped";
  function teleopTopicInfo(topics) {
    const box = $("teleop-topic-info");
    const name = $("teleop-topic").value.trim();
    const info = topics.find(t => t.name === name);
    box.replaceChildren();
    if (info && info.subscribers > 0) {
      const want = $("teleop-stamped").checked ? STAMPED : TWIST;
      const ok = info.types.includes(want);
      box.textContent = `${info.subscribers} subscriber(s), ${info.types.join(", ")}` + (ok ? "" : ` — not ${want}!`);
      box.className = "row " + (ok ? "dim" : "err");
      return;
    }
    box.className = "row err";
    box.textContent = `nobody subscribes to ${name || "(no topic)"}`;
    const alt = topics.find(t => t.subscribers > 0 && t.name !== name && t.types.some(ty => ty === TWIST || ty === STAMPED));
    if (alt) {
      const b = document.createElement("button");
      b.textContent = `use ${alt.name}`;
      b.onclick = () => {
        stopAll();
        $("teleop-topic").value = alt.name;
        $("teleop-stamped").checked = alt.types.includes(STAMPED);
        teleopTopicInfo(topics);
      };
      box.append(" ", b);
    }
  }

  // Several robots (a fleet: /robot1/…/cmd_vel, /robot2/…/cmd_vel): every velocity topic someone subscribes
  // to is offered by its robot's namespace; picking one drives that robot alone.
  function teleopTopics(topics) {
    const sel = $("teleop-robot");
    const cmds = topics.filter(t => t.subscribers > 0 && t.types.some(ty => ty === TWIST || ty === STAMPED));
    const names = cmds.map(t => t.name);
    $("teleop-robot-row").hidden = cmds.length < 2;
    if ([...sel.options].map(o => o.value).join() === names.join()) {
      sel.value = $("teleop-topic").value.trim();
      return;
    }
    sel.replaceChildren();
    for (const t of cmds) {
      const ns = t.name.split("/").filter(Boolean);
      sel.add(new Option(ns.length > 2 ? `${ns[0]} — ${t.name}` : t.name, t.name));
    }
    sel.value = $("teleop-topic").value.trim();
    sel.onchange = () => {
      stopAll();
      const t = cmds.find(c => c.name === sel.value);
      $("teleop-topic").value = sel.value;
      if (t) $("teleop-stamped").checked = t.types.includes(STAMPED);
      teleopTopicInfo(topics);
    };
  }

  function setupTeleop(t) {
    $("teleop-topic").value = t.topic;
    $("teleop-stamped").checked = t.stamped;
    for (const [id, max, def] of [["max-lin", t.max_linear, 0.5], ["max-ang", t.max_angular, 1.0]]) {
      const r = $(id);
      r.max = max; r.value = Math.min(def, max);
      $(id + "-out").textContent = Number(r.value).toFixed(2);
      r.oninput = () => { $(id + "-out").textContent = Number(r.value).toFixed(2); update(); };
    }
  }

  function command() {
    const lin = Number($("max-lin").value), ang = Number($("max-ang").value);
    if (T.joy) return [T.joy[0] * lin, T.joy[1] * ang];
    if (T.pad) return [T.pad[0] * lin, T.pad[1] * ang];
    let l = 0, a = 0;
    for (const k of T.keys) { l += KEYS[k][0]; a += KEYS[k][1]; }
    return [Math.max(-1, Math.min(1, l)) * lin, Math.max(-1, Math.min(1, a)) * ang];
  }

  function transmit() {
    const msg = { op: "teleop", topic: $("teleop-topic").value.trim(), stamped: $("teleop-stamped").checked,
                  linear: T.linear, angular: T.angular };
    if (V.send(msg)) T.sent++;
  }

  function update() {
    const [l, a] = command();
    const changed = l !== T.linear || a !== T.angular;
    T.linear = l; T.angular = a;
    $("teleop-cmd").textContent = `${l.toFixed(2)} m/s, ${a.toFixed(2)} rad/s`;
    const moving = l !== 0 || a !== 0;
    if (moving) {
      if (changed) transmit();
      T.zeroSent = false;
      if (!T.timer) T.timer = setInterval(transmit, 100);
    } else {
      if (T.timer) { clearInterval(T.timer); T.timer = null; }
      if (!T.zeroSent) { transmit(); T.zeroSent = true; }
    }
    drawJoystick();
  }
  V.teleopUpdate = update;

  function stopAll() { T.keys.clear(); T.joy = null; T.pad = null; update(); }

  const typing = (e) => e.target && (e.target.tagName === "INPUT" || e.target.tagName === "TEXTAREA" || e.target.tagName === "SELECT");
  document.addEventListener("keydown", (e) => {
    if (typing(e) || e.ctrlKey || e.metaKey || e.altKey) return;
    if (e.code === "Space") { e.preventDefault(); stopAll(); return; }
    if (!(e.code in KEYS)) return;
    e.preventDefault();
    if (!T.keys.has(e.code)) { T.keys.add(e.code); update(); }
  });
  document.addEventListener("keyup", (e) => { if (T.keys.delete(e.code)) update(); });
  window.addEventListener("blur", stopAll);
  document.addEventListener("visibilitychange", () => { if (document.hidden) stopAll(); });

  // on-screen joystick: drag inside the circle; up = forward, left = turn left
  const joy = $("joystick");
  const jctx = joy.getContext("2d");
  function drawJoystick() {
    const r = joy.width / 2;
    jctx.clearRect(0, 0, joy.width, joy.height);
    jctx.fillStyle = "#15171a"; jctx.strokeStyle = "#4da3ff"; jctx.lineWidth = 2;
    jctx.beginPath(); jctx.arc(r, r, r - 2, 0, 2 * Math.PI); jctx.fill(); jctx.stroke();
    const lin = Number($("max-lin").value) || 1, ang = Number($("max-ang").value) || 1;
    const kx = -(T.angular / ang) * (r - 20), ky = -(T.linear / lin) * (r - 20);
    jctx.fillStyle = T.linear || T.angular ? "#4da3ff" : "#555";
    jctx.beginPath(); jctx.arc(r + kx, r + ky, 16, 0, 2 * Math.PI); jctx.fill();
  }
  function joyAt(e) {
    const b = joy.getBoundingClientRect(), r = b.width / 2;
    let dx = (e.clientX - b.left - r) / (r - 20), dy = (e.clientY - b.top - r) / (r - 20);
    const n = Math.hypot(dx, dy);
    if (n > 1) { dx /= n; dy /= n; }
    T.joy = [-dy, -dx];
    update();
  }
  joy.addEventListener("pointerdown", (e) => { joy.setPointerCapture(e.pointerId); joyAt(e); });
  joy.addEventListener("pointermove", (e) => { if (T.joy) joyAt(e); });
  for (const ev of ["pointerup", "pointercancel", "lostpointercapture"]) joy.addEventListener(ev, () => { if (T.joy) { T.joy = null; update(); } });

  // game pad (browser Gamepad API, standard mapping): left stick, dead zone 0.15
  const DEAD = 0.15;
  const dz = (v) => (Math.abs(v) < DEAD ? 0 : (v - Math.sign(v) * DEAD) / (1 - DEAD));
  function pollPad() {
    const pads = navigator.getGamepads ? Array.from(navigator.getGamepads()).filter(Boolean) : [];
    const pad = pads[0];
    $("gamepad").textContent = pad ? `game pad: ${pad.id.slice(0, 40)}` : "no game pad";
    if (pad) {
      const v = [-dz(pad.axes[1] || 0), -dz(pad.axes[0] || 0)];
      const active = v[0] !== 0 || v[1] !== 0;
      if (active) { T.pad = v; update(); } else if (T.pad) { T.pad = null; update(); }
    }
    requestAnimationFrame(pollPad);
  }
  requestAnimationFrame(pollPad);
  drawJoystick();

  // ---------------------------------------------------------------- message publisher (rqt's Message Publisher)
  const pubStatus = (text, err = false) => { $("pub-status").textContent = text; $("pub-status").className = err ? "err" : "dim"; };
  // Picking a topic the graph knows fills in its type (while the type is still empty), as rqt does.
  $("pub-topic").addEventListener("input", () => {
    const known = (V.topicTypes || {})[$("pub-topic").value.trim()];
    if (known && known.length && !$("pub-type").value) $("pub-type").value = known[0];
  });
  $("pub-template").addEventListener("click", () => V.send({ op: "template", type: $("pub-type").value.trim() }));
  $("pub-send").addEventListener("click", () => {
    V.send({ op: "publish", id: "panel", topic: $("pub-topic").value.trim(), type: $("pub-type").value.trim(),
             body: $("pub-body").value, rate: Number($("pub-rate").value) || 0 });
  });
  $("pub-stop").addEventListener("click", () => V.send({ op: "publish_stop", id: "panel" }));
  V.on("publish_state", (m) => pubStatus(m.text || (m.running ? "publishing" : "stopped")));
  V.on("template", (m) => { $("pub-body").value = m.yaml; pubStatus(`fields of ${m.type_name}`); });
  V.on("error", (m) => { if (m.op === "publish" || m.op === "template") pubStatus(m.text, true); });
  V.on("refused", (m) => { if (m.op === "publish") pubStatus(m.text, true); });
})();
