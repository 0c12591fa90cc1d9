#!/usr/bin/env python3
"""Plots `bench_intersection` as an SVG: CPU time against achieved error, per peer.

Reads the bench's `ssi-csv,pair,eps,peer,outcome,cpu_ms,curves,true,on_surface,coverage`
lines on stdin and writes the SVG to the path given. One panel per named pair and one
for the random pairs together; achieved error is the larger of the two measures
(points off either surface, oracle curve not covered), relative to the pair's size.
A run that did not return, or missed a curve (infinite error), is drawn in the "failed"
column at the right. Python's standard library only.
"""
import math
import sys

PEERS = [("argil", "#1f77b4"), ("argil-warm", "#17becf"), ("occt", "#d62728"),
         ("sisl", "#2ca02c")]
PANEL_W, PANEL_H = 330, 300
LEFT, RIGHT, TOP, BOTTOM = 60, 40, 40, 50
X_LO, X_HI = 1e-15, 1e-2  # achieved error / size
Y_LO, Y_HI = 0.1, 1e4     # [ms]


def read_rows(lines):
    rows = []
    for line in lines:
        if not line.startswith("ssi-csv,"):
            continue
        f = line.strip().split(",")
        rows.append({"pair": f[1], "eps": f[2], "peer": f[3], "returned": f[4] == "returned",
                     "ms": float(f[5]), "curves": int(f[6]), "true": int(f[7]),
                     "error": max(float(f[8]), float(f[9]))})
    return rows


def panel(out, x0, title, rows):
    w, h = PANEL_W - LEFT - RIGHT, PANEL_H - TOP - BOTTOM
    fail_x = x0 + LEFT + w + 18

    def px(err):
        if not math.isfinite(err):
            return fail_x
        err = min(max(err, X_LO), X_HI)
        return x0 + LEFT + w * (math.log10(err) - math.log10(X_LO)) / (
            math.log10(X_HI) - math.log10(X_LO))

    def py(ms):
        ms = min(max(ms, Y_LO), Y_HI)
        return TOP + h - h * (math.log10(ms) - math.log10(Y_LO)) / (
            math.log10(Y_HI) - math.log10(Y_LO))

    out.append(f'<text x="{x0 + LEFT + w / 2}" y="{TOP - 14}" text-anchor="middle" '
               f'font-weight="bold">{title}</text>')
    for e in range(-15, -1, 3):
        x = px(10.0 ** e)
        out.append(f'<line x1="{x:.1f}" y1="{TOP}" x2="{x:.1f}" y2="{TOP + h}" stroke="#ddd"/>')
        out.append(f'<text x="{x:.1f}" y="{TOP + h + 16}" text-anchor="middle">1e{e}</text>')
    out.append(f'<text x="{fail_x:.1f}" y="{TOP + h + 16}" text-anchor="middle">failed</text>')
    for ms, label in [(0.1, "0.1"), (1, "1"), (10, "10"), (100, "100"), (1000, "1000"),
                      (10000, "1e4")]:
        y = py(ms)
        out.append(f'<line x1="{x0 + LEFT}" y1="{y:.1f}" x2="{x0 + LEFT + w}" y2="{y:.1f}" '
                   'stroke="#ddd"/>')
        out.append(f'<text x="{x0 + LEFT - 6}" y="{y + 4:.1f}" text-anchor="end">{label}</text>')
    out.append(f'<rect x="{x0 + LEFT}" y="{TOP}" width="{w}" height="{h}" fill="none" '
               'stroke="#888"/>')
    out.append(f'<text x="{x0 + LEFT + w / 2}" y="{TOP + h + 36}" text-anchor="middle">'
               'achieved error / size</text>')
    for peer, colour in PEERS:
        mine = [r for r in rows if r["peer"] == peer]
        for pair in sorted({r["pair"] for r in mine}):
            line = [r for r in mine if r["pair"] == pair and r["returned"] and
                    math.isfinite(r["error"])]
            pts = " ".join(f'{px(r["error"]):.1f},{py(r["ms"]):.1f}' for r in line)
            if len(line) > 1:
                out.append(f'<polyline points="{pts}" fill="none" stroke="{colour}" '
                           'stroke-opacity="0.6"/>')
        for r in mine:
            ms = r["ms"] if r["returned"] else Y_HI
            x, y = px(r["error"] if r["returned"] else math.inf), py(ms)
            missed = r["returned"] and r["curves"] != r["true"]
            fill = "none" if missed else colour
            out.append(f'<circle cx="{x:.1f}" cy="{y:.1f}" r="3.5" fill="{fill}" '
                       f'stroke="{colour}" stroke-width="1.5"/>')


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: bench_intersection | plot_intersection.py out.svg")
    rows = read_rows(sys.stdin)
    if not rows:
        sys.exit("plot_intersection.py: no ssi-csv lines on stdin")
    named = [p for p in dict.fromkeys(r["pair"] for r in rows) if not p.startswith("random")]
    groups = [(p, [r for r in rows if r["pair"] == p]) for p in named]
    random_rows = [r for r in rows if r["pair"].startswith("random")]
    if random_rows:
        count = len({r["pair"] for r in random_rows})
        groups.append((f"{count} random graph pairs", random_rows))
    width = PANEL_W * len(groups) + 20
    height = PANEL_H + 60
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           'font-family="sans-serif" font-size="11">',
           f'<rect width="{width}" height="{height}" fill="white"/>',
           f'<text x="14" y="{TOP + (PANEL_H - TOP - BOTTOM) / 2}" text-anchor="middle" '
           f'transform="rotate(-90 14 {TOP + (PANEL_H - TOP - BOTTOM) / 2})">CPU time [ms]</text>']
    for k, (title, group) in enumerate(groups):
        panel(out, 10 + PANEL_W * k, title, group)
    y = PANEL_H + 20
    for k, (peer, colour) in enumerate(PEERS):
        x = LEFT + 150 * k
        out.append(f'<circle cx="{x}" cy="{y}" r="4" fill="{colour}"/>')
        out.append(f'<text x="{x + 10}" y="{y + 4}">{peer}</text>')
    out.append(f'<text x="{LEFT}" y="{y + 24}">one point per eps (1e-3 to 1e-8 of the size); '
               'hollow: wrong curve count; "failed": no return within the limit, or a curve '
               'missed</text>')
    out.append("</svg>")
    with open(sys.argv[1], "w", encoding="utf-8") as f:
        f.write("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
