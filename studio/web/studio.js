// Placeholder page of the studio: asks the server for its health and the layout's summary and
// previews a random trajectory. The real front end (three.js) replaces this file.
'use strict';

async function getJson(url, options) {
  const res = await fetch(url, options);
  const body = await res.json();
  if (!res.ok) throw new Error(body.error || `HTTP ${res.status}`);
  return body;
}

function fillTable(table, rows) {
  const tbody = document.createElement('tbody');
  for (const [key, value] of rows) {
    const tr = tbody.insertRow();
    tr.insertCell().textContent = key;
    tr.insertCell().textContent = value;
  }
  table.replaceChildren(tbody);
}

function showError(element, err) {
  element.textContent = err.message;
  element.className = 'error';
}

async function showHealth() {
  const p = document.getElementById('health');
  try {
    const h = await getJson('/api/health');
    p.textContent = `server ${h.status}, version ${h.version}, up ${h.uptime_s} s`;
  } catch (err) {
    showError(p, err);
  }
}

async function showLayout() {
  const table = document.getElementById('layout');
  try {
    const l = await getJson('/api/layout');
    const b = l.bounds;
    const fmt = (v) => v.map((x) => x.toFixed(2)).join(', ');
    fillTable(table, [
      ['name', l.name],
      ['source', l.source],
      ['objects', `${l.objects} parts in ${l.instances} instances`],
      ['triangles', l.triangles],
      ['bounds (m)', `min (${fmt(b.min)}), max (${fmt(b.max)})`],
      ['rooms', l.rooms.map((r) => `${r.type} ${r.area_m2.toFixed(1)} m²`).join(', ') || 'none'],
      ['classes', l.classes.map((c) => `${c.name} ${c.instances}`).join(', ')],
      ['free volume', l.free_space ? `${l.free_space.free_volume_m3.toFixed(1)} m³` : '?'],
    ]);
  } catch (err) {
    fillTable(table, [['error', err.message]]);
  }
}

async function preview() {
  const out = document.getElementById('trajectory');
  out.className = '';
  out.textContent = 'computing…';
  const request = {
    type: document.getElementById('type').value,
    frames: Number(document.getElementById('frames').value),
    seed: Number(document.getElementById('seed').value),
  };
  try {
    const t = await getJson('/api/trajectory/preview', {
      method: 'POST',
      headers: {'Content-Type': 'application/json'},
      body: JSON.stringify(request),
    });
    const last = t.poses[t.poses.length - 1].position.map((x) => x.toFixed(2)).join(', ');
    out.textContent = `${t.poses.length} poses (${t.type}, v_mult ${t.v_mult.toFixed(2)}, ` +
        `w_mult ${t.w_mult.toFixed(2)}) in ${t.compute_ms} ms; last position (${last})`;
  } catch (err) {
    showError(out, err);
  }
}

document.getElementById('preview').addEventListener('click', preview);
showHealth();
showLayout();
