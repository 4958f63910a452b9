
(function () {
  const data = JSON.parse(document.getElementById('report-data').textContent);
  const byId = {};
  data.designs.forEach(function (d) { byId[d.id] = d; });
  const homeIsParameter = data.parameters.some(function (p) { return p.name === 'home_height'; });
  const tip = document.getElementById('tip');
  function esc(s) {
    return String(s).replace(/[&<>"]/g, function (c) {
      return {'&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;'}[c];
    });
  }
  function num(v) {
    if (v === null || v === undefined) return '-';
    const a = Math.abs(v);
    return (a !== 0 && (a >= 1e5 || a < 1e-3)) ? v.toExponential(4) : String(+v.toPrecision(6));
  }
  function row(name, value, unit) {
    return '<tr><th>' + esc(name) + '</th><td>' + num(value) + (unit ? ' ' + esc(unit) : '') +
        '</td></tr>';
  }
  function section(title) { return '<tr><td colspan="2" class="sec">' + title + '</td></tr>'; }
  function describe(d) {
    let h = '<b>' + esc(d.id) + '</b>' + (d.id === data.knee ? ' (knee)' : '') +
        (d.feasible ? '' : ' <span class="bad">infeasible</span>') + '<table>';
    h += section('parameters');
    data.parameters.forEach(function (p) { h += row(p.name, d.parameters[p.name], p.unit); });
    if (!homeIsParameter) h += row('home_height', d.home_height, 'm');
    h += section('objectives');
    data.objectives.forEach(function (o) {
      h += row(o.name + ' (' + (o.sense === 'maximize' ? 'max' : 'min') + ')',
               d.objectives[o.name], o.unit);
    });
    if (data.constraints.length > 0) {
      h += section('constraints (g &le; 0 satisfied)');
      data.constraints.forEach(function (c) { h += row(c.name, d.constraints[c.name], c.unit); });
    }
    if (d.actuator !== undefined) {
      h += section('actuator');
      h += d.actuator ? '<tr><th>' + esc(d.actuator.name) + '</th><td>' +
              num(d.actuator.max_force) + ' N, ' + num(d.actuator.stroke) + ' m</td></tr>'
                      : '<tr><td colspan="2" class="bad">no entry carries the legs</td></tr>';
    }
    return h + '</table>';
  }
  function mark(id, on) {
    document.querySelectorAll('[data-id="' + id + '"]').forEach(function (e) {
      e.classList.toggle('hl', on);
    });
  }
  document.querySelectorAll('[data-id]').forEach(function (e) {
    const id = e.getAttribute('data-id');
    e.addEventListener('mouseenter', function () {
      if (!byId[id]) return;
      tip.innerHTML = describe(byId[id]);
      tip.style.display = 'block';
      mark(id, true);
    });
    e.addEventListener('mousemove', function (ev) {
      tip.style.left = (ev.pageX + 14) + 'px';
      tip.style.top = (ev.pageY + 14) + 'px';
    });
    e.addEventListener('mouseleave', function () {
      tip.style.display = 'none';
      mark(id, false);
    });
  });
})();
