#!/bin/bash
# GPU timings of the library denoisers on Evolve's GI (issue 21: SVGF, ReBLUR with radii scaled
# to the resolution, the hybrid with its tile classification) at 1080p and 1440p, and of the
# optional ReSTIR DI denoiser on manylights (docs/denoise.md). Pack first:
#   ../shared/device/pack.sh build/bounce ../shared/scenes/cornell_box
# then run from the repository root on the GPU machine with .devicepack carried.
set -u
B="bash .devicepack/run.sh bounce"
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader
mkdir -p /tmp/d
r() { n=$1; shift; $B render --preset desktop --frames 240 --animate "$@" --timings /tmp/d/$n.json --out /tmp/d/$n.png > /dev/null 2>&1 || echo "$n failed"; }
r evolve --scene sunroom --res 1920x1080
r svgf --scene sunroom --denoiser svgf --res 1920x1080
r reblur --scene sunroom --denoiser reblur --res 1920x1080
r hybrid --scene sunroom --denoiser hybrid --res 1920x1080
r reblur1440 --scene sunroom --denoiser reblur --res 2560x1440
r hybrid1440 --scene sunroom --denoiser hybrid --res 2560x1440
r manylights --scene manylights --res 1920x1080
r manylights-disvgf --scene manylights --di-denoiser svgf --res 1920x1080
python3 - <<'PY'
import json, statistics
for n in ["evolve","svgf","reblur","hybrid","reblur1440","hybrid1440","manylights","manylights-disvgf"]:
    try:
        t = json.load(open(f"/tmp/d/{n}.json"))["timings"]
    except OSError:
        print(n, "missing"); continue
    passes = {}
    for e in t:
        if e["frame"] >= 16: passes.setdefault(e["pass"], []).append(e["ms"])
    med = {p: statistics.median(v) for p, v in passes.items()}
    den = {p: m for p, m in med.items() if p.startswith(("svgf", "reblur", "hybrid", "gi-temporal-denoise", "gi-spatial-denoise", "di-denoise"))}
    print(n, "denoise %.3f ms" % sum(den.values()), " ".join(f"{p} {m:.3f}" for p, m in den.items()))
PY
cp /tmp/d/manylights-disvgf.png /tmp/d/manylights.png /tmp/d/hybrid.png $OUT/
