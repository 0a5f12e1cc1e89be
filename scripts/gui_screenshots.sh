#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Drives the real MeshLab GUI (the staged build/stage/bin/meshlab with our plugins) under a
# private Xvfb with xdotool and writes the README's screenshots to docs/img/:
#   filter_menu.png              Filters > Mesh Layer, listing "Compress Animation Layers"
#   compress_dialog.png          the filter's parameter dialog
#   original_vs_reconstructed.png  frame N of the sample next to the frame the filter
#                                reconstructed from the .ams, coloured by per-vertex error
#   open_ams.png                 a second MeshLab opening that .ams (command-line argument,
#                                through io_animstream): frames listed as layers, one later
#                                frame shown on its own, drawn
# The sample frames are copied to a temporary folder (the filter writes animation.ams next
# to them); HOME/XDG point into it, so nothing is written outside it and docs/img/.
#   usage: scripts/gui_screenshots.sh        (as root when xvfb/xdotool/imagemagick are missing)
#          ANIMC_GUI_MESHLAB=2025.07 scripts/gui_screenshots.sh   the same four for MeshLab 2025.07
#          (built by fetch_meshlab_2022plus.sh) with the plugins of build-meshlab2025, installed
#          into the private home's per-user plugin folder; written to docs/img/2025.07/.
#   env:   ANIMC_STAGE (default build/stage), ANIMC_SHOT_FRAME (default 12),
#          ANIMC_SHOT_LATER_FRAME (default 20), ANIMC_GUI_KEEP_TMP=1 keeps the temporary
#          folder (with every intermediate screenshot) for debugging; for 2025.07
#          ANIMC_MESHLAB_SDK (default /var/cache/animcompress/meshlab-2025.07-float) and
#          ANIMC_BUILD_2025 (default build-meshlab2025).
# The clicks use fixed positions in a 1280x900 main window at (0,0) with Debian's default
# Qt style and fonts; every step checks its result (dialog window present, layer row
# highlighted, mesh pixels in the 3D view) and stops with a message when it is not there.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
stage=${ANIMC_STAGE:-$root/build/stage}
meshlab="$stage/bin/meshlab"
samples="$root/samples/sydney/frames"
out="$root/docs/img"
frame=${ANIMC_SHOT_FRAME:-12}
later=${ANIMC_SHOT_LATER_FRAME:-20}
convert=/usr/bin/convert
gui=${ANIMC_GUI_MESHLAB:-2020.09}

say() { echo "gui_screenshots: $*"; }
die() { echo "gui_screenshots: error: $*" >&2; exit 1; }

case "$gui" in
  2020.09) ;;
  2025.07)
    sdk=${ANIMC_MESHLAB_SDK:-${ANIMC_CACHE_DIR:-/var/cache/animcompress}/meshlab-2025.07-float}
    meshlab="$sdk/build/src/distrib/meshlab"
    plugin_build=${ANIMC_BUILD_2025:-$root/build-meshlab2025}
    out="$root/docs/img/2025.07" ;;
  *) die "ANIMC_GUI_MESHLAB must be 2020.09 or 2025.07, not $gui" ;;
esac

source "$root/scripts/host_setup.sh"
install_missing_packages gui_screenshots xvfb xauth xdotool imagemagick x11-utils

if [ "$gui" = 2020.09 ]; then
  [ -x "$meshlab" ] || die "$meshlab missing; run: cmake --install build --prefix build/stage"
else
  [ -x "$meshlab" ] || die "$meshlab missing; run: scripts/fetch_meshlab_2022plus.sh 2025.07 float"
  for so in libfilter_animcompress.so libio_animstream.so; do
    [ -f "$plugin_build/plugins/$so" ] \
      || die "$plugin_build/plugins/$so missing; build targets filter_animcompress io_animstream"
  done
fi
ls "$samples"/frame_*.ply >/dev/null 2>&1 || die "no sample frames in $samples"
nframes=$(ls "$samples"/frame_*.ply | wc -l)
[ "$frame" -lt "$nframes" ] && [ "$later" -lt "$nframes" ] || die "frame numbers must be < $nframes"

# --- temporary folder, private HOME, cleanup ------------------------------------------------
tmp=$(mktemp -d /tmp/animc-gui.XXXXXX)
work="$tmp/sydney"          # the sample frames; the filter writes sydney/animation.ams
shots="$tmp/shots"          # every screenshot, copied to docs/img only when all succeeded
mkdir -p "$work" "$shots"
cp "$samples"/frame_*.ply "$work/"

xvfb_pid=""
ml_pid=""
stop_meshlab() {
  if [ -n "$ml_pid" ]; then
    kill "$ml_pid" 2>/dev/null || true
    wait "$ml_pid" 2>/dev/null || true
    ml_pid=""
  fi
}
cleanup() {
  stop_meshlab
  if [ -n "$xvfb_pid" ]; then
    kill "$xvfb_pid" 2>/dev/null || true
    wait "$xvfb_pid" 2>/dev/null || true
  fi
  if [ "${ANIMC_GUI_KEEP_TMP:-0}" = 1 ]; then say "kept $tmp"; else rm -rf "$tmp"; fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# --- Xvfb on a free display ---------------------------------------------------------------
display=""
for n in $(seq 71 98); do
  [ -e "/tmp/.X$n-lock" ] || [ -e "/tmp/.X11-unix/X$n" ] && continue
  Xvfb ":$n" -screen 0 1280x1024x24 -nolisten tcp >"$tmp/xvfb.log" 2>&1 &
  xvfb_pid=$!
  for _ in $(seq 1 50); do
    xdpyinfo -display ":$n" >/dev/null 2>&1 && { display=":$n"; break; }
    kill -0 "$xvfb_pid" 2>/dev/null || break
    sleep 0.1
  done
  [ -n "$display" ] && break
  kill "$xvfb_pid" 2>/dev/null || true; wait "$xvfb_pid" 2>/dev/null || true; xvfb_pid=""
done
[ -n "$display" ] || die "could not start Xvfb on any display :71..:98"
say "Xvfb on $display"

export DISPLAY="$display"
use_private_meshlab_home "$tmp/home"
if [ "$gui" = 2025.07 ]; then
  # informativeShown skips the modal "Send Anonymous Statistics" question of a first start; the
  # plugins go where a user's copy would (HOME is the private one now).
  echo 'informativeShown=true' >> "$HOME/.config/VCG/MeshLab_64bit_fp.conf"
  "$root/scripts/install_user_plugins.sh" "$plugin_build" >/dev/null
fi

# --- helpers -----------------------------------------------------------------------------
# pixels.py rows FILE X [Y0 Y1]: y centres of the selected (blue) and current (yellow) layer rows
#   in column X of the layer panel (between Y0 and Y1). pixels.py eyes FILE X0 X1 Y0 Y1: y centres
#   of the open (green) eye icons there, one per visible layer. pixels.py mesh FILE X0 Y0 X1 Y1:
#   count and bounding box of the pixels in that part of the 3D view that differ from the row's background (MeshLab's
#   background is a vertical gradient, constant along a row).
cat > "$tmp/pixels.py" <<'PY'
import subprocess, sys

def load(path):
    ppm = subprocess.run(["/usr/bin/convert", path, "-depth", "8", "ppm:-"],
                         check=True, capture_output=True).stdout
    parts, pos = [], 0
    while len(parts) < 4:
        while ppm[pos:pos + 1].isspace(): pos += 1
        start = pos
        while not ppm[pos:pos + 1].isspace(): pos += 1
        parts.append(ppm[start:pos])
    w, h = int(parts[1]), int(parts[2])
    return w, h, ppm[pos + 1:]

def px(data, w, x, y):
    i = 3 * (y * w + x)
    return data[i], data[i + 1], data[i + 2]

def centre(ys):
    return (min(ys) + max(ys)) // 2 if ys else -1

cmd, path = sys.argv[1], sys.argv[2]
w, h, data = load(path)
if cmd == "rows":
    x = int(sys.argv[3])
    ry0, ry1 = (int(sys.argv[4]), int(sys.argv[5])) if len(sys.argv) > 5 else (90, 370)
    blue = [y for y in range(ry0, ry1) if (lambda p: p[2] > 150 and p[0] < 120 and p[2] - p[0] > 80)(px(data, w, x, y))]
    yellow = [y for y in range(ry0, ry1) if (lambda p: p[0] > 220 and p[1] > 220 and p[2] < 80)(px(data, w, x, y))]
    print(centre(blue), centre(yellow))
elif cmd == "eyes":
    x0, x1, y0, y1 = map(int, sys.argv[3:7])
    green = lambda p: p[1] > 180 and p[0] < 110 and p[2] < 110
    ys = [y for y in range(y0, y1) if any(green(px(data, w, x, y)) for x in range(x0, x1))]
    groups = []
    for y in ys:
        if groups and y - groups[-1][-1] <= 3: groups[-1].append(y)
        else: groups.append([y])
    print(" ".join(str(centre(g)) for g in groups))
elif cmd == "mesh":
    x0, y0, x1, y1 = map(int, sys.argv[3:7])
    n, bx0, by0, bx1, by1 = 0, w, h, -1, -1
    for y in range(y0, y1):
        bg = px(data, w, x0, y)
        for x in range(x0, x1):
            p = px(data, w, x, y)
            if abs(p[0] - bg[0]) + abs(p[1] - bg[1]) + abs(p[2] - bg[2]) > 40:
                n += 1
                bx0, by0, bx1, by1 = min(bx0, x), min(by0, y), max(bx1, x), max(by1, y)
    print(n, bx0, by0, bx1, by1)
PY
pixels() { /usr/bin/python3 "$tmp/pixels.py" "$@"; }

shot_root() { import -window root "$shots/$1"; }
click() { xdotool mousemove --sync "$1" "$2" click 1; }
settle() { sleep "${1:-1}"; }

# wait_for SECONDS COMMAND...: polls COMMAND every 0.2 s until it succeeds.
wait_for() {
  local limit=$1; shift
  local end=$((SECONDS + limit))
  until "$@" >/dev/null 2>&1; do
    [ $SECONDS -lt $end ] || return 1
    sleep 0.2
  done
}
log_has() { grep -q -- "$1" "$ml_log"; }
log_count_is() { [ "$(grep -c -- "$1" "$ml_log")" -ge "$2" ]; }
window_named() { xdotool search --onlyvisible --name "$1" | head -1 | grep -q .; }
window_id() { xdotool search --onlyvisible --name "$1" | head -1; }

# start_meshlab LOGNAME ARGS...: runs the staged meshlab in $work, sets ml_pid and ml_log.
start_meshlab() {
  ml_log="$tmp/$1"; shift
  (cd "$work" && exec "$meshlab" "$@") >"$ml_log" 2>&1 &
  ml_pid=$!
  wait_for 60 window_named "^MeshLab ${gui%.*}" || die "no MeshLab window (log: $(tail -3 "$ml_log"))"
  main_win=$(window_id "^MeshLab ${gui%.*}")
}

# The main window 1280x900 at (0,0); retried because MeshLab resizes itself while loading.
place_main_window() {
  local g
  for _ in $(seq 1 20); do
    xdotool windowmove "$main_win" 0 0 windowsize "$main_win" 1280 900
    sleep 0.3
    g=$(xdotool getwindowgeometry "$main_win" | awk '/Geometry/{print $2}')
    [ "$g" = 1280x900 ] && return 0
  done
  die "main window stays $g, not 1280x900"
}

# Windows > View from > Front (Z is up) (the sample is Z-up), then hide the trackball.
view_front_z_up() {
  if [ "$gui" = 2020.09 ]; then
    click 290 10; settle 0.7
    click 318 213; settle 0.7
    click 677 364; settle 0.5
  else
    # 2025.07 by keyboard: Alt+W opens Windows, V its View from submenu; Front (Z is up) is the
    # 7th entry. A click into the 3D view first gives the main window the keyboard.
    click 430 400; settle 0.3
    xdotool key alt+w; settle 0.5
    xdotool key v; settle 0.5
    xdotool key --repeat 6 --delay 60 Down; xdotool key Return; settle 0.5
  fi
  wait_for 5 log_has "View scene from Front (Z is up)" || die "View from > Front (Z is up) did not apply"
  click 430 400            # focus the 3D view (a click without drag does not rotate)
  xdotool key shift+h      # View > Show Trackball off
  settle 1
}

# select_row_by_keyboard ROW X: focuses the layer tree (a click at X on its first visible row),
# moves the keyboard selection to row ROW and takes the screenshot rows_ROW.png of the result.
select_row_by_keyboard() {
  click "$2" 114; settle 0.3
  xdotool key Home
  [ "$1" -gt 0 ] && xdotool key --repeat "$1" --delay 15 Down
  settle 0.6
  shot_root "rows_$1.png"
}

# show_only_layer ROW: makes layer ROW (0-based, document order) the only visible one, as a
# user does: select it in the layer panel with the keyboard (Home, Down...), then Ctrl+click
# its eye icon (MeshLab: "only that layer will remain visible").
show_only_layer() {
  [ "$gui" = 2020.09 ] || { show_only_layer_2025 "$@"; return; }
  local row=$1 ys sel cur
  select_row_by_keyboard "$row" 990
  read -r sel cur < <(pixels rows "$shots/rows_$row.png" 1220)
  [ "$sel" -gt 0 ] || die "layer row $row not found in the layer panel"
  xdotool mousemove --sync 898 "$sel"
  xdotool keydown Control_L; sleep 0.1; xdotool click 1; sleep 0.1; xdotool keyup Control_L
  settle 1
  shot_root "rows_${row}_after.png"
  local y=$sel
  read -r sel cur < <(pixels rows "$shots/rows_${row}_after.png" 1220)
  # the clicked row is now the current layer: highlighted (blue) or, if the tree's selection
  # stayed elsewhere, marked current (yellow)
  [ $((sel - y)) -le 6 ] && [ $((y - sel)) -le 6 ] || { [ $((cur - y)) -le 6 ] && [ $((y - cur)) -le 6 ]; } \
    || die "layer row $row did not become the current layer"
}

# 2025.07's layer panel: rows 31 pixels high from y 98 to 333, eye icons at x 840. The current
# layer follows a click, not the keyboard selection, and a Ctrl+click on an eye scrolls the tree to
# the current layer; so: select the row by keyboard, click its name, Ctrl+click its eye, then
# check that one eye is open, in the highlighted row.
show_only_layer_2025() {
  local row=$1 sel cur eyes
  select_row_by_keyboard "$row" 925
  read -r sel cur < <(pixels rows "$shots/rows_$row.png" 1040 98 333)
  [ "$sel" -gt 0 ] || die "layer row $row not found in the layer panel"
  click 925 "$sel"; settle 0.5                # make it the current layer
  xdotool mousemove --sync 840 "$sel"
  xdotool keydown Control_L; sleep 0.1; xdotool click 1; sleep 0.1; xdotool keyup Control_L
  settle 1
  shot_root "rows_${row}_after.png"
  read -r sel cur < <(pixels rows "$shots/rows_${row}_after.png" 1040 98 333)
  eyes=$(pixels eyes "$shots/rows_${row}_after.png" 832 849 98 333)
  [ "$sel" -gt 0 ] && [ -n "$eyes" ] && [ "${eyes// /}" = "$eyes" ] \
    && [ $((eyes - sel)) -le 8 ] && [ $((sel - eyes)) -le 8 ] \
    || die "layer row $row is not the only visible layer (highlighted row at $sel, open eyes at: $eyes)"
}

# The sample's triangles are wound clockwise (their normals point inwards), so with MeshLab's
# default one-sided lighting they are drawn almost black. Back-Face "Double" (two-sided
# lighting), applied to all visible layers from the layer panel, shows their shape.
double_sided_lighting_for_visible_layers() {
  if [ "$gui" = 2020.09 ]; then
    click 1252 683; settle 0.3     # "apply to all visible layers"
    click 1115 594; settle 1       # Back-Face: Double
  else
    click 1251 662; settle 0.3
    click 1114 573; settle 1
  fi
}

# 3D view region of the 1280x900 window (without the info panel at its bottom).
GL_X0=4 GL_Y0=74 GL_X1=856 GL_Y1=770
[ "$gui" = 2020.09 ] || { GL_X1=800; GL_Y1=775; }

t_start=$SECONDS

# --- 1. the sample as 24 layers, Filters > Mesh Layer > Compress Animation Layers -----------
frames=()
for f in "$work"/frame_*.ply; do frames+=("$(basename "$f")"); done
say "starting meshlab with ${#frames[@]} frames"
start_meshlab meshlab1.log "${frames[@]}"
wait_for 60 log_count_is "Opened mesh frame_" "${#frames[@]}" || die "frames not loaded"
place_main_window
settle 1

if [ "$gui" = 2020.09 ]; then
  click 120 10; settle 0.7            # Filters
  click 162 311; settle 1.2           # Mesh Layer (submenu opens on click)
  shot_root menu.png
  $convert "$shots/menu.png" -crop 850x810+0+0 +repage "$shots/filter_menu.png"
  click 630 386                       # Compress Animation Layers
else
  # 2025.07's submenus do not open on a click: Mesh Layer is the 11th enabled entry of Filters,
  # Right opens it and Return runs its first entry, ours (the only Mesh Layer filter built here;
  # if it were not first, the dialog check below stops the script).
  click 120 10; settle 0.7
  xdotool key --repeat 11 --delay 60 Down; xdotool key Right; settle 1.2
  shot_root menu.png
  $convert "$shots/menu.png" -crop 850x560+0+0 +repage "$shots/filter_menu.png"
  xdotool key Return
fi
wait_for 10 window_named '^Compress Animation Layers$' || die "filter dialog did not open"
dialog=$(window_id '^Compress Animation Layers$')
settle 1
import -window "$dialog" "$shots/compress_dialog.png"
geom=$(xdotool getwindowgeometry "$dialog" | awk '/Geometry/{print $2}')
dw=${geom%x*} dh=${geom#*x}
say "filter dialog ${dw}x${dh}; applying"
xdotool mousemove --sync --window "$dialog" $((dw * 74 / 100)) $((dh - 23)) click 1   # Apply
wait_for 120 log_has "Applied filter:\? Compress Animation Layers" \
  || die "filter did not finish: $(grep -v '^LOG: 0 \(Opened\|All files\)' "$ml_log" | tail -5)"
wait_for 10 log_has "added ${#frames[@]} reconstructed layers" || die "no reconstructed layers in the log"
[ -s "$work/animation.ams" ] || die "$work/animation.ams was not written"
xdotool mousemove --sync --window "$dialog" $((dw * 24 / 100)) $((dh - 23)) click 1   # Close
wait_for 5 bash -c "! xdotool search --onlyvisible --name '^Compress Animation Layers\$' | grep -q ." \
  || die "filter dialog did not close"
settle 0.5

# --- 2. original frame next to its reconstruction coloured by error --------------------------
view_front_z_up
double_sided_lighting_for_visible_layers
show_only_layer "$frame"
shot_root original.png
show_only_layer $((${#frames[@]} + frame))
shot_root reconstructed.png
read -r n_a ax0 ay0 ax1 ay1 < <(pixels mesh "$shots/original.png" $GL_X0 $GL_Y0 $GL_X1 $GL_Y1)
read -r n_b bx0 by0 bx1 by1 < <(pixels mesh "$shots/reconstructed.png" $GL_X0 $GL_Y0 $GL_X1 $GL_Y1)
say "mesh pixels: original $n_a, reconstructed $n_b"
[ "$n_a" -gt 2000 ] && [ "$n_b" -gt 2000 ] || die "a frame is not drawn (mesh pixels $n_a / $n_b)"
# One crop for both: the union of the two meshes' bounding boxes plus a margin.
m=40
cx0=$(( (ax0 < bx0 ? ax0 : bx0) - m )); cy0=$(( (ay0 < by0 ? ay0 : by0) - m ))
cx1=$(( (ax1 > bx1 ? ax1 : bx1) + m )); cy1=$(( (ay1 > by1 ? ay1 : by1) + m ))
[ $cx0 -ge $GL_X0 ] || cx0=$GL_X0; [ $cy0 -ge $GL_Y0 ] || cy0=$GL_Y0
[ $cx1 -le $GL_X1 ] || cx1=$GL_X1; [ $cy1 -le $GL_Y1 ] || cy1=$GL_Y1
cw=$((cx1 - cx0)) ch=$((cy1 - cy0))
[ $cw -ge 400 ] || { cx0=$(( (cx0 + cx1) / 2 - 200 )); cw=400; }
crop="${cw}x${ch}+${cx0}+${cy0}"
font=/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf
[ -f "$font" ] || font=""
text() { [ -n "$font" ] && echo -font "$font"; }   # ImageMagick's default font otherwise
label() {  # label IN OUT TEXT: the crop, with TEXT in a white band above it
  $convert "$1" -crop "$crop" +repage -background white -gravity north -splice 0x34 \
    $(text) -pointsize 17 -fill black -annotate +0+8 "$3" "$2"
}
fname=$(printf 'frame_%05d' "$frame")
label "$shots/original.png" "$shots/a.png" "original $fname"
label "$shots/reconstructed.png" "$shots/b.png" "decoded, coloured by error"
# Legend: MeshLab's ramp (blue, cyan, green, yellow, red) from 0 to the filter's max error,
# the one scale of every decoded frame.
max_err=$(sed -n 's/^LOG: 2 max_error: //p' "$ml_log" | head -1)
max_cube=$(sed -n 's/^LOG: 2 max_error_rel_cube: //p' "$ml_log" | head -1)
legend=$(awk -v n="${#frames[@]}" -v e="${max_err:-0}" -v c="${max_cube:-0}" 'BEGIN {
  printf "error scale, the same for all %d frames: blue = 0, red = %.3g (the largest error, %.2g %%%% of the root cube)", n, e, 100 * c }')
$convert -size 14x80 gradient:blue-cyan gradient:cyan-lime gradient:lime-yellow gradient:yellow-red \
  -append -rotate -90 "$shots/ramp.png"
$convert "$shots/a.png" "$shots/b.png" -background white -splice 6x0 +append -chop 6x0 \
  \( -size "$((2 * cw + 6))x52" xc:white \( "$shots/ramp.png" -bordercolor gray40 -border 1 \) \
     -gravity north -geometry +0+6 -composite \
     $(text) -pointsize 13 -fill black -gravity south -annotate +0+6 "$legend" \) \
  -gravity center -append "$shots/original_vs_reconstructed.png"
stop_meshlab

# --- 3. a second MeshLab opens the .ams through io_animstream -------------------------------
say "opening animation.ams in a new meshlab"
start_meshlab meshlab2.log animation.ams
wait_for 30 window_named '^Pre-Open Options$' || die "no First frame / Last frame dialog"
pre=$(window_id '^Pre-Open Options$')
settle 0.5
import -window "$pre" "$shots/preopen.png"
xdotool windowfocus --sync "$pre" key Return
wait_for 60 log_has "Opened mesh animation.ams" || die "animation.ams not opened: $(tail -3 "$ml_log")"
grep -q "Opened animation.ams: frames 0 to $((nframes - 1)) as $nframes layers" "$ml_log" \
  || die "unexpected open log: $(grep '^LOG' "$ml_log" | head -3)"
place_main_window
settle 1
shot_root ams_all.png
read -r n_all _ < <(pixels mesh "$shots/ams_all.png" $GL_X0 $GL_Y0 $GL_X1 $GL_Y1)
say "mesh pixels with all frames of the .ams visible: $n_all"
# No render mode is touched here: what is drawn is what the IO plugin set up.
view_front_z_up
show_only_layer "$later"
shot_root ams_later.png
read -r n_c _ < <(pixels mesh "$shots/ams_later.png" $GL_X0 $GL_Y0 $GL_X1 $GL_Y1)
say "mesh pixels with only frame $later of the .ams visible: $n_c"
[ "$n_c" -gt 2000 ] || die "frame $later opened from the .ams is not drawn"
$convert "$shots/ams_later.png" -crop 1280x900+0+0 +repage "$shots/open_ams.png"
stop_meshlab

# --- 4. into docs/img ----------------------------------------------------------------------
mkdir -p "$out"
for f in filter_menu compress_dialog original_vs_reconstructed open_ams; do
  $convert "$shots/$f.png" -strip -define png:compression-level=9 "$out/.$f.png.tmp"
  mv "$out/.$f.png.tmp" "$out/$f.png"
  say "wrote ${out#$root/}/$f.png ($(stat -c %s "$out/$f.png") bytes)"
done
say "done in $((SECONDS - t_start)) s"
