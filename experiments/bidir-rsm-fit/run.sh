#!/bin/bash
# Issue 12 / [TO12s] B.1: VPLs from reflective shadow maps (vpl_source = rsm) and bundle frames fitted
# to the visible points (fit = visible), region by region against the reference path tracer and
# against traced VPLs / sphere-fitted bundles. Results: results.md. Usage (from the repo root):
#   experiments/bidir-rsm-fit/run.sh BUILD_DIR OUT_DIR
# Renders 32^2 images of the point-lit Cornell box (cp) and the spot-lit one (cs), 8 pairs per frame,
# 128^2 bundles, 256^2 light cubes, 128^2 VPL cubes (the test harness of tests/modes/bidir/BidirTest.cpp),
# then prints 8 x 8 block ratios with the seeds' spread (blocks.py).
set -euo pipefail
BIN=$1/bundlelab; OUT=$2; HERE=$(cd "$(dirname "$0")" && pwd); mkdir -p "$OUT"
CP=$HERE/../../data/cornell-box/cornell-point.toml; CS=$HERE/cornell-spot.toml
H="--width 32 --height 32 --set pairs_per_frame=8 --set bundle_resolution=128 --set shadow_resolution=256 --set vpl_shadow_resolution=128"
for sc in cp cs; do
  P=$CP; [ $sc = cs ] && P=$CS
  for s in 1 2; do [ -f "$OUT/ref-$sc-s$s.exr" ] || $BIN render "$P" --mode reference --width 32 --height 32 --spp 8192 --seed $s -o "$OUT/ref-$sc-s$s.exr"; done
done
# name scene source strategy bounces seeds frames [extra --set]
run() { local n=$1 sc=$2 src=$3 st=$4 b=$5 seeds=$6 f=$7; shift 7; local P=$CP; [ $sc = cs ] && P=$CS
  for s in $(seq 1 "$seeds"); do o="$OUT/$n-s$s.exr"; [ -f "$o" ] && continue
    $BIN render "$P" --mode bidir $H --iterations "$f" --seed "$s" --set vpl_source=$src --set strategy=$st --set bounces=$b "$@" -o "$o" > "$o.log"; done; }
run cp-rsm-vpl cp rsm vpl 1 8 512 --set fit=scene
run cp-rsm-mis cp rsm mis 2 8 512 --set fit=scene
run cs-rsm-vpl cs rsm vpl 1 8 512 --set fit=scene
run cs-rsm-mis cs rsm mis 2 8 512 --set fit=scene
run cp-traced-mis cp traced mis 2 6 512 --set fit=scene
run cs-traced-mis cs traced mis 2 6 512 --set fit=scene
run cp-rsm-mis-visible cp rsm mis 2 8 512 --set fit=visible
run cp-traced-mis-visible-256 cp traced mis 2 4 256 --set fit=visible
run cp-traced-mis-scene-256 cp traced mis 2 4 256 --set fit=scene
run cs-rsm-mis1-hires cs rsm mis 1 4 256 --set fit=scene --set vpl_shadow_resolution=512 --set shadow_resolution=1024 --set bundle_resolution=256
for v in 128 256 512; do run cp-rsm-mis1-vpl$v cp rsm mis 1 2 256 --set fit=scene --set vpl_shadow_resolution=$v; done
# The floor view (visible fit, hits no camera point sees): RSM at 64^2 / 256^2 and traced VPLs.
FV=$HERE/cornell-floor-view.toml
[ -f "$OUT/ref-fv.exr" ] || $BIN render "$FV" --mode reference --width 32 --height 32 --spp 8192 --seed 1 -o "$OUT/ref-fv.exr"
for s in 1 2 3 4 5 6 7 8; do for c in rsm64 rsm256 traced; do o="$OUT/fv-$c-s$s.exr"; [ -f "$o" ] && continue
  X="--set vpl_source=rsm --set rsm_resolution=${c#rsm}"; [ $c = traced ] && X="--set vpl_source=traced"
  $BIN render "$FV" --mode bidir $H --set strategy=mis --set bounces=2 --set fit=visible $X --iterations 64 --seed $s -o "$o" > "$o.log"; done; done
for s in 11 12 13 14; do for c in rsm256 traced; do o="$OUT/fv256-$c-s$s.exr"; [ -f "$o" ] && continue
  X="--set vpl_source=rsm"; [ $c = traced ] && X="--set vpl_source=traced"
  $BIN render "$FV" --mode bidir $H --set strategy=mis --set bounces=2 --set fit=visible $X --iterations 256 --seed $s -o "$o" > "$o.log"; done; done
B="/usr/bin/python3 $HERE/blocks.py"
for sc in cp cs; do R="$OUT/ref-$sc-s1.exr+$OUT/ref-$sc-s2.exr"
  for n in $sc-rsm-vpl $sc-rsm-mis $sc-traced-mis; do for l in indirect1 indirect2; do echo "== $n $l"; $B ref "$R" $l "$OUT/$n"-s?.exr; done; done
  for l in indirect1 indirect2; do echo "== $sc rsm / traced, $l"; $B pair $l "$OUT/$sc-rsm-mis-s?.exr" "$OUT/$sc-traced-mis-s?.exr"; done
done
for l in indirect1 indirect2; do echo "== cp visible / scene, $l"; $B pair $l "$OUT/cp-rsm-mis-visible-s?.exr" "$OUT/cp-rsm-mis-s?.exr"; done
R="$OUT/ref-cp-s1.exr+$OUT/ref-cp-s2.exr"
for n in cp-traced-mis-visible-256 cp-traced-mis-scene-256; do echo "== $n per seed, indirect2"; $B seeds "$R" indirect2 "$OUT/$n"-s?.exr; done
echo "== cs hires, indirect1"; $B ref "$OUT/ref-cs-s1.exr+$OUT/ref-cs-s2.exr" indirect1 "$OUT"/cs-rsm-mis1-hires-s?.exr
for v in 128 256 512; do echo "== cp mis bounces 1, VPL cubes $v^2, per seed"; $B seeds "$R" indirect1 "$OUT"/cp-rsm-mis1-vpl$v-s?.exr; done
for n in fv-rsm64 fv-rsm256 fv-traced fv256-rsm256 fv256-traced; do for l in indirect1 indirect2; do
  echo "== floor view $n $l"; $B ref "$OUT/ref-fv.exr" $l "$OUT/$n"-s*.exr | head -1; done; done
