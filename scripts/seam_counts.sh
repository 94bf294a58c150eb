#!/usr/bin/env bash
# Counts how many places each concept of the stages still lives in: light types named
# outside the light seam, the photon maps named one by one, readers of the model
# choice, declarations of the common options, the frame's length, cli's includes.
# Usage: scripts/seam_counts.sh   (from any folder; reads src/)
set -uo pipefail
cd "$(dirname "$0")/.."

echo "M1 LightType:: uses outside the light seam (src/core/light*, src/core/lights/)"
seam='^src/core/light'
echo "   all: $(grep -rn 'LightType::' src | wc -l), outside: $(grep -rn 'LightType::' src | grep -v "$seam" | wc -l)"
grep -rn 'LightType::' src | grep -v "$seam" | cut -d: -f1 | sort | uniq -c | sort -rn | sed 's/^/   /'

echo "M2 members naming one photon map, and their uses"
echo "   members: $(grep -rnE '^\s*(ShadowPhotonMap|IndirectPhotonMap|PhotonBatches<\w+>|PrefixCuts|PhotonTally|PhotonMaps|ClassicCuts|PhysicalPhotons|const (Shadow|Indirect)PhotonMap\*) +\w+[^(]*;' src --include=*.h | wc -l)"
# LookupCacheParams' `indirect` (params, gateOnly, p) is the estimate a cache cell keeps, not a map;
# comments (the sweep's knobs name the JSON keys photons.global and photons.caustic) are not uses.
echo "   uses: $(grep -rnE '(\.|->)(shadow|indirect|global|caustic)(Map|Cuts|Tally)?\b|\.(caustic|global)(K|Radius)\b' src/emit src/trace src/plan |
  grep -v '"' | grep -vE ':[0-9]+:\s*//' | grep -vE '(counts|ph|params|gateOnly|p|a|b|cached|slot|rays)(\.|->)(shadow|indirect)' | wc -l)"

echo "M3 readers of render.model: $(grep -rn 'render\.model' src | grep -v '//.*render\.model' | grep -v '"[^"]*render\.model' | wc -l)"

echo "M4 declarations of the common options"
for o in '-t,--threads' '--max-memory' '--map-cache' '-D,--set' '-q,--quiet' '--time-limit' '--target-error' '--no-defaults' '--enable' '--disable' '--gate'; do
  echo "   $o: $(grep -rn 'add_option\|add_flag' src/cli | grep -cF "\"$o")"
done

echo "M5 renderFrame: $(awk '/^void renderFrame/,/^}/' src/plan/render_frame.cpp | wc -l) lines, its pass loop" \
  "$(awk '/^void renderFrame/,/^}/' src/plan/render_frame.cpp | awk '/for \(int pass = 0; pass < (f\.)?passes/,/^  }$/' | wc -l)"

echo "M6 cli files including more than plan/ and core/error.h:" \
  "$(grep -rE --include='*.h' --include='*.cpp' '^\s*#\s*include "(core|io|emit|gather|geometry|trace)/' src/cli |
     grep -v '"core/error.h"' | cut -d: -f1 | sort -u | wc -l) of $(find src/cli -name '*.h' -o -name '*.cpp' | wc -l)"
