#!/usr/bin/env python3
"""Plots the size table of `bench_haptic_loop N scale` as an SVG.

Reads the bench's output (its `scale-csv,name,poles,p50,p99,p999,max` lines, times
in microseconds) on stdin and writes the SVG to the path given: tick CPU time
(p50, p99.9, worst) against the control points the scene holds, log-log, with
the 1 ms haptic budget. Python's standard library only.
"""
import math
import sys

WIDTH, HEIGHT = 720, 420
LEFT, RIGHT, TOP, BOTTOM = 70, 200, 30, 60
SERIES = [("p50", 3, "#1f77b4"), ("p99.9", 5, "#d62728"), ("worst tick", 6, "#7f7f7f")]


def read_rows(lines):
    rows = []
    for line in lines:
        if not line.startswith("scale-csv,"):
            continue
        fields = line.strip().split(",")
        numbers = [float(x) for x in fields[-5:]]  # a name may hold commas
        rows.append((",".join(fields[1:-5]), numbers[0]) + tuple(numbers[1:]))
    return rows


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: bench_haptic_loop 2000 scale | plot_scale.py out.svg")
    rows = read_rows(sys.stdin)
    if not rows:
        sys.exit("plot_scale.py: no scale-csv lines on stdin")
    x_lo, x_hi = 1e2, 1e7
    y_lo, y_hi = 100.0, 1e4  # [us]

    def px(poles):
        return LEFT + (WIDTH - LEFT - RIGHT) * (math.log10(poles) - math.log10(x_lo)) / (
            math.log10(x_hi) - math.log10(x_lo))

    def py(us):
        us = min(max(us, y_lo), y_hi)
        return HEIGHT - BOTTOM - (HEIGHT - TOP - BOTTOM) * (math.log10(us) - math.log10(y_lo)) / (
            math.log10(y_hi) - math.log10(y_lo))

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{HEIGHT}" '
           f'font-family="sans-serif" font-size="12">',
           f'<rect width="{WIDTH}" height="{HEIGHT}" fill="white"/>']
    for e in range(2, 8):
        x = px(10 ** e)
        out.append(f'<line x1="{x:.1f}" y1="{TOP}" x2="{x:.1f}" y2="{HEIGHT - BOTTOM}" stroke="#ddd"/>')
        out.append(f'<text x="{x:.1f}" y="{HEIGHT - BOTTOM + 16}" text-anchor="middle">1e{e}</text>')
    for us, label in [(100, "0.1 ms"), (1000, "1 ms"), (10000, "10 ms")]:
        y = py(us)
        style = 'stroke="#2ca02c" stroke-dasharray="6 3"' if us == 1000 else 'stroke="#ddd"'
        out.append(f'<line x1="{LEFT}" y1="{y:.1f}" x2="{WIDTH - RIGHT}" y2="{y:.1f}" {style}/>')
        out.append(f'<text x="{LEFT - 6}" y="{y + 4:.1f}" text-anchor="end">{label}</text>')
    out.append(f'<text x="{(LEFT + WIDTH - RIGHT) / 2}" y="{HEIGHT - 18}" text-anchor="middle">'
               'control points in the scene</text>')
    out.append(f'<text x="16" y="{(TOP + HEIGHT - BOTTOM) / 2}" text-anchor="middle" '
               f'transform="rotate(-90 16 {(TOP + HEIGHT - BOTTOM) / 2})">tick CPU time</text>')
    for name, column, colour in SERIES:
        for row in rows:
            x, y = px(row[1]), py(row[column - 1])
            shape = "circle" if not row[0].startswith("one face") else "rect"
            if shape == "circle":
                out.append(f'<circle cx="{x:.1f}" cy="{y:.1f}" r="4" fill="{colour}"/>')
            else:
                out.append(f'<rect x="{x - 4:.1f}" y="{y - 4:.1f}" width="8" height="8" '
                           f'fill="none" stroke="{colour}" stroke-width="2"/>')
    legend_x = WIDTH - RIGHT + 16
    for k, (name, _, colour) in enumerate(SERIES):
        y = TOP + 10 + 18 * k
        out.append(f'<circle cx="{legend_x}" cy="{y}" r="4" fill="{colour}"/>')
        out.append(f'<text x="{legend_x + 10}" y="{y + 4}">{name}</text>')
    y = TOP + 10 + 18 * len(SERIES) + 10
    out.append(f'<circle cx="{legend_x}" cy="{y}" r="4" fill="#000"/>')
    out.append(f'<text x="{legend_x + 10}" y="{y + 4}">many faces / a CAD part</text>')
    out.append(f'<rect x="{legend_x - 4}" y="{y + 14}" width="8" height="8" fill="none" '
               'stroke="#000" stroke-width="2"/>')
    out.append(f'<text x="{legend_x + 10}" y="{y + 22}">one face</text>')
    out.append(f'<text x="{legend_x - 4}" y="{y + 44}">dashed: 1 kHz budget</text>')
    out.append("</svg>")
    with open(sys.argv[1], "w", encoding="utf-8") as f:
        f.write("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
