#!/usr/bin/env bash
# count_instructions.sh: the instructions a benchmark's stages execute, counted by valgrind's
# callgrind, for comparisons that the machine's speed does not blur (the same binary and input
# give the same counts, whatever else runs). Counts are not seconds: cache misses and parallelism
# are not in them; use them to compare two builds, or two stages of one run, on one input.
#
# usage: tools/count_instructions.sh BENCHMARK [ARGS...]
#   e.g. tools/count_instructions.sh build/bin/bench_optimize --threads 1 --repeat 1
#        tools/count_instructions.sh build/bin/bench_remesh --elements 20000 --threads 1
# Prints, per stage found in the run, its inclusive instruction count (calls of the stage's
# function and everything under them, every call summed), the same per step of the optimisation,
# then the optimisation's count over the extraction's (bench_optimize) and the remesh's over
# OpenVDB's meshToVolume + volumeToMesh of the same parts (bench_remesh's openvdbPipeline). Run
# the benchmark with --threads 1: callgrind runs threads one at a time anyway. Exits non-zero
# when valgrind is missing or the run fails.
set -euo pipefail

if [[ $# -lt 1 || $1 == --help ]]; then
  sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'
  [[ $# -ge 1 ]] && exit 0 || exit 2
fi
for tool in valgrind callgrind_annotate; do
  command -v "$tool" > /dev/null ||
    { echo "count_instructions.sh: $tool not found (apt-get install valgrind)" >&2; exit 2; }
done

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
if ! valgrind --tool=callgrind --callgrind-out-file="$out/callgrind.out" "$@" \
  > "$out/stdout" 2> "$out/stderr"; then
  echo "count_instructions.sh: the run failed:" >&2
  tail -n 20 "$out/stderr" >&2
  exit 1
fi

# Each stage, by the function that runs it; a name nested in itself (an overload calling
# another) is counted once, as its outermost (largest) inclusive count.
callgrind_annotate --inclusive=yes --threshold=100 "$out/callgrind.out" 2> /dev/null |
  awk '
    BEGIN {
      n = split("buildVolume extractQuadMesh optimizeQuadMesh acceptPartMesh remeshDeck " \
                "openvdbPipeline tools::volumeToMesh<", stage, " ")
      split("volume extraction optimisation acceptance remesh(whole) " \
            "OpenVDB(whole) OpenVDB-volumeToMesh", label, " ")
      # The steps of the optimisation (every call of each summed), after the stages.
      m = split("splitLongEdges cleanUpMesh collapseRhombicQuads relaxMesh mergeTrianglePairs " \
                "improveFailingElements reconnectFailingFaces removeWarping " \
                "refillFoldedRegions fitFarOriginalPoints splitInvertedQuads", step, " ")
      for (j = 1; j <= m; ++j) { stage[n + j] = "voxremesh::" step[j] "("; label[n + j] = "  " step[j] }
    }
    /^ *[0-9,]+ / {
      count = $1; gsub(",", "", count)
      for (i = 1; i <= n + m; ++i)
        if (index($0, stage[i]) > 0 && count + 0 > best[i] + 0) best[i] = count
    }
    END {
      for (i = 1; i <= n + m; ++i)
        if (i in best) printf "%-26s %14.0f instructions\n", label[i], best[i]
      if (best[3] > 0 && best[2] > 0)
        printf "optimisation / extraction: %.1f\n", best[3] / best[2]
      if (best[5] > 0 && best[6] > 0)
        printf "remesh / OpenVDB meshToVolume + volumeToMesh of the same parts: %.2f\n",
               best[5] / best[6]
    }'
