#!/usr/bin/env bash
# [camera] position and look_at as [lon, lat, height_m]: the .pov's camera is there (the sidecar
# gives the eye and the target back in degrees, and the orbit they make), and the orbit keys of
# the scene are set aside with a warning each.
# Usage: camera_position.sh RELIEF SOURCE_DIR WORK_DIR
set -u
relief=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work" || exit 1
status=0
"$relief" compile -q "$src/scenes/default.toml" -o "$work/geo.pov" \
  --set 'camera.position=[-3.1850, 55.9560, 400]' --set 'camera.look_at=[-3.1618, 55.9441, 150]' 2> "$work/stderr.txt" ||
  { echo "FAIL: compile"; cat "$work/stderr.txt"; exit 1; }
grep -q '^// camera: perspective, at lon -3.185 lat 55.956 height 400 m, looking at lon -3.1618 lat 55.9441 height 150 m' \
  "$work/geo.pov" || { echo "FAIL: the header does not name the position"; grep '^// camera' "$work/geo.pov"; status=1; }
[ "$(grep -c 'is not used: camera.position places the eye' "$work/stderr.txt")" = 2 ] ||
  { echo "FAIL: expected a warning for azimuth_deg and elevation_deg"; cat "$work/stderr.txt"; status=1; }
# The sidecar: the eye and target back in degrees and metres, and a bearing from the target to
# the eye to the north-west (Calton Hill is north-west of Arthur's Seat), looking down.
read -r elon elat eh tlon tlat th az el < <(tr -d ' \n' < "$work/geo.json" |
  sed -n 's/.*"eye_lonlat_h":\[\([^,]*\),\([^,]*\),\([^]]*\)\],"look_at_lonlat_h":\[\([^,]*\),\([^,]*\),\([^]]*\)\],"azimuth_deg":\([^,]*\),"elevation_deg":\([^,]*\),.*/\1 \2 \3 \4 \5 \6 \7 \8/p')
awk -v a="$elon" -v b="$elat" -v c="$eh" -v d="$tlon" -v e="$tlat" -v f="$th" -v az="$az" -v el="$el" 'BEGIN {
  ok = (a + 3.185)^2 < 1e-16 && (b - 55.956)^2 < 1e-16 && (c - 400)^2 < 1e-10 &&
       (d + 3.1618)^2 < 1e-16 && (e - 55.9441)^2 < 1e-16 && (f - 150)^2 < 1e-10 &&
       az > 300 && az < 325 && el > 5 && el < 10
  exit !ok }' || { echo "FAIL: sidecar camera: eye $elon $elat $eh, target $tlon $tlat $th, azimuth $az, elevation $el"; status=1; }
[ "$status" = 0 ] && echo "camera at [-3.185, 55.956, 400] looking at [-3.1618, 55.9441, 150]: azimuth $az, elevation $el"
exit $status
