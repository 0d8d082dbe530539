// The instructor station's page: polls the station's JSON API and sends the instructor's
// commands. Plain browser JavaScript, no libraries, nothing fetched from anywhere but the
// station (URLs are relative so the page also works behind a path prefix).
//
// API:   GET  api/state            sim, nodes, hands, controls, view, events_next
//        GET  api/events?after=K   events with seq > K (K = -1: the newest 200), oldest first
//        GET  view.png             the newest left-eye preview (503: none yet)
//        POST api/sim              {command, checkpoint?} -> {seq}; acked in state sim.last_ack
//        POST api/control          {control_id, position} -> {seq}
//        POST api/failure          {failure, inserted} -> {seq}; acked as a "failure" event
//
// What tests read (tests/integration/instructor_browser_test.py), besides the texts:
//   #conn[data-conn]            "live" | "disconnected"
//   #sim-time[data-sim-time]    sim time in seconds ("" when unknown)
//   #frozen[data-frozen]        "true" | "false" ("" when unknown)
//   #last-ack[data-seq, data-command, data-accepted]
//   #nodes tr[data-node]        class alive | stale, data-alive, data-age-s
//   #controls tr[data-control-id]  data-position, data-position-name; .position-name;
//                               button.set-position[data-position] (.current on the current one)
//   #events li[data-seq][data-kind]
//   #view[data-loaded]          how many frames have been shown
//   #systems-time[data-sim-time]   the systems' time ("" without a systems node)
//   #gauges .gauge[data-system]    data-value; #gear-nose/-left/-right[data-lamp] green|red|off
//   #failures tr[data-failure]     data-inserted; button.insert, button.clear
//   #procedures .procedure[data-name]  data-state, data-errors, data-started-s; its
//                               li.step[data-status] (pending | done | missed), data-flags
'use strict';

const STATE_PERIOD_MS = 250;
const EVENTS_PERIOD_MS = 500;
const VIEW_PERIOD_MS = 250;
const LIVE_WITHIN_MS = 2000;     // "live" while the last good api/state is younger than this
const REQUEST_TIMEOUT_MS = 1500; // a hung request must not stall its polling loop
const MAX_EVENTS = 200;
const PENDING_CLICK_MS = 5000;   // how long a clicked position button shows as pending

const $ = (id) => document.getElementById(id);

// ---- HTTP ------------------------------------------------------------------------------------

async function request(url, options = {}) {
  const abort = new AbortController();
  const timer = setTimeout(() => abort.abort(), REQUEST_TIMEOUT_MS);
  try {
    return await fetch(url, {cache: 'no-store', signal: abort.signal, ...options});
  } finally {
    clearTimeout(timer);
  }
}

async function getJson(url) {
  const reply = await request(url);
  if (!reply.ok) throw new Error(`${url}: HTTP ${reply.status}`);
  return reply.json();
}

// POSTs body as JSON; resolves to the reply's JSON, throws with the station's error text.
async function postJson(url, body) {
  const reply = await request(url, {
    method: 'POST',
    headers: {'Content-Type': 'application/json'},
    body: JSON.stringify(body),
  });
  let json = null;
  try { json = await reply.json(); } catch (e) { /* an empty or non-JSON body */ }
  if (!reply.ok) throw new Error((json && json.error) || `HTTP ${reply.status}`);
  return json || {};
}

// ---- formatting ------------------------------------------------------------------------------

const isNum = (v) => typeof v === 'number' && Number.isFinite(v);
const fixed = (v, digits) => (isNum(v) ? v.toFixed(digits) : '—');
const seconds = (v) => (isNum(v) ? `${v.toFixed(3)} s` : '—');

// Sets an element's text only when it changed (keeps the DOM quiet between polls).
function setText(el, text) {
  if (el.textContent !== text) el.textContent = text;
}

function cell(className) {
  const td = document.createElement('td');
  if (className) td.className = className;
  return td;
}

// Puts rows into tbody in the given order, moving only rows that are out of place: a row
// moved under the pointer between mousedown and mouseup would lose the click.
function placeRows(tbody, rows) {
  rows.forEach((row, i) => {
    if (tbody.children[i] !== row) tbody.insertBefore(row, tbody.children[i] || null);
  });
  while (tbody.children.length > rows.length) tbody.lastElementChild.remove();
}

// ---- connection ------------------------------------------------------------------------------

let lastStateOkMs = -Infinity;
let lastStateError = '';

function renderConn() {
  const live = performance.now() - lastStateOkMs < LIVE_WITHIN_MS;
  const conn = $('conn');
  const word = live ? 'live' : 'disconnected';
  setText(conn, word);
  conn.className = word;
  conn.dataset.conn = word;
  conn.title = live ? '' : lastStateError;
  document.body.classList.toggle('stale-data', !live);
}

// ---- simulation panel ------------------------------------------------------------------------

const pendingCommands = new Map();   // seq -> label, until last_ack reaches it

function renderSim(sim) {
  const t = sim.sim_time_s;
  const simTime = $('sim-time');
  setText(simTime, seconds(t));
  simTime.dataset.simTime = isNum(t) ? String(t) : '';

  const frozen = $('frozen');
  const word = sim.frozen ? 'FROZEN' : 'RUNNING';
  setText(frozen, word);
  frozen.className = `badge ${word.toLowerCase()}`;
  frozen.dataset.frozen = String(Boolean(sim.frozen));
  $('freeze').classList.toggle('active', Boolean(sim.frozen));
  $('unfreeze').classList.toggle('active', !sim.frozen);

  const names = Array.isArray(sim.checkpoints) ? sim.checkpoints : [];
  setText($('checkpoints'), names.length ? names.join(', ') : 'none');
  const list = $('checkpoint-list');
  if (list.dataset.names !== names.join('\n')) {
    list.replaceChildren(...names.map((n) => {
      const option = document.createElement('option');
      option.value = n;
      return option;
    }));
    list.dataset.names = names.join('\n');
  }

  const ack = sim.last_ack;
  const el = $('last-ack');
  if (ack) {
    const verdict = ack.accepted ? 'accepted' : 'REFUSED';
    setText(el, `#${ack.seq} ${ack.command}: ${verdict}${ack.detail ? ` — ${ack.detail}` : ''}`);
    el.className = ack.accepted ? 'accepted' : 'refused';
    el.dataset.seq = String(ack.seq);
    el.dataset.command = ack.command;
    el.dataset.accepted = String(Boolean(ack.accepted));
    const waited = pendingCommands.size;
    for (const seq of pendingCommands.keys()) if (seq <= ack.seq) pendingCommands.delete(seq);
    if (waited && !pendingCommands.size) {
      setText($('command-status'), `acknowledged up to #${ack.seq}`);
    }
  }
  if (pendingCommands.size) {
    const waiting = [...pendingCommands].map(([seq, label]) => `#${seq} ${label}`).join(', ');
    setText($('command-status'), `waiting for the acknowledgement of ${waiting}`);
  }
}

async function sendSimCommand(command, withCheckpoint) {
  const body = {command};
  if (withCheckpoint) body.checkpoint = $('checkpoint-name').value.trim() || 'default';
  const status = $('command-status');
  try {
    const {seq} = await postJson('api/sim', body);
    pendingCommands.set(seq, command);
    setText(status, `sent #${seq} ${command}`);
    status.className = '';
  } catch (e) {
    setText(status, `${command} failed: ${e.message}`);
    status.className = 'error';
  }
}

function wireSimButtons() {
  const buttons = {
    'freeze': ['freeze', false],
    'unfreeze': ['unfreeze', false],
    'reset-start': ['reset_start', false],
    'restart-replay': ['restart_replay', false],
    'save-checkpoint': ['save_checkpoint', true],
    'reset-checkpoint': ['reset_checkpoint', true],
  };
  for (const [id, [command, withCheckpoint]] of Object.entries(buttons)) {
    $(id).addEventListener('click', () => sendSimCommand(command, withCheckpoint));
  }
}

// ---- nodes -----------------------------------------------------------------------------------

const nodeRows = new Map();   // name -> tr

function nodeRow(name) {
  let tr = nodeRows.get(name);
  if (!tr) {
    tr = document.createElement('tr');
    tr.dataset.node = name;
    for (const c of ['name', 'state', 'num loop', 'num input', 'num late', 'num rejected',
                     'num glove-lost', 'detail', 'num age']) tr.append(cell(c));
    tr.cells[0].textContent = name;
    nodeRows.set(name, tr);
  }
  return tr;
}

function renderNodes(nodes) {
  const rows = nodes.map((n) => {
    const tr = nodeRow(n.name);
    const alive = Boolean(n.alive);
    tr.className = alive ? 'alive' : 'stale';
    tr.dataset.alive = String(alive);
    tr.dataset.ageS = isNum(n.age_s) ? String(n.age_s) : '';
    const c = tr.cells;
    setText(c[1], n.state || '—');
    c[1].className = `state state-${String(n.state || 'unknown').toLowerCase()}`;
    setText(c[2], fixed(n.loop_rate_hz, 1));
    setText(c[3], fixed(n.input_rate_hz, 1));
    setText(c[4], fixed(n.late_steps, 0));
    setText(c[5], fixed(n.rejected, 0));
    setText(c[6], fixed(n.glove_lost, 0));
    setText(c[7], n.detail || '');
    setText(c[8], isNum(n.age_s) ? `${n.age_s.toFixed(1)} s` : '—');
    return tr;
  });
  const names = new Set(nodes.map((n) => n.name));
  for (const name of nodeRows.keys()) if (!names.has(name)) nodeRows.delete(name);
  placeRows($('nodes').tBodies[0], rows);
}

// ---- hands -----------------------------------------------------------------------------------

function renderHands(hands) {
  const ul = $('hands');
  const key = JSON.stringify(hands);
  if (ul.dataset.key === key) return;
  ul.dataset.key = key;
  ul.replaceChildren(...hands.map((h) => {
    const li = document.createElement('li');
    li.dataset.handId = String(h.hand_id);
    li.dataset.tracking = String(Boolean(h.tracking));
    li.dataset.holding = h.holding || '';
    li.className = h.tracking ? 'tracking' : 'lost';
    const what = h.holding ? `holding ${h.holding}` : 'empty';
    const tracking = h.tracking ? 'tracking' : 'NOT TRACKING';
    li.textContent = `${h.side} hand (${h.hand_id}): ${tracking}, ${what}`;
    return li;
  }));
}

// ---- controls --------------------------------------------------------------------------------

const controlRows = new Map();   // control_id -> tr

// A row's buttons depend on the control's name, kind and positions only; the row is rebuilt
// when those change, otherwise updated in place so a click in flight is never lost.
function controlShape(c) {
  return JSON.stringify([c.name, c.kind, c.positions]);
}

function buildControlRow(c) {
  const tr = document.createElement('tr');
  tr.dataset.controlId = String(c.control_id);
  tr.dataset.shape = controlShape(c);
  tr.dataset.name = c.name;
  const name = cell('name');
  name.textContent = c.name;
  const kind = cell('kind');
  kind.textContent = String(c.kind || '').toLowerCase();
  const set = cell('set');
  (c.positions || []).forEach((p, i) => {
    const b = document.createElement('button');
    b.type = 'button';
    b.className = 'set-position';
    b.dataset.position = String(i);
    b.textContent = p;
    set.append(b);
  });
  tr.append(name, kind, cell('position-name'), cell('num coordinate'), cell('lit-held'), set);
  return tr;
}

function renderControls(controls) {
  const rows = controls.map((c) => {
    let tr = controlRows.get(c.control_id);
    if (!tr || tr.dataset.shape !== controlShape(c)) {
      const fresh = buildControlRow(c);
      if (tr) tr.replaceWith(fresh);
      tr = fresh;
      controlRows.set(c.control_id, tr);
    }
    tr.dataset.position = String(c.position);
    tr.dataset.positionName = c.position_name || '';
    setText(tr.querySelector('.position-name'), c.position_name || '—');
    setText(tr.querySelector('.coordinate'), fixed(c.coordinate, 3));
    const held = isNum(c.held_by) && c.held_by >= 0 ? `held by hand ${c.held_by}` : '';
    const litHeld = tr.querySelector('.lit-held');
    setText(litHeld, [c.lit ? 'LIT' : '', held].filter(Boolean).join(' · ') || '—');
    litHeld.classList.toggle('lit', Boolean(c.lit));
    for (const b of tr.querySelectorAll('button.set-position')) {
      const current = Number(b.dataset.position) === c.position;
      b.classList.toggle('current', current);
      if (current || performance.now() - Number(b.dataset.clickedMs || 0) > PENDING_CLICK_MS) {
        b.classList.remove('pending');
      }
    }
    return tr;
  });
  const ids = new Set(controls.map((c) => c.control_id));
  for (const id of controlRows.keys()) if (!ids.has(id)) controlRows.delete(id);
  placeRows($('controls').tBodies[0], rows);
}

// One listener on the table: buttons may be rebuilt, the listener stays.
function wireControls() {
  $('controls').addEventListener('click', async (ev) => {
    const b = ev.target.closest('button.set-position');
    if (!b) return;
    const tr = b.closest('tr');
    const body = {control_id: Number(tr.dataset.controlId), position: Number(b.dataset.position)};
    const status = $('command-status');
    b.classList.add('pending');
    b.dataset.clickedMs = String(performance.now());
    try {
      const {seq} = await postJson('api/control', body);
      setText(status, `sent #${seq} ${tr.dataset.name} → ${b.textContent}`);
      status.className = '';
    } catch (e) {
      b.classList.remove('pending');
      setText(status, `${tr.dataset.name} → ${b.textContent} failed: ${e.message}`);
      status.className = 'error';
    }
  });
}

// ---- view ------------------------------------------------------------------------------------

let viewCounter = 0;
let viewObjectUrl = null;

function renderViewCaption(view) {
  const caption = $('view-caption');
  if (!view) {
    setText(caption, 'no frame yet');
    caption.dataset.frameSeq = '';
    return;
  }
  caption.dataset.frameSeq = String(view.frame_seq);
  setText(caption, `frame ${view.frame_seq} · sim ${seconds(view.sim_time_s)} · ` +
    `${view.width_px}×${view.height_px} · ${fixed(view.age_s, 1)} s old`);
}

// Fetches the frame itself and shows it from a blob: a failed fetch (503 before the first
// frame, a dropped connection) keeps the last good picture instead of a broken image.
async function refreshView() {
  const started = performance.now();
  const img = $('view');
  try {
    const reply = await request(`view.png?n=${++viewCounter}`);
    if (reply.ok) {
      const url = URL.createObjectURL(await reply.blob());
      await new Promise((done) => { img.onload = img.onerror = done; img.src = url; });
      if (viewObjectUrl) URL.revokeObjectURL(viewObjectUrl);
      viewObjectUrl = url;
      img.dataset.loaded = String(Number(img.dataset.loaded || 0) + 1);
      $('view-figure').classList.remove('no-view');
    } else {
      $('view-figure').classList.add('no-view');
    }
  } catch (e) {
    $('view-figure').classList.add('no-view');
  }
  setTimeout(refreshView, Math.max(0, VIEW_PERIOD_MS - (performance.now() - started)));
}

// ---- events ----------------------------------------------------------------------------------

let eventsAfter = -1;   // the seq of the newest event shown

function addEvents(events) {
  const ul = $('events');
  for (const ev of events) {   // oldest first: each goes on top
    if (ev.seq <= eventsAfter) continue;
    eventsAfter = ev.seq;
    const li = document.createElement('li');
    li.dataset.seq = String(ev.seq);
    li.dataset.kind = ev.kind;
    li.className = `event-${ev.kind}`;
    const time = document.createElement('span');
    time.className = 'time';
    time.textContent = seconds(ev.sim_time_s);
    li.append(time, ` ${ev.text}`);
    ul.prepend(li);
  }
  while (ul.children.length > MAX_EVENTS) ul.lastElementChild.remove();
}

async function pollEvents() {
  let again = false;
  try {
    const reply = await getJson(`api/events?after=${eventsAfter}`);
    const events = Array.isArray(reply.events) ? reply.events : [];
    const next = isNum(reply.next) ? reply.next : eventsAfter + 1;
    if (events.length) {
      addEvents(events);
      again = next - 1 > eventsAfter;          // more than one reply's worth waiting
    } else if (next - 1 < eventsAfter) {       // the station restarted: seqs begin again
      $('events').replaceChildren();
      eventsAfter = -1;
      again = true;
    } else {
      eventsAfter = next - 1;                  // events the station no longer keeps
    }
  } catch (e) { /* the connection indicator tells */ }
  setTimeout(pollEvents, again ? 0 : EVENTS_PERIOD_MS);
}

// ---- the aircraft: gauges, gear lights, annunciators ----------------------------------------------

// The readouts the page shows, if the aircraft has them (config/aircraft.yaml's names).
const GAUGES = [
  {system: 'engine', label: 'engine'},
  {system: 'rpm', label: 'RPM', digits: 0, max: 110},
  {system: 'egt', label: 'EGT', digits: 0, max: 900},
  {system: 'fuel_flow', label: 'fuel flow', digits: 1, max: 70},
  {system: 'flap_deg', label: 'flaps', digits: 0, max: 40},
  {system: 'heading_bug_deg', label: 'hdg bug', digits: 0},
  {system: 'bus', label: 'bus', words: ['off', 'on']},
];

function renderSystems(systems) {
  const time = $('systems-time');
  if (!systems || !systems.values) {
    setText(time, 'no systems node');
    time.dataset.simTime = '';
    return;
  }
  setText(time, `at ${seconds(systems.sim_time_s)}`);
  time.dataset.simTime = isNum(systems.sim_time_s) ? String(systems.sim_time_s) : '';
  const values = systems.values;
  const box = $('gauges');
  for (const g of GAUGES) {
    const v = values[g.system];
    if (!v) continue;
    let el = box.querySelector(`[data-system="${CSS.escape(g.system)}"]`);
    if (!el) {
      el = document.createElement('div');
      el.className = 'gauge';
      el.dataset.system = g.system;
      el.innerHTML = '<span class="label"></span><span class="value"></span><span class="bar"><span></span></span>';
      el.querySelector('.label').textContent = g.label;
      box.append(el);
    }
    let text = '—';
    if (v.state) text = v.state;
    else if (g.words && isNum(v.value)) text = g.words[v.value ? 1 : 0];
    else if (isNum(v.value)) text = `${v.value.toFixed(g.digits || 0)}${v.unit ? ' ' + v.unit : ''}`;
    setText(el.querySelector('.value'), text);
    el.dataset.value = isNum(v.value) ? String(v.value) : '';
    const fill = el.querySelector('.bar span');
    fill.style.width = g.max && isNum(v.value) ? `${Math.max(0, Math.min(100, 100 * v.value / g.max))}%` : '0';
  }
  const lamp = (id, on, colour) => {
    const el = $(id);
    const word = on ? colour : 'off';
    el.dataset.lamp = word;
    el.className = `lamp ${word}` + (id === 'master-caution' ? ' caution' : id === 'gear-horn' ? ' warning' : '');
  };
  const lit = (name) => values[name] && values[name].value > 0;
  for (const leg of ['nose', 'left', 'right']) {
    const red = lit(`gear_red_${leg}`);
    lamp(`gear-${leg}`, red || lit(`gear_green_${leg}`), red ? 'red' : 'green');
  }
  lamp('master-caution', lit('master_caution_light'), 'amber');
  lamp('gear-horn', lit('gear_horn'), 'red');
  const ul = $('annunciators');
  const lights = Object.keys(values).filter((n) => n.startsWith('ann_'));
  const items = lights.map((n) => {
    let li = ul.querySelector(`[data-system="${CSS.escape(n)}"]`);
    if (!li) {
      li = document.createElement('li');
      li.dataset.system = n;
      li.textContent = n.slice(4).replace(/_/g, ' ').toUpperCase();
    }
    li.classList.toggle('lit', lit(n));
    return li;
  });
  placeRows(ul, items);
}

// ---- failures --------------------------------------------------------------------------------

const failureRows = new Map();   // name -> tr

function renderFailures(failures) {
  const rows = failures.map((f) => {
    let tr = failureRows.get(f.name);
    if (!tr) {
      tr = document.createElement('tr');
      tr.dataset.failure = f.name;
      const name = cell();
      name.textContent = f.text || f.name;
      name.title = f.name;
      const state = cell('state');
      const buttons = cell();
      for (const [cls, label, inserted] of [['insert', 'Insert', true], ['clear', 'Clear', false]]) {
        const b = document.createElement('button');
        b.type = 'button';
        b.className = cls;
        b.textContent = label;
        b.addEventListener('click', () => sendFailure(f.name, inserted));
        buttons.append(b);
      }
      tr.append(name, state, buttons);
      failureRows.set(f.name, tr);
    }
    tr.dataset.inserted = f.inserted ? 'true' : 'false';
    tr.classList.toggle('inserted', !!f.inserted);
    setText(tr.querySelector('.state'), f.inserted ? 'INSERTED' : 'clear');
    return tr;
  });
  placeRows($('failures').querySelector('tbody'), rows);
}

async function sendFailure(name, inserted) {
  const status = $('failure-status');
  try {
    const reply = await postJson('api/failure', {failure: name, inserted});
    setText(status, `${inserted ? 'insert' : 'clear'} ${name}: sent (#${reply.seq})`);
  } catch (e) {
    setText(status, `${inserted ? 'insert' : 'clear'} ${name}: ${e.message}`);
  }
}

// ---- procedures ------------------------------------------------------------------------------

function stepFlags(step) {
  return ['out_of_order', 'late', 'undone'].filter((k) => step[k]).join(' ');
}

function renderProcedures(procedures) {
  const list = (procedures && procedures.list) || [];
  setText($('lesson'), procedures && procedures.lesson ? procedures.lesson : 'no lesson');
  const box = $('procedures');
  const blocks = list.map((p) => {
    let div = box.querySelector(`.procedure[data-name="${CSS.escape(p.name)}"]`);
    if (!div) {
      div = document.createElement('div');
      div.className = 'procedure';
      div.dataset.name = p.name;
      div.innerHTML = '<h3><span class="title"></span> <span class="badge"></span> <span class="errors"></span></h3><ol class="steps"></ol>';
      setText(div.querySelector('.title'), p.title);
    }
    div.dataset.state = p.state;
    div.dataset.errors = String(p.errors);
    div.dataset.startedS = isNum(p.started_s) ? String(p.started_s) : '';
    const badge = div.querySelector('.badge');
    setText(badge, p.state);
    badge.className = `badge ${p.state}`;
    setText(div.querySelector('.errors'), p.state === 'waiting' ? '' :
      `${p.errors} error${p.errors === 1 ? '' : 's'}` + (isNum(p.started_s) && isNum(p.ended_s) ?
        ` · ${(p.ended_s - p.started_s).toFixed(1)} s` : ''));
    const ol = div.querySelector('.steps');
    const items = p.steps.map((st, i) => {
      const li = ol.children[i] || document.createElement('li');
      li.className = `step ${st.status}`;
      li.dataset.status = st.status;
      li.dataset.flags = stepFlags(st);
      const when = st.status === 'done' && isNum(st.done_s) ?
        ` — ${st.done_s.toFixed(2)} s (+${isNum(st.since_previous_s) ? st.since_previous_s.toFixed(2) : '?'} s)` : '';
      const flags = stepFlags(st) ? ` [${stepFlags(st).replace(/_/g, ' ')}]` : '';
      setText(li, `${st.item}: ${st.action} — ${st.status}${when}${flags}`);
      return li;
    });
    placeRows(ol, items);
    return div;
  });
  placeRows(box, blocks);
}

// ---- state polling ---------------------------------------------------------------------------

async function pollState() {
  try {
    const state = await getJson('api/state');
    renderSim(state.sim || {});
    renderNodes(state.nodes || []);
    renderHands(state.hands || []);
    renderControls(state.controls || []);
    renderViewCaption(state.view);
    renderSystems(state.systems);
    renderFailures(state.failures || []);
    renderProcedures(state.procedures);
    lastStateOkMs = performance.now();
  } catch (e) {
    lastStateError = e.message;
    console.error('api/state:', e);
  }
  renderConn();
  setTimeout(pollState, STATE_PERIOD_MS);
}

wireSimButtons();
wireControls();
setInterval(renderConn, STATE_PERIOD_MS);   // turns "disconnected" even while a poll hangs
pollState();
pollEvents();
refreshView();
