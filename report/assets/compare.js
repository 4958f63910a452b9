
(function () {
  const data = JSON.parse(document.getElementById('compare-data').textContent);
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
  function describe(run, d) {
    let h = '<b>' + esc(run.label) + ': ' + esc(d.id) + '</b>' +
        (d.id === run.knee ? ' (knee)' : '') +
        (d.feasible ? '' : ' <span class="bad">infeasible</span>') + '<table>';
    h += '<tr><td colspan="2" class="sec">objectives</td></tr>';
    run.objectives.forEach(function (o, k) {
      h += row(o.name + ' (' + (o.sense === 'maximize' ? 'max' : 'min') + ')', d.objectives[k],
               o.unit);
    });
    h += '<tr><td colspan="2" class="sec">parameters</td></tr>';
    run.parameters.forEach(function (p, k) { h += row(p.name, d.parameters[k], p.unit); });
    h += row('home_height', d.home_height, 'm');
    return h + '</table>';
  }
  document.querySelectorAll('path.mk').forEach(function (e) {
    const run = data.runs[+e.getAttribute('data-run')];
    const id = e.getAttribute('data-id');
    const design = run.designs.find(function (d) { return d.id === id; });
    e.addEventListener('mouseenter', function () {
      tip.innerHTML = describe(run, design);
      tip.style.display = 'block';
      e.classList.add('hl');
    });
    e.addEventListener('mousemove', function (ev) {
      tip.style.left = (ev.pageX + 14) + 'px';
      tip.style.top = (ev.pageY + 14) + 'px';
    });
    e.addEventListener('mouseleave', function () {
      tip.style.display = 'none';
      e.classList.remove('hl');
    });
  });
  document.querySelectorAll('g.legend').forEach(function (e) {
    e.addEventListener('click', function () {
      const r = e.getAttribute('data-run');
      const off = !e.classList.contains('off');
      e.classList.toggle('off', off);
      document.querySelectorAll('g.run[data-run="' + r + '"]').forEach(function (g) {
        g.classList.toggle('off', off);
      });
    });
  });
})();
