// The measurements panel (bottom right; shown only when the scenario has "measurements"): per
// measurement line its flow and specific flow over the last 10 s and how many crossed, per
// measurement area its classic density and mean speed, with a small live fundamental diagram
// (speed against density, one dot per simulated second, the latest largest) — the numbers of
// crowd/measure.js, redrawn at most twice a second. ▾ folds it.
const kDensityAxis = 6;  // [1/m²] the diagram's x range
const kSpeedAxis = 2;    // [m/s] its y range

function drawDiagram(canvas, samples) {
  const g = canvas.getContext('2d');
  const w = canvas.width, h = canvas.height, pad = 14;
  g.clearRect(0, 0, w, h);
  g.strokeStyle = '#889'; g.lineWidth = 1;
  g.beginPath(); g.moveTo(pad, 2); g.lineTo(pad, h - pad); g.lineTo(w - 2, h - pad); g.stroke();
  g.fillStyle = '#556'; g.font = '9px sans-serif';
  g.fillText(`${kDensityAxis} /m²`, w - 34, h - 3);
  g.fillText(`${kSpeedAxis} m/s`, pad + 3, 10);
  samples.forEach((s, i) => {
    const x = pad + Math.min(s.density / kDensityAxis, 1) * (w - pad - 4);
    const y = h - pad - Math.min(s.speed / kSpeedAxis, 1) * (h - pad - 4);
    const last = i === samples.length - 1;
    g.fillStyle = last ? '#8a3ab9' : 'rgba(138, 58, 185, 0.35)';
    g.beginPath(); g.arc(x, y, last ? 3.5 : 2, 0, 2 * Math.PI); g.fill();
  });
}

export class MeasurePanel {
  /** el: the panel's element; measurements: a crowd/measure.js Measurements. */
  constructor(el, measurements) {
    this.el = el;
    this.measurements = measurements;
    this.lastDraw = -Infinity;
    this.folded = false;
    el.classList.toggle('hidden', measurements.size === 0);
    el.innerHTML = '';
    const head = document.createElement('div');
    head.className = 'legend-head';
    head.innerHTML = '<span>Measurements</span>';
    const fold = document.createElement('button');
    fold.className = 'fold';
    fold.textContent = '▾';
    fold.title = 'fold';
    fold.onclick = () => { this.folded = !this.folded; this.body.classList.toggle('hidden', this.folded); fold.textContent = this.folded ? '▸' : '▾'; };
    head.appendChild(fold);
    el.appendChild(head);
    this.body = document.createElement('div');
    el.appendChild(this.body);
    this.rows = measurements.rows().map((r) => {
      const row = document.createElement('div');
      row.className = 'measure-row';
      const label = document.createElement('div');
      label.innerHTML = `<b>${r.id}</b> <span class="small">${r.kind}</span>`;
      const value = document.createElement('div');
      value.className = 'measure-value';
      row.append(label, value);
      let canvas = null;
      if (r.kind === 'area') {
        canvas = document.createElement('canvas');
        canvas.width = 200; canvas.height = 90;
        canvas.className = 'measure-fd';
        canvas.title = 'fundamental diagram: mean speed against classic density, one dot per simulated second';
        row.appendChild(canvas);
      }
      this.body.appendChild(row);
      return { value, canvas };
    });
  }

  /** Redraws (at most every 0.5 s of wall time, nowMs from performance.now()). */
  update(nowMs) {
    if (this.measurements.size === 0 || this.folded || nowMs - this.lastDraw < 500) return;
    this.lastDraw = nowMs;
    this.measurements.rows().forEach((r, i) => {
      this.rows[i].value.textContent = r.text;
      if (this.rows[i].canvas) drawDiagram(this.rows[i].canvas, r.meter.fd);
    });
  }
}
