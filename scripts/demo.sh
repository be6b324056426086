#!/usr/bin/env bash
# First set-up command: install dependencies, build (Release), run the demo deck.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)" --target rigidflex
./build/rigidflex run examples/bar_impact.k -o bar_impact_out
out="$(pwd)/bar_impact_out"
# The frame collection: frames.pvd, or d3plot.pvd (its older name).
frames=frames.pvd
[ -e "$out/$frames" ] || frames=d3plot.pvd
echo
echo "Results: $out (log: d3hsp.txt)"
echo "  ParaView: File > Open > bar_impact_out/$frames, Apply; the points are the deformed"
echo "  positions (no Warp By Vector needed): colour by displacement or effective_stress"
echo "  LS-PrePost or ParaView's LS-DYNA reader: bar_impact_out/d3plot"
echo "  Energies and momenta: bar_impact_out/glstat.csv; node histories: bar_impact_out/nodout.csv"
# Pictures: PNG plots of the histories (matplotlib) and the last frame coloured by effective
# stress (pvpython under xvfb-run); each is skipped with a note when its package is missing.
if /usr/bin/python3 scripts/rigidflex-plot.py "$out" >/dev/null; then
  echo "  Plots: $(cd "$out" && ls plot_*.png | sed "s|^|$out/|" | tr '\n' ' ')"
else
  echo "  Plots: skipped (python3-matplotlib missing: scripts/install-deps.sh)"
fi
if command -v pvpython >/dev/null && command -v xvfb-run >/dev/null; then
  if xvfb-run -a pvpython scripts/rigidflex-render.py "$out" >/dev/null 2>&1; then
    echo "  Last frame coloured by effective stress: $out/plot_stress.png"
  else
    echo "  Last frame picture: pvpython failed (run: xvfb-run -a pvpython scripts/rigidflex-render.py $out)"
  fi
else
  echo "  Last frame picture: skipped (python3-paraview or xvfb missing: scripts/install-deps.sh)"
fi
