// The force on the device against time, drawn on a 2D canvas, with a cursor
// at the timeline's tick.

export class ForcePlot {
  constructor(canvas, run) {
    this.canvas = canvas;
    this.run = run;
    const n = run.time.length;
    this.magnitude = new Float32Array(n);
    let peak = 0;
    for (let k = 0; k < n; ++k) {
      const f = Math.hypot(run.force[3 * k], run.force[3 * k + 1], run.force[3 * k + 2]);
      this.magnitude[k] = f;
      peak = Math.max(peak, f);
    }
    this.peak = peak > 0 ? peak : 1;
    this.duration = n > 1 ? run.time[n - 1] : 1;
  }

  draw(tick) {
    const { canvas, run, magnitude } = this;
    const g = canvas.getContext("2d");
    const w = canvas.width, h = canvas.height, pad = 28;
    g.clearRect(0, 0, w, h);
    g.fillStyle = "#1d2026";
    g.fillRect(0, 0, w, h);
    const x = (t) => pad + ((w - 2 * pad) * t) / this.duration;
    const y = (f) => h - 16 - ((h - 30) * f) / this.peak;
    g.strokeStyle = "#555c66";
    g.strokeRect(pad, 14, w - 2 * pad, h - 30);
    g.fillStyle = "#aab";
    g.font = "11px sans-serif";
    g.fillText(`${Number(this.peak.toPrecision(3))} N`, 2, 12);
    g.fillText(`${Number(this.duration.toPrecision(3))} s`, w - pad - 20, h - 2);
    g.strokeStyle = "#f0a030";
    g.beginPath();
    const step = Math.max(1, Math.floor(magnitude.length / (w - 2 * pad)));
    for (let k = 0; k < magnitude.length; k += step) {
      // The largest force in each pixel column, so no peak is lost.
      let f = 0;
      for (let j = k; j < Math.min(k + step, magnitude.length); ++j) f = Math.max(f, magnitude[j]);
      if (k === 0) g.moveTo(x(run.time[k]), y(f));
      else g.lineTo(x(run.time[k]), y(f));
    }
    g.stroke();
    if (tick >= 0 && tick < magnitude.length) {
      g.strokeStyle = "#e8e8e8";
      g.beginPath();
      g.moveTo(x(run.time[tick]), 14);
      g.lineTo(x(run.time[tick]), h - 16);
      g.stroke();
      g.fillStyle = "#e8e8e8";
      g.fillText(`${Number(magnitude[tick].toPrecision(3))} N`, x(run.time[tick]) + 3, 26);
    }
  }
}
