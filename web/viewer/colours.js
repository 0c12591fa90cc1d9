// The signed deviation colour map: blue where the surface moved in (against
// its outward normal), red where it moved out, on a scale symmetric about 0;
// movements within eps keep the neutral surface colour.

export const NEUTRAL = [0.8, 0.76, 0.68];
const IN = [0.13, 0.35, 0.85];
const OUT = [0.85, 0.16, 0.12];

/// RGB in [0, 1] of a signed displacement d [mm].
export function deviationColour(d, scale, eps) {
  if (!(scale > 0) || Math.abs(d) <= eps) return NEUTRAL;
  const s = Math.min(Math.abs(d) / scale, 1);
  const to = d < 0 ? IN : OUT;
  return NEUTRAL.map((c, i) => c + (to[i] - c) * s);
}

const css = (rgb) => `rgb(${rgb.map((c) => Math.round(c * 255)).join(",")})`;

/// The legend's gradient (CSS), from -scale on the left to +scale.
export function legendGradient() {
  return `linear-gradient(to right, ${css(IN)}, ${css(NEUTRAL)}, ${css(OUT)})`;
}

/// A length for the legend: 3 significant digits.
export function mm(x) {
  return `${Number(x.toPrecision(3))} mm`;
}
