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
echo "  ParaView: File > Open > bar_impact_out/d3plot.pvd, Apply, then Filters > Warp By Vector (displacement)"
echo "  Energies and momenta: bar_impact_out/glstat.csv; node histories: bar_impact_out/nodout.csv"
