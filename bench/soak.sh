#!/usr/bin/env bash
# soak.sh — every lab in a real window for a while, driven like a restless user.
#
#   bash bench/soak.sh [MINUTES] [LAB...]    default: 10 minutes for every lab that is built
#   bash bench/soak.sh 1 lab2_lighting       (what the CTest version lab2_soak runs)
#
# Each lab runs with --validate under its own Xvfb and openbox (a real window manager, so that
# minimize and restore are real). xdotool sends, in a fixed pseudo-random order (SOAK_SEED):
# window resizes (to 1×1 and back included), minimize + restore, camera keys (W A S D, Space,
# Shift), mouse drags and wheel steps, the camera-mode key (C), the reload key (R), and rewrites
# of the scene file that alternate a good and a broken scene; the good ones add and remove an
# object and, from lab 2 on, add and remove lights (down to none); from lab 4 on they also switch
# every light's shadow off and on (with other PCF, filter and map size), take every object's
# shadow away and make every material translucent.
#
# Every input must be answered within SOAK_ANSWER_S seconds (default 10): the lab's status file
# (LAB_STATUS_FILE, common/status_file.h) shows a frame drawn after the input — after a resize, at
# the new size — and a scene write shows "reloaded" on stdout or "reload failed" on stderr. So the
# soak also works for a lab that draws only when something happens: every input wakes it.
# Resident memory (VmRSS) is read at rest — after every input answered by a frame drawn, so the
# renderer in use has drawn at least once, and once the lab has gone idle after it (its status line
# ends in " idle": frames finished, freed memory given back with malloc_trim) — and, for the record,
# every SOAK_SAMPLE_S seconds (default 3).
#
# Pass: no crash; every input answered; no validation message (the lab, closed with Alt+F4 at the
# end, exits 0; it exits 1 after any message) and nothing unexpected on stderr; resident memory
# after the warm-up — the first minute, or the first third of a shorter run — grows by less than
# 1 % (SOAK_MEMORY_GATE; the samples at rest of the last quarter of the time after the warm-up
# against those of the first quarter, each divided by the usual level of the scene variant it was
# taken with: bench/soak_memory.awk; at least SOAK_MIN_SAMPLES after the warm-up, default 10).
# Prints the figures per lab; exit 0 when every lab passed, 1 otherwise, 2 for bad usage.
# SOAK_KEEP=1 keeps each lab's folder (logs, the RSS samples, the inputs with their times) even
# when it passed. For finding where memory goes: SOAK_ACTIONS="scene reload" (only those inputs;
# names: resize tiny minimize key drag wheel mode scene reload pause) and SOAK_NO_VALIDATE=1 (the
# lab without the validation layer; such a run is not a pass of the soak).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${LAB_BUILD_DIR:-$root/build}"
minutes="${1:-10}"
shift || true
answer_s="${SOAK_ANSWER_S:-10}"
start_s="${SOAK_START_S:-60}"
sample_s="${SOAK_SAMPLE_S:-3}"
seed="${SOAK_SEED:-1}"

die() { echo "soak: error: $*" >&2; exit 2; }
[[ "$minutes" =~ ^[0-9]+([.][0-9]+)?$ ]] || die "MINUTES must be a number, got '$minutes' (usage: bench/soak.sh [MINUTES] [LAB...])"
[[ "${SOAK_MEMORY_GATE:-1}" =~ ^[0-9]+([.][0-9]+)?$ ]] || die "SOAK_MEMORY_GATE must be a percentage, got '${SOAK_MEMORY_GATE}'"
for tool in Xvfb openbox xdotool xprop jq; do
  command -v "$tool" >/dev/null || die "$tool not found: run scripts/setup.sh (it installs xvfb, openbox, xdotool, x11-utils, jq)"
done
labs=("$@")
if ((${#labs[@]} == 0)); then
  for lab in lab1_camera lab2_lighting lab3_textures lab4_shadows; do
    [[ -x "$build/$lab/$lab" ]] && labs+=("$lab")
  done
fi
((${#labs[@]})) || die "no lab built in $build (run scripts/setup.sh)"
seconds=$(awk -v m="$minutes" 'BEGIN { printf "%d", m * 60 }')
warmup=$(( seconds >= 180 ? 60 : seconds / 3 ))

now() { date +%s.%N; }
xdo() { timeout 5 xdotool "$@"; }  # xdotool --sync waits forever for a window that never changes
elapsed() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.2f", b - a }'; }

# What one lab's soak started; stopped when it ends, and on any exit (a CTest timeout included).
xvfb_pid="" wm_pid="" lab_pid="" sampler_pid=""
cleanup_lab() {
  local p
  for p in "$lab_pid" "$sampler_pid" "$wm_pid" "$xvfb_pid"; do [[ -n "$p" ]] && kill "$p" 2>/dev/null; done
  for p in "$lab_pid" "$wm_pid" "$xvfb_pid"; do [[ -n "$p" ]] && wait "$p" 2>/dev/null; done
  xvfb_pid="" wm_pid="" lab_pid="" sampler_pid=""
  return 0
}
trap cleanup_lab EXIT
trap 'exit 1' INT TERM

# ---------------------------------------------------------------- one lab
soak_lab() {
  local lab="$1" exe="$build/$1/$1"
  [[ -x "$exe" ]] || { echo "soak: $lab: not built ($exe)"; return 1; }
  local work; work="$(mktemp -d "${TMPDIR:-/tmp}/soak_${lab}.XXXXXX")"
  xvfb_pid="" wm_pid="" lab_pid="" sampler_pid=""  # global: the exit trap stops them
  local failure=""
  fail() { failure="$*"; echo "soak: $lab: FAIL: $*"; }

  # A private X server (-displayfd picks a free display) and a window manager on it.
  Xvfb -displayfd 3 -screen 0 1280x800x24 -nolisten tcp 3>"$work/display" 2>"$work/xvfb.log" &
  xvfb_pid=$!
  for _ in $(seq 100); do [[ -s "$work/display" ]] && break; sleep 0.1; done
  [[ -s "$work/display" ]] || { fail "Xvfb did not start: $(tail -2 "$work/xvfb.log")"; cleanup_lab; return 1; }
  export DISPLAY=":$(cat "$work/display")"
  # -displayfd can name the display a moment before it takes connections (seen under load with
  # several servers starting at once): wait until a client gets in, then start the window manager,
  # and start it again if it gave up before the server answered.
  for _ in $(seq 100); do xprop -root >/dev/null 2>&1 && break; sleep 0.1; done
  local wm_up=""
  for _ in 1 2 3; do
    openbox --sm-disable >"$work/openbox.log" 2>&1 &
    wm_pid=$!
    for _ in $(seq 100); do
      xprop -root _NET_SUPPORTING_WM_CHECK 2>/dev/null | grep -q "window id" && { wm_up=1; break; }
      kill -0 "$wm_pid" 2>/dev/null || break
      sleep 0.1
    done
    [[ -n "$wm_up" ]] && break
    kill "$wm_pid" 2>/dev/null; wait "$wm_pid" 2>/dev/null
  done
  [[ -n "$wm_up" ]] || { fail "openbox did not start: $(tail -2 "$work/openbox.log")"; cleanup_lab; return 1; }

  # The lab's own scene, in a folder of its own (models/ and textures/ linked), and the variants it cycles through.
  local scenes="$work/scenes"
  mkdir -p "$scenes"
  ln -s "$root/scenes/models" "$scenes/models"
  [ -d "$root/scenes/textures" ] && ln -s "$root/scenes/textures" "$scenes/textures"  # lab 3's images
  local base="$root/scenes/$lab.json" scene="$scenes/scene.json"
  cp "$base" "$scene"
  local -a goods=("$base")
  local material; material="$(jq -r '.materials | keys[0]' "$base")"
  jq --arg m "$material" '.objects += [{"mesh": "torus", "material": $m, "position": [0, 2.5, 0]}]' "$base" >"$scenes/good_object.json"
  goods+=("$scenes/good_object.json")
  if [[ "$lab" != lab1_* ]]; then  # from lab 2 on: lights come and go through the scene file
    jq '.lights += [{"type": "point", "position": [0, 3, 2], "color": [1, 0.6, 0.3], "intensity": 3}]' "$base" >"$scenes/good_light_added.json"
    jq '.lights += [{"type": "point", "position": [0, 3, 2], "intensity": 3},
                    {"type": "spot", "position": [2, 4, 2], "direction": [-1, -2, -1], "intensity": 5}]' "$base" >"$scenes/good_two_added.json"
    jq '.lights |= .[1:]' "$base" >"$scenes/good_light_removed.json"
    jq '.lights = []' "$base" >"$scenes/good_no_lights.json"
    goods+=("$scenes/good_light_added.json" "$base" "$scenes/good_two_added.json" "$scenes/good_light_removed.json"
            "$scenes/good_no_lights.json")
  fi
  if [[ "$lab" != lab[123]_* ]]; then  # from lab 4 on: shadows switched off and on, filtered, translucent
    jq '.lights |= map(.cast_shadows = false)' "$base" >"$scenes/good_shadows_off.json"
    jq '.lights |= map(.cast_shadows = true | .shadow = ((.shadow // {}) + {"resolution": 256, "pcf": 5, "filter": "bilinear"}))' \
      "$base" >"$scenes/good_shadows_all_pcf5.json"
    jq '.objects |= map(.cast_shadows = false)' "$base" >"$scenes/good_no_casters.json"
    jq '.materials |= map_values(.opacity = 0.5)' "$base" >"$scenes/good_translucent.json"
    goods+=("$scenes/good_shadows_off.json" "$base" "$scenes/good_shadows_all_pcf5.json" "$scenes/good_no_casters.json"
            "$scenes/good_translucent.json")
  fi
  head -c "$(( $(wc -c <"$base") / 2 ))" "$base" >"$scenes/broken_truncated.json"
  jq '.camera.near = -1' "$base" >"$scenes/broken_near.json"
  local -a brokens=("$scenes/broken_truncated.json" "$scenes/broken_near.json")

  local status="$work/status"
  local validate=(--validate)
  [[ -n "${SOAK_NO_VALIDATE:-}" ]] && validate=()  # diagnosis only: the lab's memory without the layer's
  LAB_STATUS_FILE="$status" "$exe" "${validate[@]}" --scene "$scene" >"$work/stdout" 2>"$work/stderr" &
  lab_pid=$!
  local rss_log="$work/rss" rss_rest="$work/rss_rest"
  ( while kill -0 "$lab_pid" 2>/dev/null; do
      rss=$(awk '/^VmRSS:/ { print $2 }' "/proc/$lab_pid/status" 2>/dev/null || true)
      [[ -n "$rss" ]] && echo "$(date +%s.%N) $rss $(awk '/^RssAnon:/ { print $2 }' "/proc/$lab_pid/status" 2>/dev/null)"
      sleep "$sample_s"
    done >"$rss_log" ) &
  sampler_pid=$!
  local started; started="$(now)"

  # ---- helpers: what the lab said last, and waiting for an answer
  local frame=0 width=0 height=0 idle=0
  read_status() {
    local line=""
    line="$(cat "$status" 2>/dev/null || true)"
    if [[ "$line" =~ frame=([0-9]+)\ width=([0-9]+)\ height=([0-9]+)(\ idle)? ]]; then
      frame=${BASH_REMATCH[1]} width=${BASH_REMATCH[2]} height=${BASH_REMATCH[3]}
      idle=$([[ -n "${BASH_REMATCH[4]}" ]] && echo 1 || echo 0)
    fi
  }
  alive() { kill -0 "$lab_pid" 2>/dev/null; }
  declare -A worst=() count=()
  # answered KIND CONDITION...: waits until CONDITION holds; records the time it took.
  answered() {
    local kind="$1"; shift
    local t0; t0="$(now)"
    while true; do
      read_status
      if "$@"; then break; fi
      alive || { fail "$kind: the lab died: $(tail -3 "$work/stderr")"; return 1; }
      if awk -v e="$(elapsed "$t0")" -v l="$answer_s" 'BEGIN { exit !(e > l) }'; then
        fail "$kind: no answer within ${answer_s} s (status: $(cat "$status" 2>/dev/null))"
        if command -v gdb >/dev/null; then  # where it hangs, for the report
          timeout 60 gdb -batch -p "$lab_pid" -ex "thread apply all bt" >"$work/hang_backtrace.txt" 2>&1 || true
          echo "soak: $lab: backtraces of the hanging lab in $work/hang_backtrace.txt"
        fi
        return 1
      fi
      sleep 0.05
    done
    local took; took="$(elapsed "$t0")"
    count[$kind]=$(( ${count[$kind]:-0} + 1 ))
    if awk -v a="$took" -v b="${worst[$kind]:-0}" 'BEGIN { exit !(a > b) }'; then worst[$kind]="$took"; fi
  }
  local before=0
  frame_after() { ((frame > before)); }
  size_is() { ((width == want_w && height == want_h && frame > before)); }
  local out_lines=0 err_lines=0
  reload_seen() {
    (($(grep -c "^reloaded " "$work/stdout" || true) > out_lines)) && return 0
    (($(grep -c "^reload failed" "$work/stderr" || true) > err_lines)) && return 0
    return 1
  }
  mark() { read_status; before=$frame; }
  # Resident memory at rest: right after an input that is answered by a frame drawn (a resize, a
  # key, a drag...), so that the renderer in use has drawn at least once. Not after a reload: a new
  # renderer's images take memory only when first written (lab 4's shadow maps, about 100 MB, at
  # its first frame), and the sampler above also catches moments in the middle of a reload, when
  # the old and the new renderer both exist. Its quarters' medians therefore move with how many of
  # its samples fell just before or into a reload (lab 4: 320 or 420 MB).
  # At rest means idle: the lab marks its status line " idle" once it has finished its frames and
  # given freed memory back (malloc_trim, common/lab_app.cpp); the sample waits for that (at most
  # 2 s; a sample that never saw it is still taken and counted in not_idle). Read straight after
  # the frame instead, a sample caught up to ~40 MB of freed but not yet trimmed heap in lab 3
  # (peaks 193 MB against 155 MB), and the quarters' medians moved by that, not by what is kept.
  local not_idle=0
  rest_sample() {
    local rss t0
    t0="$(now)"
    until read_status; ((idle)); do
      if awk -v e="$(elapsed "$t0")" 'BEGIN { exit !(e > 2) }'; then not_idle=$((not_idle + 1)); break; fi
      sleep 0.02
    done
    rss=$(awk '/^VmRSS:/ { print $2 }' "/proc/$lab_pid/status" 2>/dev/null || true)
    [[ -n "$rss" ]] && echo "$(now) $rss $loaded_scene" >>"$rss_rest"
    return 0
  }

  # The window (it may take a while to appear: Vulkan start-up with validation).
  local wid=""
  for _ in $(seq 300); do
    wid="$(xdotool search --onlyvisible --pid "$lab_pid" 2>/dev/null | head -1 || true)"
    [[ -n "$wid" ]] && break
    alive || break
    sleep 0.1
  done
  [[ -n "$wid" ]] || { fail "no window appeared: $(tail -3 "$work/stderr")"; cleanup_lab; return 1; }
  # The first frame: start-up (shader compilation, uploads, lab 4's shadow pipelines), not an
  # answer to an input, so it gets SOAK_START_S (default 60 s) on a loaded machine.
  local answer_input_s="$answer_s"
  answer_s="$start_s"
  before=0; answered start frame_after || { answer_s="$answer_input_s"; cleanup_lab; return 1; }
  answer_s="$answer_input_s"

  local want_w=0 want_h=0
  resize() {
    want_w=$1 want_h=$2
    mark
    xdo windowsize "$wid" "$want_w" "$want_h"
    answered "resize" size_is
  }
  key_hold() {  # KEY SECONDS: a key held down, as a user walks the camera
    xdo windowactivate --sync "$wid" >/dev/null 2>&1 || true
    mark
    xdo keydown "$1"; sleep "$2"; xdo keyup "$1"
    answered "key $1" frame_after
  }
  drag() {  # a left-button drag in the lower right of the window, away from the UI panels
    xdo windowactivate --sync "$wid" >/dev/null 2>&1 || true
    local x=$(( width * (55 + RANDOM % 30) / 100 )) y=$(( height * (60 + RANDOM % 30) / 100 ))
    mark
    xdo mousemove --window "$wid" "$x" "$y" mousedown 1
    for _ in 1 2 3 4 5 6; do xdo mousemove_relative -- $(( RANDOM % 41 - 20 )) $(( RANDOM % 31 - 15 )); sleep 0.03; done
    xdo mouseup 1
    answered "drag" frame_after
  }
  wheel() {
    xdo windowactivate --sync "$wid" >/dev/null 2>&1 || true
    local x=$(( width * 3 / 4 )) y=$(( height * 3 / 4 ))
    mark
    xdo mousemove --window "$wid" "$x" "$y" click "$(( 4 + RANDOM % 2 ))"
    answered "wheel" frame_after
  }
  minimize_restore() {
    xdo windowminimize "$wid"
    answered "minimize" is_iconic || return 1
    sleep 0.5
    alive || { fail "the lab died while minimized"; return 1; }
    mark
    xdo windowactivate --sync "$wid" >/dev/null 2>&1 || xdo windowmap "$wid"
    answered "restore" frame_after
  }
  is_iconic() { xprop -id "$wid" WM_STATE 2>/dev/null | grep -q "Iconic"; }
  local goods_i=0 brokens_i=0 next_good=1
  local loaded_scene; loaded_scene="$(basename "$base" .json)"  # the scene variant the lab shows now
  write_scene() {  # alternately a good and a broken scene, written whole (rename) like an editor
    local from
    if ((next_good)); then
      goods_i=$(( (goods_i + 1) % ${#goods[@]} )); from="${goods[$goods_i]}"
    else
      from="${brokens[$brokens_i]}"; brokens_i=$(( (brokens_i + 1) % ${#brokens[@]} ))
    fi
    local good=$next_good
    next_good=$(( 1 - next_good ))
    out_lines=$(grep -c "^reloaded " "$work/stdout" || true)
    err_lines=$(grep -c "^reload failed" "$work/stderr" || true)
    cp "$from" "$scene.tmp" && mv "$scene.tmp" "$scene"
    answered "scene $(basename "$from" .json)" reload_seen || return 1
    # A good scene must load and a broken one must be rejected (not just answered).
    local loaded; loaded=$(( $(grep -c "^reloaded " "$work/stdout" || true) > out_lines ))
    if ((good && !loaded)); then fail "good scene $(basename "$from") rejected: $(grep '^reload failed' "$work/stderr" | tail -1)"; return 1; fi
    if ((!good && loaded)); then fail "broken scene $(basename "$from") was loaded"; return 1; fi
    if ((good)); then loaded_scene="$(basename "$from" .json)"; fi
    return 0
  }
  reload_key() {
    xdo windowactivate --sync "$wid" >/dev/null 2>&1 || true
    out_lines=$(grep -c "^reloaded " "$work/stdout" || true)
    err_lines=$(grep -c "^reload failed" "$work/stderr" || true)
    xdo key r
    answered "key r (reload)" reload_seen
  }

  # ---- the soak: a fixed pseudo-random walk through the inputs until the time is up
  RANDOM=$seed
  local -a sizes=("1 1" "2 3" "64 48" "320 200" "1280 720" "333 777" "1000 10" "10 700")
  # Weighted: names repeat. SOAK_ACTIONS="resize scene" keeps only those (to find what costs memory).
  local -a actions=(resize resize tiny minimize key key key drag drag drag wheel mode mode scene scene scene scene
                    reload pause pause)
  if [[ -n "${SOAK_ACTIONS:-}" ]]; then
    local -a kept=()
    for a in "${actions[@]}"; do [[ " $SOAK_ACTIONS " == *" $a "* ]] && kept+=("$a"); done
    ((${#kept[@]})) || die "SOAK_ACTIONS='$SOAK_ACTIONS' names none of: ${actions[*]}"
    actions=("${kept[@]}")
  fi
  local steps=0
  while awk -v e="$(elapsed "$started")" -v s="$seconds" 'BEGIN { exit !(e < s) }'; do
    local action="${actions[$(( RANDOM % ${#actions[@]} ))]}"
    echo "$(elapsed "$started") $action" >>"$work/actions"
    {
    case $action in
      resize) resize ${sizes[$(( RANDOM % ${#sizes[@]} ))]} && resize 960 600 ;;
      tiny) resize 1 1 && resize 960 600 ;;
      minimize) minimize_restore ;;
      key) key_hold "$(echo w a s d space shift | tr ' ' '\n' | sed -n "$(( 1 + RANDOM % 6 ))p")" 0.$(( 1 + RANDOM % 4 )) ;;
      drag) drag ;;
      wheel) wheel ;;
      mode) key_hold c 0.05 ;;
      scene) write_scene ;;
      reload) reload_key ;;
      pause) sleep 0.5 ;;  # nothing to answer (a lab that draws on demand may draw nothing)
    esac
    } || true  # a failed step has set $failure
    [[ -n "$failure" ]] && break
    alive || { fail "the lab died: $(tail -3 "$work/stderr")"; break; }
    if grep -qi "validation" "$work/stderr"; then fail "validation message: $(grep -i -m1 validation "$work/stderr")"; break; fi
    steps=$((steps + 1))
    case $action in resize|tiny|minimize|key|drag|wheel|mode) rest_sample ;; esac
  done

  # ---- close the window as a user does (Alt+F4 through the window manager); the lab must exit 0
  local code=""
  if [[ -z "$failure" ]]; then
    xdo windowactivate --sync "$wid" >/dev/null 2>&1 || true
    xdo key alt+F4
    for _ in $(seq 300); do alive || break; sleep 0.1; done
    if alive; then
      fail "did not exit within 30 s of Alt+F4"
    else
      wait "$lab_pid" && code=0 || code=$?
      lab_pid=""
      [[ "$code" == 0 ]] || fail "exit code $code after closing: $(grep -v '^reload failed' "$work/stderr" | tail -3)"
    fi
  fi
  kill "$sampler_pid" 2>/dev/null; sampler_pid=""
  # Anything on stderr but the expected "reload failed" lines (broken scenes) is a finding.
  local unexpected; unexpected="$(grep -v '^reload failed, keeping the last good scene: ' "$work/stderr" || true)"
  if [[ -z "$failure" && -n "$unexpected" ]]; then fail "unexpected stderr: $(head -3 <<<"$unexpected")"; fi

  # ---- memory: after the warm-up, the first quarter of the time against the last, each sample
  # compared with the usual level of the scene variant it was taken with (bench/soak_memory.awk).
  # memory_figures FILE MIN [by-scene]: FILE has "time rss [scene]" lines; MIN: the fewest samples
  # after the warm-up that give a figure.
  memory_figures() {
    awk -v t0="$started" -v warm="$warmup" -v min="$2" -v by_scene="$([[ "${3:-}" == by-scene ]] && echo 1 || echo 0)" \
        -f "$root/bench/soak_memory.awk" "$1"
  }
  # Gated: the samples at rest. Reported: the samples every SOAK_SAMPLE_S seconds.
  local figures sampled
  figures="$(memory_figures "$rss_rest" "${SOAK_MIN_SAMPLES:-10}" by-scene)" || { [[ -z "$failure" ]] && fail "memory: $figures"; }
  sampled="$(memory_figures "$rss_log" 10)" || true
  local growth; growth="$(sed -n 's/.*growth_pct=\([-0-9.]*\).*/\1/p' <<<"$figures")"
  # The limit: SOAK_MEMORY_GATE percent (default 1, the issue's rule for the minutes after the first;
  # 0 = report only, for looking at a run by hand). The one-minute CTest runs use 2: their 40-s
  # window moves with the scene variant loaded at its start and at its end (lab 3's resident memory
  # steps between about 175 and 180 MB with it), so fixed labs measured -1.43 ... +0.53 % there
  # (16 runs); a 1 % gate would fail now and then on nothing. 2 % still catches a leak of lab 3's
  # old size (2.6-3 % in a minute); slower leaks show in the 10-minute run, which keeps 1 %.
  local gate="${SOAK_MEMORY_GATE:-1}"
  if awk -v g="$gate" 'BEGIN { exit !(g == 0) }'; then
    echo "soak: $lab: memory growth ${growth:-?} % reported, not gated (SOAK_MEMORY_GATE=0)"
  elif [[ -z "$failure" && -n "$growth" ]] && awk -v g="$growth" -v l="$gate" 'BEGIN { exit !(g >= l) }'; then
    fail "resident memory grew by ${growth} % after the warm-up (limit ${gate} %)"
  fi

  # Resident memory minute by minute (median of each minute's samples), for the record.
  local per_minute
  per_minute="$(awk -v t0="$started" '{ t = $1 - t0; if (t < 0) next; m = int(t / 60); n[m]++; v[m, n[m]] = $2; if (m > last) last = m }
    END { for (k = 0; k <= last; k++) { c = n[k]; if (!c) continue
            for (i = 1; i <= c; i++) a[i] = v[k, i]
            for (i = 1; i <= c; i++) for (j = i + 1; j <= c; j++) if (a[j] < a[i]) { t = a[i]; a[i] = a[j]; a[j] = t }
            printf "%s%d", (k ? " " : ""), a[int((c + 1) / 2)] } }' "$rss_log")"
  local answers=""
  for k in "${!count[@]}"; do answers+="$k=${count[$k]}x/max${worst[$k]:-0}s, "; done
  echo "soak: $lab: $(elapsed "$started") s, $steps inputs, warm-up ${warmup} s; at rest (after the idle trim; ${not_idle} samples did not see it within 2 s): $figures"
  echo "soak: $lab: every ${sample_s} s (reported, not gated): $sampled"
  echo "soak: $lab: resident memory per minute (KiB, medians): $per_minute"
  echo "soak: $lab: answers (count, slowest): ${answers%, }"
  echo "soak: $lab: $(grep -c '^reloaded ' "$work/stdout" || true) reloads, $(grep -c '^reload failed' "$work/stderr" || true) rejected scenes; last $(cat "$status")"
  cleanup_lab
  if [[ -n "$failure" ]]; then
    echo "soak: $lab: FAILED ($failure); files kept in $work"
    return 1
  fi
  if [[ -n "${SOAK_KEEP:-}" ]]; then echo "soak: $lab: files kept in $work"; else rm -rf "$work"; fi
  if [[ -n "${SOAK_NO_VALIDATE:-}" ]]; then
    echo "soak: $lab: checks passed WITHOUT validation (SOAK_NO_VALIDATE: a diagnosis run, not a pass)"
    return 1
  fi
  echo "soak: $lab: PASS"
}

result=0
for lab in "${labs[@]}"; do
  soak_lab "$lab" || result=1
done
exit "$result"
