// vdrive dashboard. Plain script, no build step: the page talks to the JSON API of
// /api/v1/openapi.json and takes live data from the server-sent event stream /api/v1/stream.
'use strict';

(() => {
  const API = '/api/v1';
  const EVENT_KINDS = ['al_state', 'alarm_raised', 'alarm_cleared', 'fault_injected', 'fault_cleared', 'fault_refused',
    'plant_set', 'signal', 'host_stall', 'od_write', 'od_abort', 'sdo_abort', 'scenario', 'part_silent', 'part_answers'];
  const TEXT_TYPES = /^(VS|US|VISIBLE_STRING|UNICODE_STRING)$/i;   // written as text; everything else as a number or hex
  const MAX_EVENTS = 2000;           // what the server keeps, so a reload shows the same log
  const MAX_ROWS = 400;              // rows in the table: an alarm storm on 64 drives must not lay out thousands
  const KEEP_S = 21;                 // samples kept per axis: the longest plot window plus a margin
  const POLL_MS = 50;                // fallback polling when the stream cannot be used: 20 Hz

  const $ = (sel, root = document) => root.querySelector(sel);
  const $$ = (sel, root = document) => Array.from(root.querySelectorAll(sel));

  const st = {
    token: null,
    tokenRequired: false,
    layout: '',                      // the slaves' positions and products: a change rebuilds the page
    slaves: [],
    boxes: new Map(),                // position -> network box
    axes: new Map(),                 // position -> Axis (slaves with a drive)
    selected: 0,
    sampleSeq: 0,
    eventSeq: 0,
    events: [],
    latestT: 0,
    windowS: 10,
    paused: false,
    faultKinds: [],
    updates: 0,
    drawPending: false,
  };

  // ---------------------------------------------------------------- helpers

  // Writes only when the text changes: with 64 drives at 25 updates a second most values stay the same, and
  // untouched nodes cost the browser no layout.
  function setText(el, text) {
    text = String(text);
    if (el.__t !== text) { el.__t = text; el.textContent = text; }
  }
  function setAttr(el, name, value) {
    value = String(value);
    if (el.getAttribute(name) !== value) el.setAttribute(name, value);
  }
  function el(tag, props = {}, ...children) {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(props)) {
      if (k === 'class') e.className = v;
      else if (k === 'text') e.textContent = v;
      else if (k.startsWith('data-') || k === 'title' || k === 'type' || k === 'placeholder' || k === 'value' || k === 'list' || k === 'id') e.setAttribute(k, v);
      else e[k] = v;
    }
    for (const c of children) if (c != null) e.append(c);
    return e;
  }
  // A panel's parts, looked up once: 64 drives x 25 updates a second would otherwise search the
  // DOM thousands of times a second.
  function part(root, sel) {
    const cache = root.__parts || (root.__parts = {});
    return cache[sel] || (cache[sel] = root.querySelector(sel));
  }
  const hex = (v, digits = 4) => '0x' + (Number(v) >>> 0).toString(16).toUpperCase().padStart(digits, '0');
  const idx = (i, s) => (Number(i) >>> 0).toString(16).toUpperCase().padStart(4, '0') + 'h:' + (Number(s) >>> 0).toString(16).toUpperCase().padStart(2, '0');
  // An alarm's code as the product prints it; a 603Fh value the alarm table lacks shows as hex.
  const alarmCode = a => a.code || hex(a.error_code);
  const secs = ns => (Number(ns) / 1e9).toFixed(3);
  function duration(ns) {
    if (ns == null || ns < 0) return 'until cleared';
    if (ns < 1e6) return (ns / 1e3).toFixed(0) + ' µs';
    if (ns < 1e9) return (ns / 1e6).toFixed(0) + ' ms';
    return (ns / 1e9).toFixed(1) + ' s';
  }
  function compact(v) {
    const a = Math.abs(v);
    if (a >= 1e9) return (v / 1e9).toFixed(a >= 1e10 ? 0 : 1) + 'G';
    if (a >= 1e6) return (v / 1e6).toFixed(a >= 1e7 ? 0 : 1) + 'M';
    if (a >= 1e4) return (v / 1e3).toFixed(0) + 'k';
    return Number.isInteger(v) ? String(v) : v.toPrecision(3);
  }

  // ---------------------------------------------------------------- API

  function loadToken() {
    const m = /(?:^#|&)token=([^&]+)/.exec(location.hash);
    if (m) {
      sessionStorage.setItem('vdrive.token', decodeURIComponent(m[1]));
      // Out of the address bar, so it is not bookmarked, shared or seen in a screenshot.
      history.replaceState(null, '', location.pathname + location.search);
    }
    return sessionStorage.getItem('vdrive.token');
  }

  // Every request goes through here: mutating ones carry the JSON content type the server
  // insists on and the token when the page has one. Resolves to {ok, status, data}; data is the
  // parsed body, or {error: text} when the body is not JSON.
  async function api(method, path, body) {
    const headers = {};
    const opts = { method, headers, cache: 'no-store' };
    if (method !== 'GET') {
      headers['Content-Type'] = 'application/json';
      if (st.token) headers['Authorization'] = 'Bearer ' + st.token;
      if (body !== undefined) opts.body = JSON.stringify(body);
    }
    let res;
    try {
      res = await fetch(API + path, opts);
    } catch (e) {
      return { ok: false, status: 0, data: { error: 'no answer from vdrive: ' + e.message } };
    }
    const text = await res.text();
    let data;
    try { data = text ? JSON.parse(text) : {}; } catch { data = { error: text || res.statusText }; }
    return { ok: res.ok, status: res.status, data };
  }

  // Empty while a request is under way, so an old answer is never read as the new one.
  function clearResult(node) {
    node.classList.remove('ok', 'err');
    node.textContent = '';
  }
  function showResult(node, ok, text) {
    node.classList.toggle('ok', ok);
    node.classList.toggle('err', !ok);
    node.textContent = text;
  }
  const errorText = r => `${r.status ? 'HTTP ' + r.status + ': ' : ''}${(r.data && r.data.error) || 'failed'}`;

  // ---------------------------------------------------------------- live data

  function setConn(state, text) {
    const c = $('#conn');
    c.className = 'badge conn-' + state;
    c.dataset.state = state;
    setText(c, text);
  }

  let source = null;
  let streamFailures = 0;
  let pollTimer = 0;

  function connect() {
    if (!window.EventSource || streamFailures >= 3) { startPolling(); return; }
    source = new EventSource(API + '/stream');
    let opened = false;
    source.addEventListener('open', () => {
      opened = true;
      streamFailures = 0;
      setConn('live', 'live');
      // No catch-up request: a new stream's first update carries everything the server keeps.
    });
    source.addEventListener('update', ev => {
      let d;
      try { d = JSON.parse(ev.data); } catch { return; }
      onUpdate(d);
    });
    source.addEventListener('error', () => {
      if (!opened) streamFailures++;
      if (source.readyState === EventSource.CLOSED) {
        source = null;
        setConn('lost', 'disconnected');
        setTimeout(connect, 2000);
      } else {
        setConn('wait', 'reconnecting');
      }
    });
  }

  // For a proxy that buffers event streams: the same data by polling at 20 Hz.
  function startPolling() {
    if (source) { source.close(); source = null; }
    setConn('live', 'polling');
    const tick = async () => {
      const begun = performance.now();
      const [l, s, e] = await Promise.all([api('GET', '/line'), api('GET', '/samples?since=' + st.sampleSeq),
        api('GET', '/events?since=' + st.eventSeq)]);
      if (l.ok) {
        onUpdate({ line: l.data, samples: s.ok ? s.data : null, events: e.ok ? e.data.events : [] });
        setConn('live', 'polling');
      } else {
        setConn('lost', 'disconnected');
      }
      pollTimer = setTimeout(tick, Math.max(0, POLL_MS - (performance.now() - begun)));   // a period, not a pause
    };
    clearTimeout(pollTimer);
    tick();
  }

  function onUpdate(d) {
    st.updates++;
    if (d.line) renderLine(d.line);
    if (d.samples) addSamples(d.samples);
    if (d.events && d.events.length) addEvents(d.events);
    scheduleDraw();
  }

  // Plots are drawn at most once per animation frame, only for axes on screen and expanded;
  // a background tab draws nothing.
  function scheduleDraw() {
    if (st.drawPending) return;
    st.drawPending = true;
    requestAnimationFrame(() => {
      st.drawPending = false;
      if (!st.paused) for (const ax of st.axes.values()) ax.draw();
      followEvents();
    });
  }

  // ---------------------------------------------------------------- the line

  function renderLine(line) {
    // The line's clock going back is another vdrive behind the same address: start afresh.
    if (st.lineTime != null && line.time_ns < st.lineTime - 1e9) restart();
    st.lineTime = line.time_ns;
    st.tokenRequired = !!line.token_required;
    const tokenBadge = $('#token-state');
    tokenBadge.hidden = !(st.tokenRequired && !st.token);
    setText(tokenBadge, 'read-only: open the URL vdrive printed (#token=...) to change anything');

    setText($('#line-source'), `${line.version || ''} · ${line.source || ''}`);
    setText($('#line-info'), line.interface ? `on ${line.interface}` : '');
    renderCounters(line.counters || {});

    const slaves = line.slaves || [];
    const layout = slaves.map(s => `${s.position}:${s.product}:${s.drive ? 1 : 0}`).join(',');
    if (layout !== st.layout) { st.layout = layout; rebuild(slaves); }
    st.slaves = slaves;
    for (const s of slaves) {
      const box = st.boxes.get(s.position);
      if (box) renderSlaveBox(box, s);
      const ax = st.axes.get(s.position);
      if (ax && s.drive) ax.render(s);
    }
    renderFaults(line.faults || []);
    renderScenario(line.scenario);
  }

  function renderCounters(c) {
    st.framesIn = c.frames_in;
    const node = $('#line-counters');
    const parts = [
      ['frames in', c.frames_in], ['out', c.frames_out], ['dropped', c.frames_dropped],
      ['send failed', c.send_failed], ['rx errors', c.rx_errors], ['lost links', c.lost_links],
      ['host stalls', c.host_stalls || 0],
    ];
    const sig = parts.map(p => p[1]).join(',');
    if (node.__sig === sig) return;
    node.__sig = sig;
    node.replaceChildren(...parts.map(([k, v], i) => {
      const bad = i >= 2 && v > 0;
      return el('span', {}, (i ? ' · ' : '') + k + ' ', el('b', { class: bad ? 'bad' : '', text: v ?? '-' }));
    }));
  }

  function rebuild(slaves) {
    const strip = $('#net-strip');
    strip.replaceChildren();
    // A long line wraps as small boxes, so a bench of 64 drives fits on the screen.
    st.compact = slaves.length > 12;
    strip.classList.toggle('compact', st.compact);
    st.boxes.clear();
    for (const ax of st.axes.values()) ax.destroy();
    st.axes.clear();
    $('#axis-grid').replaceChildren();

    strip.append(el('div', { class: 'net-master', title: 'the master, on the other end of the cable' },
      el('div', { class: 'sl-head', text: 'master' }), el('div', { class: 'sl-product', id: 'net-iface' })));
    const tpl = $('#tpl-slave');
    let previous = 0;
    for (const s of slaves) {
      // In a line each slave hangs off the one before; a tree's branch says which port feeds it.
      const branch = s.parent !== undefined && s.parent !== previous;
      strip.append(branch
        ? el('div', { class: 'net-cable branch', title: `cabled to port ${s.parent_port} of slave ${s.parent}`,
                      text: `${s.parent}:${s.parent_port}` })
        : el('div', { class: 'net-cable' }));
      previous = s.position;
      const box = tpl.content.firstElementChild.cloneNode(true);
      box.dataset.slave = s.position;
      box.id = 'slave-' + s.position;
      box.addEventListener('click', () => select(s.position, true));
      box.addEventListener('keydown', e => { if (e.key === 'Enter') select(s.position, true); });
      strip.append(box);
      st.boxes.set(s.position, box);
      if (s.drive) {
        const ax = new Axis(s);
        st.axes.set(s.position, ax);
        $('#axis-grid').append(ax.root);
      }
    }
    fillSlaveSelects(slaves);
    if (!st.boxes.has(st.selected)) st.selected = slaves.length ? slaves[0].position : 0;
    select(st.selected, false);
  }

  function fillSlaveSelects(slaves) {
    const label = s => `${s.position} ${s.name || s.product}`;
    // Only a drive moves a plant: couplers and terminals are not offered there.
    const lists = { '#fault-slave': slaves, '#od-slave': slaves, '#plant-slave': slaves.filter(s => s.drive) };
    for (const [id, list] of Object.entries(lists)) {
      const sel = $(id);
      const keep = sel.value;
      sel.replaceChildren(...list.map(s => el('option', { value: s.position, text: label(s) })));
      if (keep && list.some(s => String(s.position) === keep)) sel.value = keep;
    }
    const ev = $('#ev-slave');
    const keep = ev.value;
    ev.replaceChildren(el('option', { value: '', text: 'every slave' }), el('option', { value: '0', text: 'line' }),
      ...slaves.map(s => el('option', { value: s.position, text: label(s) })));
    ev.value = keep;
  }

  function select(pos, scroll) {
    st.selected = pos;
    for (const [p, box] of st.boxes) box.classList.toggle('selected', p === pos);
    for (const [p, ax] of st.axes) ax.root.classList.toggle('selected', p === pos);
    for (const id of ['#fault-slave', '#od-slave', '#plant-slave']) {
      const sel = $(id);
      if (pos && [...sel.options].some(o => o.value === String(pos))) sel.value = pos;
    }
    const ax = st.axes.get(pos);
    if (scroll && ax) ax.root.scrollIntoView({ block: 'nearest', behavior: 'smooth' });
  }

  function renderSlaveBox(box, s) {
    setAttr(box, 'data-al-state', s.al_state);
    setAttr(box, 'data-al-error', !!s.al_error);
    setText(part(box, '.sl-pos'), s.position);
    setText(part(box, '.sl-name'), s.name || s.product);
    setText(part(box, '.sl-product'), `${s.product_name || s.product} · ${s.product}`);
    box.title = `vendor ${hex(s.vendor_id, 8)} product ${hex(s.product_code, 8)} revision ${hex(s.revision, 8)}`;
    setText(part(box, '.sl-addr'), `${s.address ? hex(s.address) : 'no address'}${s.alias ? ' alias ' + s.alias : ''}`);
    const al = part(box, '.sl-al-state');
    setText(al, (s.al_state_name || s.al_state) + (s.al_error ? (st.compact ? '+E' : ' + error') : ''));
    al.className = 'sl-al-state ' + (s.al_error ? 'al-err' : 'al-' + s.al_state);
    const status = part(box, '.sl-al-status');
    setText(status, s.al_status_code ? `${hex(s.al_status_code)} ${s.al_status_text}` : s.al_status_text || 'No error');
    status.classList.toggle('err', !!s.al_status_code);
    setText(part(box, '.sl-drive'), s.drive ? `${s.drive.state}${s.drive.alarm ? ' · ' + alarmCode(s.drive.alarm) : ''}` : 'no drive');
    const rx = s.rx_errors || [], lost = s.lost_links || [];
    const cnt = part(box, '.sl-counters');
    const sig = rx.join('/') + '|' + lost.join('/');
    if (cnt.__sig !== sig) {
      cnt.__sig = sig;
      const bad = a => a.some(v => v > 0) ? 'bad' : '';
      cnt.replaceChildren(el('span', { class: bad(rx), title: 'invalid frame counters per port (0300h)', text: 'rx ' + rx.join('/') }), ' ',
        el('span', { class: bad(lost), title: 'lost link counters per port (0310h)', text: 'll ' + lost.join('/') }));
    }
    const dc = part(box, '.sl-dc');
    const d = s.dc || {};
    setText(dc, !d.enabled ? 'DC off' : `DC ${d.locked ? 'locked' : 'not locked'} ${d.system_time_difference_ns} ns`);
    dc.className = 'sl-dc small ' + (!d.enabled ? '' : d.locked ? 'locked' : 'unlocked');
    setAttr(box, 'data-dc-locked', !!(d.enabled && d.locked));
  }

  function restart() {
    for (const ax of st.axes.values()) ax.reset();
    st.sampleSeq = 0;
    st.eventSeq = 0;
    st.events = [];
    st.latestT = 0;
    $('#ev-list tbody').replaceChildren();
  }

  // ---------------------------------------------------------------- axes

  const visibility = new IntersectionObserver(entries => {
    for (const e of entries) {
      const ax = e.target.__axis;
      if (!ax) continue;
      ax.visible = e.isIntersecting;
      if (ax.visible) {
        if (ax.last) ax.render(ax.last);
        ax.dirty = true;
        scheduleDraw();
      }
    }
  }, { rootMargin: '200px 0px' });

  const SERIES = [
    // key, label, scale, colour, dash
    ['target_position', 'target', 'yPos', '#c9d1d9', [4, 3]],
    ['position', 'position', 'yPos', '#4aa3ff', []],
    ['velocity', 'velocity', 'yVel', '#3fb950', []],
    ['torque', 'torque', 'yTrq', '#d29922', []],
    ['following_error', 'following error', 'yFe', '#f85149', []],
  ];

  class Axis {
    constructor(s) {
      this.pos = s.position;
      this.root = $('#tpl-axis').content.firstElementChild.cloneNode(true);
      this.root.dataset.slave = s.position;
      this.root.id = 'axis-' + s.position;
      this.root.__axis = this;
      part(this.root, '.ax-alarm-code').id = 'alarm-' + s.position;
      setText(part(this.root, '.ax-title'), `${s.position} · ${s.name || s.product} · ${s.product_name || ''}`);
      this.values = Object.fromEntries($$('[data-v]', this.root).map(b => [b.dataset.v, b]));
      this.data = Object.fromEntries(SERIES.map(([k]) => [k, []]));
      this.lastT = -Infinity;
      this.chart = null;
      this.visible = false;
      this.expanded = true;
      this.dirty = false;
      this.emcySig = '';
      part(this.root, '.ax-toggle').addEventListener('click', () => this.expand(!this.expanded));
      part(this.root, '.ax-title').addEventListener('click', () => select(this.pos, false));
      visibility.observe(this.root);
    }

    expand(on) {
      this.expanded = on;
      this.root.classList.toggle('collapsed', !on);
      part(this.root, '.ax-toggle').setAttribute('aria-expanded', on);
      if (on) { this.dirty = true; scheduleDraw(); }
    }

    destroy() {
      visibility.unobserve(this.root);
      if (this.chart) this.chart.destroy();
    }

    // Off screen only what the page is asked about (state, alarm) is kept current; the numbers
    // follow when the panel scrolls into view. With 64 drives this is most of the page's work.
    render(s) {
      this.last = s;
      const d = s.drive;
      const r = this.root;
      setAttr(r, 'data-pds', d.state);
      setAttr(r, 'data-error-code', d.error_code);
      this.renderAlarm(d.alarm);
      if (!this.visible && this.rendered) return;
      this.rendered = true;
      const stEl = part(r, '.ax-state');
      setText(stEl, d.state);
      setAttr(stEl, 'data-pds', d.state);
      setText(part(r, '.ax-mode'), d.mode_name || 'mode ' + d.mode);
      for (const k of ['position', 'target_position', 'velocity', 'torque', 'following_error']) setText(this.values[k], d[k]);
      setText(this.values.statusword, hex(d.statusword));
      setText(this.values.controlword, hex(d.controlword));
      setText(this.values.error_code, hex(d.error_code));
      this.renderIo(d);
      this.renderEmergencies(d.emergencies || []);
    }

    renderAlarm(a) {
      const r = this.root;
      const alarm = part(r, '.ax-alarm');
      setText(part(r, '.ax-alarm-code'), a ? alarmCode(a) : '');
      setText(part(r, '.ax-alarm-name'), a ? `${a.name} (603Fh ${hex(a.error_code)})` : '');
      alarm.classList.toggle('active', !!a && !a.warning);
      alarm.classList.toggle('warning', !!a && !!a.warning);
      alarm.title = a ? (a.warning ? 'warning ' : 'alarm ') + alarmCode(a) + ' ' + a.name : '';
      setAttr(r, 'data-alarm-code', a ? alarmCode(a) : '');
    }

    renderIo(d) {
      const di = part(this.root, '.ax-di');
      const sig = String(d.digital_inputs);
      if (di.__sig !== sig) {
        di.__sig = sig;
        // 60FDh bits 0-2 are CiA 402's: negative limit, positive limit, home switch.
        const bits = [[0, 'NOT'], [1, 'POT'], [2, 'HOME']].map(([b, name]) =>
          el('span', { title: `bit ${b}` }, el('span', { class: 'bit' + ((d.digital_inputs >>> b) & 1 ? ' on' : '') }), name + ' '));
        di.replaceChildren('DI ', ...bits, hex(d.digital_inputs, 8));
      }
      setText(part(this.root, '.ax-probe'), `probe ${hex(d.probe_status)} pos1 ${d.probe_position1}`);
    }

    renderEmergencies(list) {
      const last = list[list.length - 1];
      const sig = list.length + ':' + (last ? last.time_ns : '');
      if (sig === this.emcySig) return;
      this.emcySig = sig;
      const count = part(this.root, '.ax-emcy-count');
      setText(count, list.length ? `(${list.length}, last ${hex(last.error_code)})` : '(none)');
      count.classList.toggle('some', list.length > 0);
      part(this.root, '.ax-emcy ol').replaceChildren(...list.slice().reverse().map(e =>
        el('li', { text: `${secs(e.time_ns)} s  ${hex(e.error_code)}  ${e.text}` })));
    }

    addSamples(a) {
      const t = a.t || [];
      let added = 0;
      for (let i = 0; i < t.length; i++) {
        const x = t[i];
        if (!(x > this.lastT)) continue;     // the stream and a catch-up poll may overlap
        for (const [k] of SERIES) this.data[k].push({ x, y: (a[k] || [])[i] ?? null });
        this.lastT = x;
        added++;
      }
      if (!added) return;
      const cut = this.lastT - KEEP_S;
      const pos = this.data.position;
      let n = 0;
      while (n < pos.length && pos[n].x < cut) n++;
      if (n) for (const [k] of SERIES) this.data[k].splice(0, n);
      if (this.lastT > st.latestT) st.latestT = this.lastT;
      this.dirty = true;
    }

    reset() {
      for (const [k] of SERIES) this.data[k].length = 0;
      this.lastT = -Infinity;
      this.dirty = true;
    }

    draw() {
      if (!this.visible || !this.expanded || !this.dirty || !window.Chart) return;
      if (!this.chart) this.chart = makeChart($('canvas', this.root), this.data);
      const x = this.chart.options.scales.x;
      x.max = st.latestT;
      x.min = st.latestT - st.windowS;
      this.chart.update('none');
      this.dirty = false;
    }
  }

  function makeChart(canvas, data) {
    const grid = { color: '#26303a', drawBorder: false };
    const ticks = weight => ({ color: '#8a96a3', font: { size: 10 }, maxTicksLimit: weight > 1 ? 5 : 3, callback: v => compact(v) });
    // Four strips stacked on one time axis, like an oscilloscope: each quantity keeps its own
    // scale. Fixed tick width keeps the strips' left edges aligned.
    const strip = (title, weight) => ({
      type: 'linear', stack: 'axis', stackWeight: weight, offset: true, grid, ticks: ticks(weight),
      title: { display: true, text: title, color: '#8a96a3', font: { size: 10 } },
      afterFit: s => { s.width = 62; },
    });
    return new Chart(canvas, {
      type: 'line',
      data: {
        datasets: SERIES.map(([k, label, yAxisID, color, dash]) => ({
          label, data: data[k], yAxisID, borderColor: color, backgroundColor: color, borderDash: dash,
          borderWidth: k === 'target_position' ? 1 : 1.3,
        })),
      },
      options: {
        animation: false, parsing: false, normalized: true, responsive: true, maintainAspectRatio: false,
        spanGaps: true,
        elements: { point: { radius: 0, hitRadius: 3 }, line: { tension: 0 } },
        interaction: { mode: 'nearest', axis: 'x', intersect: false },
        plugins: {
          legend: { labels: { color: '#c9d1d9', boxWidth: 10, boxHeight: 2, font: { size: 10 } } },
          tooltip: { animation: false },
          decimation: { enabled: false },
        },
        // Chart.js stacks the scales of one stack bottom-up in the order they are declared.
        scales: {
          x: { type: 'linear', grid, ticks: { color: '#8a96a3', font: { size: 10 }, maxTicksLimit: 7, maxRotation: 0, callback: v => Number(v).toFixed(0) + ' s' } },
          yFe: strip('ferr', 1),
          yTrq: strip('trq', 1),
          yVel: strip('vel', 1),
          yPos: strip('pos', 2),
        },
      },
    });
  }

  function addSamples(samples) {
    if (!samples || !samples.axes) return;
    // Stream updates and catch-up polls interleave, so an older seq is normal: keep the newest.
    if (typeof samples.seq === 'number' && samples.seq > st.sampleSeq) st.sampleSeq = samples.seq;
    for (const a of samples.axes) {
      const ax = st.axes.get(a.slave);
      if (ax) ax.addSamples(a);
    }
  }

  // ---------------------------------------------------------------- events

  function addEvents(list) {
    const fresh = [];
    for (const e of list) {
      if (e.seq != null && e.seq <= st.eventSeq) continue;
      if (e.seq != null) st.eventSeq = e.seq;
      st.events.push(e);
      fresh.push(e);
      if (e.kind === 'signal') refreshSignalsSoon();
    }
    if (!fresh.length) return;
    const kinds = $('#ev-kind');
    for (const e of fresh) {
      if (!$$('option', kinds).some(o => o.value === e.kind)) kinds.append(el('option', { value: e.kind, text: e.kind }));
    }
    const drop = st.events.length - MAX_EVENTS;
    if (drop > 0) st.events.splice(0, drop);
    const body = $('#ev-list tbody');
    const f = eventFilter();
    const rows = fresh.filter(f).slice(-MAX_ROWS).map(eventRow);
    if (rows.length) {
      body.append(...rows);
      for (let n = body.rows.length - MAX_ROWS; n > 0; n--) body.deleteRow(0);
      if ($('#ev-follow').checked) st.followEvents = true;
    }
    showEventCount(body.rows.length);
  }

  // Reading scrollHeight lays the page out at once: done in the animation frame, after the
  // frame's own layout, never once per update.
  function followEvents() {
    if (!st.followEvents) return;
    st.followEvents = false;
    const w = $('#ev-wrap');
    w.scrollTop = w.scrollHeight;
  }

  function showEventCount(shown) {
    setText($('#ev-count'), shown < st.events.length ? `(${shown} shown of ${st.events.length})` : `(${st.events.length})`);
  }

  function eventRow(e) {
    const tr = el('tr', { 'data-kind': e.kind, 'data-slave': e.slave },
      el('td', { text: secs(e.time_ns) }), el('td', { text: e.slave || '' }), el('td', { text: e.kind }), el('td', { text: e.text }));
    tr.title = `${e.text}\nseq ${e.seq}, value ${e.value}, previous ${e.previous}`;
    return tr;
  }

  function eventFilter() {
    const kind = $('#ev-kind').value;
    const slave = $('#ev-slave').value;
    const text = $('#ev-text').value.trim().toLowerCase();
    return e => (!kind || e.kind === kind) && (slave === '' || String(e.slave) === slave)
      && (!text || (e.text || '').toLowerCase().includes(text) || e.kind.includes(text));
  }

  function refilterEvents() {
    const f = eventFilter();
    const rows = st.events.filter(f).slice(-MAX_ROWS).map(eventRow);
    $('#ev-list tbody').replaceChildren(...rows);
    showEventCount(rows.length);
    // The server filters the CSV by kind and slave; the text filter is the page's own.
    const q = new URLSearchParams();
    if ($('#ev-kind').value) q.set('kind', $('#ev-kind').value);
    if ($('#ev-slave').value !== '') q.set('slave', $('#ev-slave').value);
    $('#ev-csv').href = API + '/events.csv' + (q.toString() ? '?' + q : '');
    const w = $('#ev-wrap'); w.scrollTop = w.scrollHeight;
  }

  // ---------------------------------------------------------------- faults

  async function loadFaultKinds() {
    const r = await api('GET', '/fault-kinds');
    if (!r.ok) { showResult($('#fault-result'), false, 'fault kinds: ' + errorText(r)); return; }
    st.faultKinds = r.data.kinds || [];
    const sel = $('#fault-kind');
    const layers = new Map();
    for (const k of st.faultKinds) {
      if (!layers.has(k.layer)) layers.set(k.layer, el('optgroup', { label: k.layer }));
      layers.get(k.layer).append(el('option', { value: k.kind, text: k.kind + (k.one_shot ? ' (one-shot)' : '') }));
    }
    sel.replaceChildren(...layers.values());
    renderFaultFields();
  }

  function currentKind() { return st.faultKinds.find(k => k.kind === $('#fault-kind').value); }

  function renderFaultFields() {
    const k = currentKind();
    const box = $('#fault-fields');
    box.replaceChildren();
    if (!k) return;
    setText($('#fault-summary'), k.summary || '');
    const fields = k.fields || [];
    $('#fault-slave-label').hidden = !fields.some(f => f.name === 'slave');
    for (const f of fields) {
      if (f.name === 'slave' || f.name === 'kind') continue;
      const id = 'fault-f-' + f.name;
      const label = el('label', { class: f.required ? 'req' : '', text: f.name });
      label.htmlFor = id;
      let input;
      const def = f.default != null ? String(f.default) : '';
      if (f.type === 'enum') {
        input = el('select', { id });
        if (!f.required) input.append(el('option', { value: '', text: def ? `(default ${def})` : '(default)' }));
        for (const c of f.choices || []) input.append(el('option', { value: c, text: c }));
      } else {
        const ph = def || (f.type === 'time' ? (f.name === 'duration' ? 'until cleared' : '300ms') : '');
        input = el('input', { id, type: 'text', placeholder: ph });
        if (f.choices && f.choices.length) {
          const list = el('datalist', { id: id + '-choices' }, ...f.choices.map(c => el('option', { value: c })));
          box.append(list);
          input.setAttribute('list', id + '-choices');
        }
      }
      // The alarm fault's code is one of the slave's product's alarms: offer its table.
      if (f.name === 'code' && k.kind === 'alarm') fillAlarmChoices(box, input, id);
      input.dataset.field = f.name;
      input.dataset.type = f.type;
      box.append(label, input);
      if (f.help) box.append(el('div', { class: 'help', text: f.help }));
    }
  }

  async function fillAlarmChoices(box, input, id) {
    const pos = Number($('#fault-slave').value);
    if (!pos) return;
    const r = await api('GET', `/slaves/${pos}/alarms`);
    if (!r.ok) return;
    const list = el('datalist', { id: id + '-choices' },
      ...r.data.alarms.map(a => el('option', { value: a.code, text: `${a.code} ${a.name}` })));
    box.append(list);
    input.setAttribute('list', id + '-choices');
    input.placeholder = r.data.alarms.length ? r.data.alarms[0].code : '';
  }

  // Integers go as JSON numbers when decimal; "0x06020000" goes as text, which the server reads
  // as hex. Empty fields are left out so the server applies its defaults.
  function faultRequest() {
    const k = currentKind();
    if (!k) return null;
    const body = { kind: k.kind };
    if ((k.fields || []).some(f => f.name === 'slave')) body.slave = Number($('#fault-slave').value);
    for (const input of $$('[data-field]', $('#fault-fields'))) {
      const raw = input.value.trim();
      if (raw === '') continue;
      const type = input.dataset.type;
      let v = raw;
      if (type === 'integer' && /^[-+]?\d+$/.test(raw)) v = Number(raw);
      else if (type === 'real' && raw !== '' && Number.isFinite(Number(raw))) v = Number(raw);
      body[input.dataset.field] = v;
    }
    if ($('#fault-later').checked) body.after = $('#fault-after').value.trim() || '0s';
    return body;
  }

  async function injectFault(ev) {
    ev.preventDefault();
    const body = faultRequest();
    const out = $('#fault-result');
    if (!body) { showResult(out, false, 'no fault kinds (is vdrive running?)'); return; }
    const btn = $('#fault-inject');
    btn.disabled = true;
    clearResult(out);
    const r = await api('POST', '/faults', body);
    btn.disabled = false;
    if (r.status === 202) showResult(out, true, `${body.kind} scheduled in ${body.after} (ticket ${r.data.scheduled})`);
    else if (r.ok) showResult(out, true, r.data.id ? `fault ${r.data.id} ${body.kind} injected` : `${body.kind} done (one-shot)`);
    else showResult(out, false, errorText(r));
    refreshScheduled();
  }

  function renderFaults(faults) {
    const body = $('#fault-list tbody');
    const sig = faults.map(f => `${f.id}:${Math.floor((f.elapsed_ns || 0) / 1e8)}:${f.remaining_ns}`).join(',');
    if (body.__sig === sig) return;
    body.__sig = sig;
    if (!faults.length) {
      body.replaceChildren(el('tr', {}, el('td', { class: 'muted', text: 'none', colSpan: 5 })));
      return;
    }
    body.replaceChildren(...faults.map(f => {
      const b = el('button', { type: 'button', text: 'clear', 'data-fault-id': f.id });
      b.addEventListener('click', () => clearFault(f.id));
      return el('tr', { 'data-fault-id': f.id }, el('td', { text: f.id }), el('td', { text: f.description || f.kind }),
        el('td', { text: duration(f.elapsed_ns) }), el('td', { text: duration(f.remaining_ns) }), el('td', {}, b));
    }));
  }

  async function clearFault(id) {
    const r = await api('DELETE', '/faults/' + id);
    showResult($('#fault-result'), r.ok, r.ok ? `fault ${id} cleared` : errorText(r));
  }

  async function clearAllFaults() {
    const r = await api('DELETE', '/faults');
    showResult($('#fault-result'), r.ok, r.ok ? `cleared ${r.data.cleared} fault(s)` : errorText(r));
    refreshScheduled();
  }

  // Scheduled faults are only in GET /faults: watched once a second while there are any.
  let scheduledTimer = 0;
  async function refreshScheduled() {
    clearTimeout(scheduledTimer);
    const r = await api('GET', '/faults');
    const list = (r.ok && r.data.scheduled) || [];
    $('#fault-scheduled').replaceChildren(...list.map(s =>
      el('div', { text: `scheduled ${s.ticket}: ${(s.fault && s.fault.kind) || '?'}${s.fault && s.fault.slave ? ' slave ' + s.fault.slave : ''} at ${secs(s.at_ns)} s` })));
    if (list.length) scheduledTimer = setTimeout(refreshScheduled, 1000);
  }

  // ---------------------------------------------------------------- object dictionary

  // Indexes are hex as engineers write them ("6041", "0x6041", "6041h"); "6041:2" sets the
  // subindex too. Subindexes are decimal unless written as hex.
  function parseIndex(text) {
    const t = text.trim().replace(/^0x/i, '').replace(/h$/i, '');
    return /^[0-9a-f]{1,4}$/i.test(t) ? parseInt(t, 16) : NaN;
  }
  function parseSub(text) {
    const t = text.trim();
    if (/^0x[0-9a-f]+$/i.test(t)) return parseInt(t, 16);
    if (/^[0-9a-f]+h$/i.test(t)) return parseInt(t.slice(0, -1), 16);
    return /^\d+$/.test(t) ? parseInt(t, 10) : NaN;
  }
  function odTarget() {
    const indexInput = $('#od-index');
    if (indexInput.value.includes(':')) {
      const [i, s] = indexInput.value.split(':');
      indexInput.value = i;
      $('#od-sub').value = s;
    }
    const index = parseIndex(indexInput.value);
    const sub = parseSub($('#od-sub').value || '0');
    const slave = Number($('#od-slave').value);
    if (!(index >= 0) || !(sub >= 0 && sub <= 255)) return null;
    return { slave, index, sub, path: `/slaves/${slave}/objects/${hex(index)}/${sub}` };
  }

  let odTypes = new Map();           // "index:sub" -> type, from searches and reads

  async function odSearch(ev) {
    ev.preventDefault();
    const q = $('#od-query').value.trim();
    const slave = Number($('#od-slave').value);
    const r = await api('GET', `/slaves/${slave}/objects` + (q ? '?q=' + encodeURIComponent(q) : ''));
    const body = $('#od-list tbody');
    if (!r.ok) { body.replaceChildren(); showResult($('#od-result'), false, errorText(r)); return; }
    const objs = r.data.objects || [];
    const rows = objs.map(o => {
      odTypes.set(`${o.index}:${o.subindex}`, o.type);
      const range = o.min != null || o.max != null ? `${o.min ?? ''}..${o.max ?? ''}` : '';
      const tr = el('tr', { 'data-index': o.index, 'data-sub': o.subindex },
        el('td', { class: 'mono', text: idx(o.index, o.subindex) }), el('td', { text: o.name }), el('td', { text: o.type }),
        el('td', { text: o.access }), el('td', { text: o.pdo || '' }), el('td', { class: 'mono', text: range }),
        el('td', { class: 'mono', text: o.default ?? '' }));
      tr.addEventListener('click', () => {
        $$('tr.picked', body).forEach(x => x.classList.remove('picked'));
        tr.classList.add('picked');
        $('#od-index').value = hex(o.index);
        $('#od-sub').value = o.subindex;
        odRead();
      });
      return tr;
    });
    if (!rows.length) rows.push(el('tr', {}, el('td', { colSpan: 7, class: 'muted', text: `no object matches "${q}"` })));
    if (r.data.truncated) rows.push(el('tr', {}, el('td', { colSpan: 7, class: 'muted', text: 'more objects match: narrow the search' })));
    body.replaceChildren(...rows);
  }

  // The drive's answer as a master would see it: the SDO abort code and its text; the server's
  // message only when there is no abort (no such slave, a bad value).
  function showOdRefusal(r, t, what) {
    const out = $('#od-result');
    const d = r.data || {};
    out.dataset.abortCode = d.abort_code || '';
    showResult(out, false, d.abort_code
      ? `${idx(t.index, t.sub)} ${what} refused: abort ${d.abort_code} ${d.abort_text || ''}`
      : errorText(r));
  }

  async function odRead() {
    const t = odTarget();
    const out = $('#od-result');
    if (!t) { showResult(out, false, 'index: hex, e.g. 6041; sub: 0..255'); return; }
    clearResult(out);
    const r = await api('GET', t.path);
    if (!r.ok) { showOdRefusal(r, t, 'read'); return; }
    const o = r.data;
    odTypes.set(`${o.index}:${o.subindex}`, o.type);
    out.dataset.abortCode = '';
    const num = typeof o.value === 'number' ? ` (${hex(o.value, 2)})` : '';
    showResult(out, true, `${idx(o.index, o.subindex)} ${o.name || ''} = ${JSON.stringify(o.value)}${num}\n${o.type || ''} ${o.access || ''} · bytes ${o.hex}`);
    $('#od-value').value = $('#od-hex').checked ? o.hex : typeof o.value === 'string' ? o.value : String(o.value);
  }

  async function odWrite(ev) {
    ev.preventDefault();
    const t = odTarget();
    const out = $('#od-result');
    if (!t) { showResult(out, false, 'index: hex, e.g. 6041; sub: 0..255'); return; }
    const raw = $('#od-value').value.trim();
    let body;
    if ($('#od-hex').checked) body = { hex: raw.replace(/\s+/g, '') };
    else {
      const type = odTypes.get(`${t.index}:${t.sub}`) || '';
      // Numbers for numeric objects (0x.. accepted), text for strings; the server names a mismatch.
      const numeric = /^[-+]?(0x[0-9a-f]+|\d+(\.\d*)?([eE][-+]?\d+)?)$/i.test(raw);
      body = { value: !TEXT_TYPES.test(type) && numeric ? Number(raw) : raw };
    }
    clearResult(out);
    const r = await api('PUT', t.path, body);
    if (!r.ok) { showOdRefusal(r, t, 'write'); return; }
    out.dataset.abortCode = '';
    showResult(out, true, `${idx(t.index, t.sub)} written; read back ${JSON.stringify(r.data.value)} · bytes ${r.data.hex}`);
  }

  // ---------------------------------------------------------------- plant and signals

  async function plantSet(body) {
    const slave = Number($('#plant-slave').value);
    const r = await api('POST', `/slaves/${slave}/plant`, body);
    const what = Object.entries(body).map(([k, v]) => `${k.replace('_', ' ')} ${v}`).join(', ');
    showResult($('#plant-result'), r.ok, r.ok ? `slave ${slave}: ${what}` : errorText(r));
  }

  async function refreshSignals() {
    const r = await api('GET', '/signals');
    if (!r.ok) { showResult($('#signal-result'), false, errorText(r)); return; }
    renderSignals(r.data.signals || []);
  }
  let signalsTimer = 0;
  function refreshSignalsSoon() {
    if (signalsTimer) return;
    signalsTimer = setTimeout(() => { signalsTimer = 0; refreshSignals(); }, 250);
  }

  function renderSignals(list) {
    const body = $('#signal-list tbody');
    if (!list.length) {
      body.replaceChildren(el('tr', {}, el('td', { colSpan: 5, class: 'muted', text: 'no named signals (a network file names them, docs/networks.md)' })));
      return;
    }
    body.replaceChildren(...list.map(s => {
      const input = el('input', { type: 'text', value: s.value, size: 5 });
      const set = el('button', { type: 'button', text: 'set' });
      const cell = el('td', {}, input, ' ', set);
      if (s.type === 'BOOL') {
        const toggle = el('button', { type: 'button', text: s.value ? 'off' : 'on' });
        toggle.addEventListener('click', () => signalSet(s.name, s.value ? 0 : 1));
        cell.append(' ', toggle);
      }
      set.addEventListener('click', () => {
        const v = input.value.trim();
        signalSet(s.name, /^[-+]?(0x[0-9a-f]+|\d+(\.\d*)?)$/i.test(v) ? Number(v) : v);
      });
      return el('tr', { 'data-signal': s.name }, el('td', { text: s.name }), el('td', { class: 'mono', text: s.point }),
        el('td', { text: s.type }), el('td', { class: 'mono', text: s.value }), cell);
    }));
  }

  async function signalSet(name, value) {
    const r = await api('PUT', '/signals/' + encodeURIComponent(name), { value });
    showResult($('#signal-result'), r.ok, r.ok ? `${name} = ${value}` : errorText(r));
    if (r.ok && r.data.signals) renderSignals(r.data.signals);
  }

  // ---------------------------------------------------------------- scenario

  function renderScenario(s) {
    const panel = $('#scenario');
    panel.hidden = !s;
    if (!s) return;
    setAttr(panel, 'data-state', s.state);
    setText($('#scn-name'), s.name);
    const badge = $('#scn-state');
    setText(badge, s.state);
    setAttr(badge, 'data-state', s.state);
    const frac = s.duration_ns > 0 ? Math.min(1, s.elapsed_ns / s.duration_ns) : (s.state === 'running' ? 0 : 1);
    $('#scn-progress').style.width = (frac * 100).toFixed(1) + '%';
    setText($('#scn-time'), `${secs(s.elapsed_ns)} / ${secs(s.duration_ns)} s`);

    const log = $('#scn-log');
    const lines = s.log || [];
    const shown = log.__n || 0;
    if (lines.length < shown) { log.textContent = ''; log.__n = 0; }
    if (lines.length > (log.__n || 0)) {
      const atEnd = log.scrollTop + log.clientHeight >= log.scrollHeight - 4;
      log.append(lines.slice(log.__n || 0).join('\n') + '\n');
      log.__n = lines.length;
      if (atEnd) log.scrollTop = log.scrollHeight;
    }

    const exp = s.expectations || [];
    const body = $('#scn-expect tbody');
    const sig = exp.map(e => e.line + e.state + e.detail).join('|');
    if (body.__sig === sig) return;
    body.__sig = sig;
    body.replaceChildren(...exp.map(e => el('tr', { 'data-state': e.state },
      el('td', { class: 'mono', text: e.line }), el('td', { text: e.text }), el('td', { text: e.state }), el('td', { class: 'small', text: e.detail || '' }))));
  }

  // ---------------------------------------------------------------- start

  function wire() {
    for (const b of $$('.tabs button')) {
      b.addEventListener('click', () => {
        for (const x of $$('.tabs button')) x.classList.toggle('active', x === b);
        for (const p of $$('.tab-page')) p.hidden = p.dataset.page !== b.dataset.tab;
        if (b.dataset.tab === 'plant') refreshSignals();
      });
    }
    $('#fault-kind').addEventListener('change', renderFaultFields);
    $('#fault-slave').addEventListener('change', () => { if (currentKind()?.kind === 'alarm') renderFaultFields(); });
    $('#fault-form').addEventListener('submit', injectFault);
    $('#fault-after').addEventListener('focus', () => { $('#fault-later').checked = true; });
    $('#fault-clear-all').addEventListener('click', clearAllFaults);
    $('#od-search-form').addEventListener('submit', odSearch);
    $('#od-read').addEventListener('click', odRead);
    $('#od-access').addEventListener('submit', odWrite);
    $('#od-slave').addEventListener('change', () => select(Number($('#od-slave').value), true));
    $('#plant-form').addEventListener('submit', e => {
      e.preventDefault();
      const v = Number($('#plant-load').value);
      if (!Number.isFinite(v)) { showResult($('#plant-result'), false, 'external load: a number'); return; }
      plantSet({ external_load: v });
    });
    for (const b of $$('.plant-brake')) b.addEventListener('click', () => plantSet({ brake: b.dataset.brake }));
    for (const b of $$('.fault-shortcut')) {
      b.addEventListener('click', () => {
        const slave = $('#plant-slave').value;
        $('.tabs button[data-tab="faults"]').click();
        $('#fault-kind').value = b.dataset.kind;
        renderFaultFields();
        $('#fault-slave').value = slave;
      });
    }
    $('#signals-refresh').addEventListener('click', refreshSignals);
    for (const id of ['#ev-kind', '#ev-slave']) $(id).addEventListener('change', refilterEvents);
    $('#ev-text').addEventListener('input', refilterEvents);
    $('#plot-window').addEventListener('change', e => {
      st.windowS = Number(e.target.value);
      for (const ax of st.axes.values()) ax.dirty = true;
      scheduleDraw();
    });
    $('#plot-pause').addEventListener('change', e => { st.paused = e.target.checked; if (!st.paused) { for (const ax of st.axes.values()) ax.dirty = true; scheduleDraw(); } });
    $('#axes-expand').addEventListener('click', () => { for (const ax of st.axes.values()) ax.expand(true); });
    $('#axes-collapse').addEventListener('click', () => { for (const ax of st.axes.values()) ax.expand(false); });
    const kinds = $('#ev-kind');
    for (const k of EVENT_KINDS) kinds.append(el('option', { value: k, text: k }));
  }

  // Once a second: the updates that arrived (the figure the page promises, >= 20) and the frames
  // the line answered, shown at the master's end of the cable.
  function rateMeter() {
    let lastUpdates = st.updates;
    let lastFrames = null;
    setInterval(() => {
      const c = $('#conn');
      c.title = `${st.updates - lastUpdates} updates/s`;
      lastUpdates = st.updates;
      const frames = st.framesIn;
      const box = $('#net-iface');
      if (box && frames != null && lastFrames != null) setText(box, `${Math.max(0, frames - lastFrames)} frames/s`);
      lastFrames = frames;
    }, 1000);
  }

  async function start() {
    st.token = loadToken();
    // The printed URL pasted into a tab that already shows the page changes only the fragment.
    window.addEventListener('hashchange', () => {
      st.token = loadToken();
      $('#token-state').hidden = !(st.tokenRequired && !st.token);
    });
    wire();
    rateMeter();
    const line = await api('GET', '/line');
    if (line.ok) renderLine(line.data);
    else setConn('lost', errorText(line));
    loadFaultKinds();
    refreshScheduled();
    connect();
  }

  window.vdrivePage = st;            // for a look from the browser's console
  document.addEventListener('DOMContentLoaded', start);
})();
