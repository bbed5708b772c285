#!/bin/bash
# Sourced by the device scripts that time Evolve's frame with `bounce bench` (energy_bench.sh,
# ray_lists_bench.sh); not run on its own. Run from the repository root with .devicepack carried.

# evolve_bench PROGRAM SCENE OUT PASSES [OPTION...]: `bounce bench` of the packed PROGRAM, Evolve
# on SCENE at 1920x1080 desktop, 120 frames, the sun fixed at noon, with the extra OPTIONs;
# prints the output lines that match the extended regular expression PASSES.
evolve_bench() {
  local program=$1 scene=$2 out=$3 passes=$4
  shift 4
  bash .devicepack/run.sh $program bench --scene $scene --res 1920x1080 --gi evolve "$@" \
    --frames 120 --time-of-day 12 --day-cycle 100000 --out $out \
    2>&1 | tr '\r' '\n' | grep -E "$passes"
}

# evolve_rounds OUT_DIR PASSES PROGRAM...: evolve_bench of each PROGRAM on sunroom and city, the
# programs alternated twice so that a drift of the GPU's clocks falls on all of them; each run
# headed "== PROGRAM SCENE (round N)" and written to OUT_DIR/PROGRAM-SCENE-N.
evolve_rounds() {
  local outDir=$1 passes=$2
  shift 2
  local round program scene
  for round in 1 2; do
    for program in "$@"; do
      for scene in sunroom city; do
        echo "== $program $scene (round $round)"
        evolve_bench $program $scene $outDir/$program-$scene-$round "$passes"
      done
    done
  done
}
