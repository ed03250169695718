#!/usr/bin/env bash
# [D-thesis] App. A, Fig. A-2: the steady nonlocal solution (App. A.2, the
# linear equation l^2 g'' = |mu - mu_s| (g - g_loc) with zero flux at the
# walls; verification/ngf1d) of the vertical chute for the mu_s of Fig. A-1,
# the other parameters of Table 4.1 (no simulation, seconds). The thesis: the
# velocity's sharp cut-off is smoothed and no plug can be located. We print
# how far the speed still falls inside the local plug: 1 - v(edge)/v(centre)
# at the local plug's edge x_c = mu_s p / (rho g) from the centre (0 for the
# local model).
#   figures/dthesis-figA-2.sh OUTDIR
set -euo pipefail
src=${GRANMPM_SRCDIR:-$(cd "$(dirname "$0")/.." && pwd)}
export GRANMPM=${GRANMPM:-$src/src/app/granmpm}
out=${1:?usage: dthesis-figA-2.sh OUTDIR}
source "$src/figures/vchute-ref.inc"
work=$out/dthesis-figA-2.d
mkdir -p "$work"
files= titles=
for ms in 0.05 0.1 0.2 0.3 0.3819 0.5 0.6; do
  f=$work/nonlocal-mus$ms.csv
  vchute_ref "$f" --A 0.48 --mu_s "$ms"
  awk -F, -v ms="$ms" 'NR > 1 { n++; x[n] = $1; v[n] = $2 }
    END { xc = ms * 900 / (1500 * 0.8); c = v[int((n + 1) / 2)]
          for (i = 1; i < n; i++) if (x[i] <= 0.5 + xc && x[i + 1] > 0.5 + xc)
            e = v[i] + (v[i + 1] - v[i]) * (0.5 + xc - x[i]) / (x[i + 1] - x[i])
          printf "mu_s = %-6s centre speed %.5f m/s; at the local plug edge (%.3f m from the centre) %.1f %% lower\n",
            ms, c, xc, 100 * (1 - e / c) }' "$f"
  files="$files $f"
  titles="$titles${titles:+|}mu_s = $ms"
done
gnuplot -e "files='$files'; titles='$titles'; out='$out/dthesis-figA-2.png'; \
  ttl='[D-thesis] Fig. A-2 redrawn: steady nonlocal solution (App. A.2, A = 0.48), mu_s varied'" \
  "$src/figures/dthesis-figA.gp"
