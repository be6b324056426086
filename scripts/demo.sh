#!/usr/bin/env bash
# First set-up command: install dependencies, build (Release), run the demo deck.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j"$(nproc)" --target rigidflex
./build/rigidflex run examples/bar_impact.k -o bar_impact_out
echo
echo "Results: $(pwd)/bar_impact_out"
echo "  ParaView: File > Open > bar_impact_out/frames.pvd, Apply (points are the deformed shape at true scale: no Warp By Vector needed)"
echo "  LS-PrePost or ParaView's LS-DYNA reader: bar_impact_out/d3plot"
echo "  Energies and momenta: bar_impact_out/glstat.csv; node histories: bar_impact_out/nodout.csv"
