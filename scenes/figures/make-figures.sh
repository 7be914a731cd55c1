#!/usr/bin/env bash
# Reproduces the source papers' curve figures with `relief curve` (SVGs in out/figures/).
# Usage: scenes/figures/make-figures.sh [path/to/relief]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
relief=${1:-$here/../../build/relief}
out=${OUT:-out/figures}
mkdir -p "$out"

# Paper 004, Fig. 11: the blending scheme on a regular hexagon with four (alpha, beta, gamma):
# the polygon itself, the quadratic B-spline (touching the edges' midpoints), an interpolating
# member (Deslauriers-Dubuc, through the vertices) and the quartic B-spline.
"$relief" curve "$here/hexagon.json" --scheme ternary-blend --depth 5 \
  --set "alpha=0,beta=0,gamma=0" --set "alpha=-1/9,beta=0,gamma=0" \
  --set "alpha=0,beta=5/81,gamma=4/81" --set "alpha=-5/27,beta=-5/81,gamma=-1/81" \
  --title "Paper 004 Fig. 11: ternary blending scheme, four (alpha, beta, gamma)" \
  -o "$out/paper004-fig11.svg"

# Paper 000, Fig. 3(a): lambda = mu = 0, omega growing: from outward to inward interpolation
# (this paper's sign: omega = -1/16 is the classic 4-point).
"$relief" curve "$here/zigzag.json" --scheme binary-3p --depth 6 \
  --param lambda=0 --param mu=0 --vary "omega=-1/10,-1/16,-1/32,0,1/32" \
  --title "Paper 000 Fig. 3(a): effect of omega (lambda = mu = 0)" -o "$out/paper000-fig3a.svg"

# Paper 000, Fig. 3(b): mu = 3/16, omega = 1/32, lambda shrinking: the curve approaches the polygon.
"$relief" curve "$here/zigzag.json" --scheme binary-3p --depth 6 \
  --param mu=3/16 --param omega=1/32 --vary "lambda=3/64,1/32,1/64,0" \
  --title "Paper 000 Fig. 3(b): effect of lambda (mu = 3/16, omega = 1/32)" -o "$out/paper000-fig3b.svg"

# Paper 001, Fig. 2: (a) C1 (the classic 4-point), (b) as printed (lambda = 1/80: only C0) and as
# meant (lambda = mu = 1/16: C2).
"$relief" curve "$here/closed-polygon.json" --scheme four-point-4p --depth 6 --param nu=1/2 \
  --set "lambda=0,mu=0,omega=1/16" --set "lambda=1/80,mu=1/16,omega=1/32" \
  --set "lambda=1/16,mu=1/16,omega=1/32" \
  --title "Paper 001 Fig. 2: (a) C1, (b) as printed and as meant (C2)" -o "$out/paper001-fig2.svg"
