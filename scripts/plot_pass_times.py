#!/usr/bin/env python3
"""Per-pass GPU times from `bounce render --timings` files: a Markdown table and a stacked-bar SVG.

    scripts/plot_pass_times.py --svg docs/images/gi-pass-times.svg --prefix cache- --prefix gi- \
        sunroom-mobile=out/sunroom-mobile.json sunroom-desktop=out/sunroom-desktop.json ...

Each bar is one run (label=file); its segments are the median milliseconds of each pass over the
run's frames after --skip warm-up frames. Only passes whose names start with one of the --prefix
values are kept (all passes without --prefix). The table goes to standard output. Needs only the
Python standard library, so it runs anywhere the timings land.
"""
import argparse
import json
import statistics
import sys
from xml.sax.saxutils import escape

# Distinct, colour-blind-friendly hues (Okabe-Ito, then Tableau), cycled if there are more passes.
PALETTE = ["#0072B2", "#E69F00", "#009E73", "#D55E00", "#CC79A7", "#56B4E9", "#F0E442",
           "#4E79A7", "#F28E2B", "#59A14F", "#E15759", "#B07AA1", "#76B7B2", "#EDC948",
           "#9C755F", "#BAB0AC"]


def load_run(spec, prefixes, skip):
    label, sep, path = spec.partition("=")
    if not sep:
        sys.exit(f"{spec}: expected LABEL=FILE.json")
    try:
        with open(path) as f:
            data = json.load(f)
        timings = data["timings"]
    except (OSError, ValueError, KeyError) as error:
        sys.exit(f"{path}: not a `bounce render --timings` file ({error})")
    per_pass = {}
    order = []
    for row in timings:
        name = row["pass"]
        if row["frame"] < skip or name.startswith("debug-view"):
            continue
        if prefixes and not any(name.startswith(p) for p in prefixes):
            continue
        if name not in per_pass:
            per_pass[name] = []
            order.append(name)
        per_pass[name].append(row["ms"])
    medians = {name: statistics.median(values) for name, values in per_pass.items()}
    return {"label": label, "device": data.get("device", "?"), "order": order,
            "medians": medians, "width": data.get("width"), "height": data.get("height")}


def markdown_table(runs, passes):
    header = "| pass | " + " | ".join(r["label"] for r in runs) + " |"
    lines = [header, "|---|" + "---:|" * len(runs)]
    for name in passes:
        cells = [f"{r['medians'][name]:.3f}" if name in r["medians"] else "-" for r in runs]
        lines.append(f"| `{name}` | " + " | ".join(cells) + " |")
    totals = [f"**{sum(r['medians'].values()):.3f}**" for r in runs]
    lines.append("| **total** | " + " | ".join(totals) + " |")
    return "\n".join(lines)


def svg_chart(runs, passes, title):
    bar_height, gap, left, right, top = 22, 10, 170, 90, 40
    legend_rows = (len(passes) + 2) // 3
    chart_width = 560
    height = top + len(runs) * (bar_height + gap) + 40 + legend_rows * 18
    width = left + chart_width + right
    longest = max(sum(r["medians"].values()) for r in runs) or 1.0
    scale = chart_width / longest
    colour = {name: PALETTE[i % len(PALETTE)] for i, name in enumerate(passes)}
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'font-family="sans-serif" font-size="12">',
           f'<rect width="{width}" height="{height}" fill="white"/>',
           f'<text x="{left}" y="22" font-size="14">{escape(title)}</text>']
    y = top
    for run in runs:
        out.append(f'<text x="{left - 8}" y="{y + 15}" text-anchor="end">{escape(run["label"])}</text>')
        x = float(left)
        for name in passes:
            ms = run["medians"].get(name, 0.0)
            w = ms * scale
            if w > 0:
                out.append(f'<rect x="{x:.1f}" y="{y}" width="{w:.1f}" height="{bar_height}" '
                           f'fill="{colour[name]}"><title>{escape(name)}: {ms:.3f} ms</title></rect>')
            x += w
        total = sum(run["medians"].values())
        out.append(f'<text x="{x + 6:.1f}" y="{y + 15}">{total:.3f} ms</text>')
        y += bar_height + gap
    y += 14
    for i, name in enumerate(passes):
        lx = left + (i % 3) * 200
        ly = y + (i // 3) * 18
        out.append(f'<rect x="{lx}" y="{ly - 10}" width="12" height="12" fill="{colour[name]}"/>')
        out.append(f'<text x="{lx + 16}" y="{ly}">{escape(name)}</text>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("runs", nargs="+", help="LABEL=FILE.json from bounce render --timings")
    parser.add_argument("--prefix", action="append", default=[], help="keep passes starting so")
    parser.add_argument("--skip", type=int, default=8, help="warm-up frames left out (default 8)")
    parser.add_argument("--svg", help="write the stacked bar chart here")
    parser.add_argument("--title", default="GPU milliseconds per pass (median)")
    args = parser.parse_args()
    runs = [load_run(spec, args.prefix, args.skip) for spec in args.runs]
    passes = []
    for run in runs:
        passes += [name for name in run["order"] if name not in passes]
    if not passes:
        sys.exit("no pass matched the prefixes")
    devices = sorted({r["device"] for r in runs})
    print(f"Device: {', '.join(devices)}\n")
    print(markdown_table(runs, passes))
    if args.svg:
        with open(args.svg, "w") as f:
            f.write(svg_chart(runs, passes, f"{args.title}, {', '.join(devices)}"))


if __name__ == "__main__":
    main()
