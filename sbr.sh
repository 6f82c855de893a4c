#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# sbr's one entry point: set-up, the main job and the tests.
#
#   ./sbr.sh detect [--input DIR|VIDEO] [--out DIR] [--range A-B] [--baseline FILE]
#                   [--model FILE.sbrm --picto FILE.sbrp] [recogniser options]
#                                               the main job (docs/usage/detect.md): the recogniser
#                                               over a folder of images (default: GTSDB's
#                                               development split 00400-00599), detections,
#                                               annotated images, CAN log, summary; or over a
#                                               recorded drive's video file (its signs tracked,
#                                               out/annotated.mp4);
#                                               --baseline: an earlier version's
#                                               detections_all.txt, compared in evaluation.txt;
#                                               other options go to sbr_detect (--threshold,
#                                               --views, ...: sbr_detect --help)
#   ./sbr.sh dashboard [--log FILE | --socketcan IF | --virtual CH] [options]
#                                               the reference dashboard (dashboard/), default:
#                                               replay out/sbr_can.log; --help for options
#   ./sbr.sh train [--range A-B[,C-D]] [--out DIR]
#                                               relearn the built-in prototype library and
#                                               its class stage (pictogram classifier) on
#                                               GTSDB 00000-00599 (lib/models); another
#                                               --range writes model files only (build/)
#   ./sbr.sh crossval [--out DIR] [--baseline DIR] [--models DIR] [--*-args "..."]
#                                               3-fold cross-validation on GTSDB 00000-00599
#                                               (docs/usage/crossval.md): both models
#                                               trained per fold, figures per fold and
#                                               summed; --baseline: an earlier run's DIR
#   ./sbr.sh robustness [--models DIR] [--out DIR] [--baseline DIR] [--cache DIR]
#                       [--corruptions a,b] [--severities 1,2,3] [--detect-args "..."]
#                                               the robustness benchmark (docs/usage/robustness.md):
#                                               a cross-validation's fold models (--models,
#                                               default out/crossval, trained first when it
#                                               holds none) on corrupted copies of each
#                                               fold's test images (albumentations, seeded
#                                               per image, cached); F1 per corruption and
#                                               severity, mPC, rPC, the plot
#   ./sbr.sh cost [--range A-B] [--out DIR] [--no-wall] [--no-m4] [-- sbr_detect options]
#                                               the cost benchmark (docs/usage/cost.md):
#                                               instructions per frame and per stage under
#                                               callgrind (x86-64) and qemu -icount
#                                               (Cortex-M4F) on 00400-00419, wall clock of
#                                               sbr_detect --repeat 3 on 00400-00599
#   ./sbr.sh track [sbr_track options]          the channel tracker against Kalman and particle
#                                               filters on KITTI tracking (default 0006-0010)
#   ./sbr.sh learn-tracker                      relearn the tracker's motion model (0000-0005)
#   ./sbr.sh test                               every test: native, sanitizers, Cortex-M4
#                                               (qemu), armhf (qemu user), the gates, the
#                                               build matrix (every build type, gcc, clang,
#                                               arm-none-eabi) and a fuzz smoke run
#   ./sbr.sh fuzz [--minutes N] [--target NAME[,NAME]]
#                                               the libFuzzer harnesses (tests/fuzz) for N
#                                               minutes a target (default 5), resuming the
#                                               corpus in build/fuzz-corpus; a table of
#                                               executions, coverage and findings
#   ./sbr.sh setup                              only install what is missing
#
# Each command installs the Debian packages it needs (apt-get, as root or through sudo)
# and fetches Unity itself, so both work on a fresh Debian 12 machine.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$ROOT"
BUILD="${SBR_BUILD_ROOT:-$ROOT/build}"
# The read-only data sets (GTSDB, GTSRB, MPEG-7, KITTI tracking), beside the project.
DATA="${SBR_DATA_ROOT:-$ROOT/../shared/data}"
JOBS="$(nproc 2>/dev/null || echo 2)"

PACKAGES=(cmake ninja-build gcc g++ make pkg-config python3 python3-pip python3-venv can-utils
          gcc-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm
          gcc-arm-linux-gnueabihf libc6-dev-armhf-cross qemu-user
          libfftw3-dev libkissfft-dev cppcheck libopencv-dev libcli11-dev chromium clang libclang-rt-14-dev valgrind)

log() { printf '\n== %s\n' "$*"; }

# The usage text: this file's head comment without its '#' marks.
usage() { sed -n '3,/^set -euo/{/^set -euo/!p}' "$0" | sed -E 's/^# ?//'; }

# need_file OPTION PATH: a file option's file must be there before anything runs.
need_file() {
  if [ ! -f "$2" ]; then
    echo "sbr.sh: $1 $2: no such file (nothing was run)" >&2
    exit 2
  fi
}

# need_value OPTION COUNT: an option that takes a value must have one (COUNT: the
# arguments left, the option included).
need_value() {
  if [ "$2" -lt 2 ]; then
    echo "sbr.sh: $1 needs a value (./sbr.sh --help)" >&2
    exit 2
  fi
}

# detection_file_problem FILE: the first line of a detection file that is not
# "NNNNN.ext;left;top;right;bottom;class[;score]" (the rule of sbr_eval's reader,
# host_tools/common/detection.cpp), as "LINE: TEXT"; nothing when every line is one.
detection_file_problem() {
  awk 'BEGIN { n = "[-+]?([0-9]+[.]?[0-9]*|[.][0-9]+)([eE][-+]?[0-9]+)?"
               re = "^[0-9][^;]*;" n ";" n ";" n ";" n ";[+]?[0-9]+([.]0*)?(;" n ")?$" }
       { sub(/\r$/, "") }
       $0 == "" || /^#/ { next }
       $0 !~ re { print NR ": " substr($0, 1, 80); exit }' "$1"
}

# The images of GTSDB that the built-in models (lib/models) are trained on.
SHIPPED_TRAINING="0-599"

# What apt, dpkg and pip print while setting up goes to this log, not to the terminal.
SETUP_LOG="$BUILD/setup.log"

# logged CMD...: runs CMD with its output appended to the set-up log; on failure, the
# log's last lines are shown.
logged() {
  if ! "$@" >> "$SETUP_LOG" 2>&1; then
    echo "sbr.sh: set-up step failed: $* (the last lines of $SETUP_LOG:)" >&2
    tail -n 25 "$SETUP_LOG" >&2
    return 1
  fi
}

# install_packages P...: the Debian packages of the list that are missing.
install_packages() {
  local missing=()
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ "${#missing[@]}" -gt 0 ]; then
    mkdir -p "$BUILD"
    log "installing ${#missing[@]} Debian packages: ${missing[*]} (output: $SETUP_LOG)"
    local sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    logged $sudo apt-get update -qq
    logged $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
  fi
}

setup() {
  install_packages "${PACKAGES[@]}"
  mkdir -p "$BUILD"
  setup_venv
}

# The pinned Python packages (dashboard: cantools, python-can; tests: pytest, Playwright)
# in build/venv, rebuilt when a requirements file changes.
setup_venv() {
  local venv="$BUILD/venv" req="$ROOT/tests/python/requirements.txt"
  local want
  want="$(cat "$req" "$ROOT/dashboard/requirements.txt" "$ROOT/dashboard/pyproject.toml")"
  if [ ! -x "$venv/bin/python" ] || [ "$want" != "$(cat "$venv/requirements.installed" 2>/dev/null)" ]; then
    log "python environment: $venv (output: $SETUP_LOG)"
    rm -rf "$venv"
    logged python3 -m venv "$venv"
    logged "$venv/bin/pip" install --disable-pip-version-check -r "$req"
    # the dashboard package and its console script, editable: the checkout's code runs
    logged "$venv/bin/pip" install --disable-pip-version-check --no-build-isolation --no-deps -e "$ROOT/dashboard"
    printf '%s\n' "$want" > "$venv/requirements.installed"
  fi
}

# configure_build PRESET: the build tree of a configure preset of CMakePresets.json (every
# build configuration is there: cmake --list-presets) in $BUILD/PRESET. The paths the
# presets give under build/ follow SBR_BUILD_ROOT when it is set.
configure_build() {
  local name="$1" paths=()
  case "$name" in
    native) paths=(-DSBR_VENV_PYTHON="$BUILD/venv/bin/python"
                   -DSBR_COST_M4_ELF="$BUILD/cortex-m4/tests/bench_m4/sbr_cost_m4.elf"
                   -DSBR_DATA_DIR="$DATA") ;;
    sanitize) paths=(-DUNITY_ROOT="$(unity_root)") ;;
    cortex-m4|armhf) paths=(-DUNITY_ROOT="$(unity_root)" -DSBR_HOST_TESTS_DIR="$BUILD/native/tests") ;;
  esac
  log "build $name"
  cmake --preset "$name" -S "$ROOT" -B "$BUILD/$name" ${paths[@]+"${paths[@]}"} > "$BUILD/$name.configure.log" 2>&1 \
    || { cat "$BUILD/$name.configure.log"; return 1; }
  cmake --build "$BUILD/$name" -j "$JOBS"
}

# The native build with tests and host tools (the test command, detect and train share it).
build_native() { configure_build native; }

unity_root() { echo "$BUILD/native/_deps/unity"; }

# The fuzz harnesses (clang, libFuzzer + ASan + UBSan) in build/fuzz.
build_fuzz() { configure_build fuzz; }

# Seed corpora from real data (GTSDB crops, MPEG-7 contours, the models, the DBC's
# frames) in build/fuzz-seeds; needs the native build (sbr_fuzz_seeds) and the venv.
make_fuzz_seeds() {
  local seeds="$BUILD/fuzz-seeds" data="$DATA"
  local args=(--out "$seeds")
  [ -d "$data/gtsdb" ] && args+=(--gtsdb "$data/gtsdb")
  [ -d "$data/mpeg7" ] && args+=(--mpeg7 "$data/mpeg7")
  rm -rf "$seeds"
  "$BUILD/native/host_tools/sbr_fuzz_seeds" "${args[@]}"
  "$BUILD/venv/bin/python" "$ROOT/tests/fuzz/can_seeds.py" --dbc "$ROOT/dbc/sbr.dbc" --out "$seeds/can"
}

cmd_test() {
  case "${1:-}" in
    -h|--help) usage; return 0 ;;
    "") ;;
    *) echo "unknown option $1 (./sbr.sh test takes none)" >&2; return 2 ;;
  esac
  setup
  mkdir -p "$BUILD"
  local failed=0
  build_native
  configure_build sanitize
  configure_build cortex-m4
  configure_build armhf
  configure_build cortex-m7
  build_fuzz

  local junit=()
  for name in native sanitize cortex-m4 armhf; do
    log "ctest $name"
    local out="$BUILD/$name.ctest.log"
    # as the test presets of CMakePresets.json run it; the JUnit file keeps each test's
    # whole output for the summary (tests/test_summary.py)
    if ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
       ctest --test-dir "$BUILD/$name" --output-on-failure -j "$JOBS" --output-junit "$BUILD/$name.junit.xml" \
         --test-output-size-passed 1000000 --test-output-size-failed 1000000 > "$out" 2>&1; then :; else failed=1; fi
    grep -E "Test +#|tests passed|FAILED|\*\*\*" "$out" || true
    junit+=(--ctest "$name=$BUILD/$name.junit.xml")
  done
  log "Cortex-M4 size / static RAM / stack report"
  ctest --test-dir "$BUILD/cortex-m4" -R "report_cortex_m_size_stack|gate_fft_tables_dropped" -V 2>/dev/null \
    | sed -nE 's/^[0-9]+: //p' | grep -vE "^(Test command|Working Directory|Test timeout)" || true
  log "core symbols (no heap / no stdio)"
  for name in native cortex-m4; do
    ctest --test-dir "$BUILD/$name" -R "^gate_core_symbols$" -V 2>/dev/null | sed -nE 's/^[0-9]+: (OK|FAIL|.* external references).*/&/p' | sed -E 's/^[0-9]+: /'"$name"': /'
  done
  log "unit sizes (cmake/unit_report.py)"
  ctest --test-dir "$BUILD/native" -R "^report_units$" -V 2>/dev/null | sed -nE 's/^[0-9]+: //p' \
    | grep -vE "^(Test command|Working Directory|Test timeout)" || true
  # every build type of the core with -Werror: gcc, clang, arm-none-eabi
  log "build matrix"
  if python3 "$ROOT/cmake/build_matrix.py" --source "$ROOT" --work "$BUILD/matrix" --jobs "$JOBS" \
       > "$BUILD/matrix.log" 2>&1; then :; else failed=1; fi
  grep -vE "^build matrix: " "$BUILD/matrix.log" || true

  # the fuzz harnesses, a fixed number of runs each after the seeds (fresh corpus)
  log "fuzz smoke"
  make_fuzz_seeds
  rm -rf "$BUILD/fuzz-smoke"
  if python3 "$ROOT/tests/fuzz/run_fuzz.py" --bin "$BUILD/fuzz/tests/fuzz" --corpus "$BUILD/fuzz-smoke" \
       --seeds "$BUILD/fuzz-seeds" --runs "${SBR_FUZZ_SMOKE_RUNS:-3000}" --jobs "$JOBS" \
       > "$BUILD/fuzz-smoke.log" 2>&1; then :; else failed=1; fi
  grep -vE "^fuzz: " "$BUILD/fuzz-smoke.log" || true

  log "summary"
  echo "cortex-m7: core built (-mcpu=cortex-m7 -mfpu=fpv5-sp-d16), no tests run"
  # every part that decides the exit status: the ctest entries of the four builds, the
  # build matrix's builds, the fuzz harnesses' smoke runs
  python3 "$ROOT/tests/test_summary.py" "${junit[@]}" --matrix "$BUILD/matrix.log" \
    --fuzz "$BUILD/fuzz-smoke.log" || failed=1
  echo "set-up output: $SETUP_LOG; each build's test log: $BUILD/<build>.ctest.log"
  return "$failed"
}

cmd_fuzz() {
  local minutes=5 targets=""
  while [ $# -gt 0 ]; do
    case "$1" in
      --minutes) need_value "$1" "$#"; minutes="$2"; shift 2 ;;
      --target) need_value "$1" "$#"; targets="$2"; shift 2 ;;
      -h|--help) usage; return 0 ;;
      *) echo "unknown option $1" >&2; return 2 ;;
    esac
  done
  if ! [[ "$minutes" =~ ^[0-9]+$ ]] || [ "$minutes" -lt 1 ] || [ "$minutes" -gt 1440 ]; then
    echo "--minutes: a whole number of minutes, 1 .. 1440 (got '$minutes')" >&2
    return 2
  fi
  if [ -n "$targets" ] && ! [[ "$targets" =~ ^[a-z_]+(,[a-z_]+)*$ ]]; then
    echo "--target: harness names separated by commas (got '$targets')" >&2
    return 2
  fi
  setup
  build_native
  build_fuzz
  make_fuzz_seeds
  log "fuzzing ${targets:-every harness} for $minutes min a target (corpus: $BUILD/fuzz-corpus)"
  python3 "$ROOT/tests/fuzz/run_fuzz.py" --bin "$BUILD/fuzz/tests/fuzz" --corpus "$BUILD/fuzz-corpus" \
    --seeds "$BUILD/fuzz-seeds" ${targets:+--targets "$targets"} --seconds "$((minutes * 60))" \
    --jobs "$JOBS" --report "$BUILD/fuzz-report.md"
}

# --out of ./sbr.sh detect: a folder or nothing yet (a file there is refused, nothing written)
out_folder_ok() {
  if [ -e "$1" ] && [ ! -d "$1" ]; then
    echo "sbr.sh detect: --out $1 is a file, not a folder (nothing was written)" >&2
    return 1
  fi
}

# ./sbr.sh detect --input VIDEO: a recorded drive (sbr_detect reads the frames at the
# file's times, tracks the signs and writes the annotated video; no ground truth)
cmd_detect_video() {
  local input="$1" out="$2" status=0
  shift 2
  out_folder_ok "$out" || return 2
  setup
  mkdir -p "$BUILD" "$out"
  build_native
  log "sbr_detect over the video $input"
  # status 3: the video ended early (named); what was read is written, the status kept
  "$BUILD/native/host_tools/sbr_detect" --input "$input" --detections "$out/detections.txt" \
      --annotated-video "$out/annotated.mp4" --canlog "$out/sbr_can.log" --summary "$out/summary.txt" "$@" \
    || status=$?
  if [ "$status" -eq 0 ] || [ "$status" -eq 3 ]; then
    echo "wrote: $out/detections.txt, $out/annotated.mp4, $out/sbr_can.log, $out/summary.txt"
  fi
  return "$status"
}

cmd_detect() {
  local input="" out="$ROOT/out" range="" baseline="" models=() note="" extra=()
  while [ $# -gt 0 ]; do
    case "$1" in
      --input) need_value "$1" "$#"; input="$2"; shift 2 ;;
      --model|--picto) need_value "$1" "$#"; need_file "$1" "$2"
        models+=("$1" "$(cd "$(dirname "$2")" && pwd)/$(basename "$2")"); shift 2 ;;
      --out) need_value "$1" "$#"; out="$2"; shift 2 ;;
      --range) need_value "$1" "$#"; range="$2"; shift 2 ;;
      --baseline) need_value "$1" "$#"; need_file "$1" "$2"
        baseline="$(cd "$(dirname "$2")" && pwd)/$(basename "$2")"; shift 2 ;;
      -h|--help) usage; return 0 ;;
      # the recogniser's options (and their values) go to sbr_detect, which checks them
      *) extra+=("$1"); shift ;;
    esac
  done
  if [ -n "$input" ] && [ -f "$input" ]; then
    cmd_detect_video "$input" "$out" ${models[@]+"${models[@]}"} ${extra[@]+"${extra[@]}"}
    return $?
  fi
  if [ -n "$input" ] && [ ! -d "$input" ]; then
    echo "sbr.sh detect: --input $input: no such folder or video file (nothing was written)" >&2
    return 2
  fi
  if [ -n "$baseline" ]; then
    # read before anything runs: a malformed baseline is refused now, not after every image
    local bad
    bad="$(detection_file_problem "$baseline")"
    if [ -n "$bad" ]; then
      echo "sbr.sh detect: --baseline $baseline:$bad: not a detection line (NNNNN.ext;left;top;right;bottom;class[;score]; nothing was run)" >&2
      return 2
    fi
  fi
  if [ -z "$input" ]; then
    if [ -d "$DATA/gtsdb" ]; then
      input="$DATA/gtsdb"
      # the development split by default (a fixed, quick set of 200 images)
      [ -n "$range" ] || range="400-599"
      if [ "${#models[@]}" -eq 0 ]; then
        note="note: the built-in models are trained on GTSDB 00000-00599 (./sbr.sh train), these images
included: the figures are training-set figures, not what unseen images give. For those, see
./sbr.sh crossval (docs/usage/crossval.md); for the development-split figures, models trained
on 00000-00399: ./sbr.sh train --range 0-399, then ./sbr.sh detect --model FILE --picto FILE."
      fi
    else
      echo "no --input folder given and no GTSDB copy in ../shared/data/gtsdb" >&2
      return 2
    fi
  fi
  local imgdir="$input"
  [ -d "$input/FullIJCNN2013" ] && imgdir="$input/FullIJCNN2013"
  # -L: images linked into the folder count (sbr_detect reads them too)
  if [ -z "$(find -L "$imgdir" -maxdepth 1 -type f \( -iname '*.jpg' -o -iname '*.jpeg' -o -iname '*.png' -o -iname '*.ppm' \) -print -quit)" ]; then
    echo "sbr.sh detect: no .jpg, .jpeg, .png or .ppm images in $imgdir (nothing was written)" >&2
    return 2
  fi
  out_folder_ok "$out" || return 2
  setup
  mkdir -p "$BUILD" "$out"
  build_native
  local tools="$BUILD/native/host_tools"
  log "sbr_detect over $input${range:+ (images $range)}"
  local gt="" status=0
  for g in "$input/gt.txt" "$input/FullIJCNN2013/gt.txt"; do [ -f "$g" ] && gt="$g" && break; done
  # an earlier run's files stay until this run has written its own: sbr_detect writes each
  # file under a temporary name and renames it at the end, the pictures go to a folder of
  # their own that replaces annotated/ afterwards; a run that fails leaves them as they were
  local pictures="$out/annotated.tmp-$$"
  rm -rf "$pictures"
  # status 3: some images failed (reported); the rest is evaluated, the status kept
  "$tools/sbr_detect" --input "$input" ${range:+--range "$range"} \
      --detections "$out/detections.txt" --all-detections "$out/detections_all.txt" \
      --annotated "$pictures" ${gt:+--overview "$out/overview.png"} \
      --canlog "$out/sbr_can.log" --summary "$out/summary.txt" \
      ${models[@]+"${models[@]}"} ${extra[@]+"${extra[@]}"} || status=$?
  if [ "$status" -ne 0 ] && [ "$status" -ne 3 ]; then
    rm -rf "$pictures"
    return "$status"
  fi
  # the folder holds this run's files only: the earlier run's that this one did not write go
  rm -rf "$out/annotated"
  mv "$pictures" "$out/annotated"
  [ -n "$gt" ] || rm -f "$out"/{overview.png,evaluation.txt,pr_curve.png}
  rm -f "$out/evaluation.txt.new"
  if [ -n "$note" ]; then
    { echo "$note"; echo; cat "$out/summary.txt"; } > "$out/summary.txt.new" && mv "$out/summary.txt.new" "$out/summary.txt"
    printf '\n%s\n' "$note"
  fi
  if [ -n "$gt" ]; then
    log "sbr_eval against $gt"
    local thr
    thr="$(sed -nE 's/.*operating point score >= ([0-9.]+).*/\1/p' "$out/summary.txt" | head -1)"
    "$tools/sbr_eval" --detections "$out/detections_all.txt" --gt "$gt" \
        ${range:+--range "$range"} --threshold "${thr:-0}" --plot "$out/pr_curve.png" \
        ${baseline:+--baseline "$baseline"} > "$out/evaluation.txt.new"
    { [ -z "$note" ] || printf '%s\n\n' "$note"; cat "$out/evaluation.txt.new"; } | tee "$out/evaluation.txt"
    { echo; echo "evaluation (sbr_eval, operating point score >= ${thr:-0}):"; cat "$out/evaluation.txt.new"; } >> "$out/summary.txt"
    rm -f "$out/evaluation.txt.new"
  fi
  local wrote=()
  for f in detections.txt detections_all.txt annotated sbr_can.log summary.txt evaluation.txt pr_curve.png overview.png; do
    if [ -d "$out/$f" ]; then wrote+=("$f/"); elif [ -e "$out/$f" ]; then wrote+=("$f"); fi
  done
  log "wrote $out: $(printf '%s, ' "${wrote[@]}" | sed 's/, $//')"
  [ "$status" -eq 0 ] || echo "sbr.sh detect: some images failed (listed in $out/summary.txt)" >&2
  return "$status"
}

cmd_train() {
  local range="$SHIPPED_TRAINING" out="" args=()
  while [ $# -gt 0 ]; do
    case "$1" in
      --range) need_value "$1" "$#"; range="$2"; shift 2 ;;
      --out) need_value "$1" "$#"; out="$2"; shift 2 ;;
      *) args+=("$1"); shift ;;
    esac
  done
  setup
  build_native
  local tools="$BUILD/native/host_tools" data="$DATA/gtsdb" c_model=() c_picto=()
  if [ "$range" = "$SHIPPED_TRAINING" ] && [ -z "$out" ]; then
    # the shipped models: the generated tables in lib/models and their files in build/
    out="$BUILD"
    c_model=(--out-c "$ROOT/lib/models/sbr_model_gtsdb.c")
    c_picto=(--out-c "$ROOT/lib/models/sbr_picto_gtsdb.c")
  else
    # other images (e.g. --range 0-399 for the development-split figures): model files
    # only, for sbr_detect --model/--picto and ./sbr.sh detect --model/--picto
    out="${out:-$BUILD/models-$range}"
  fi
  mkdir -p "$out"
  log "sbr_train on GTSDB $range -> $out/sbr_gtsdb.sbrm${c_model:+, lib/models/sbr_model_gtsdb.c}"
  "$tools/sbr_train" --data "$data" --range "$range" "${c_model[@]}" --out-model "$out/sbr_gtsdb.sbrm" \
      ${args[@]+"${args[@]}"}
  # the class stage learns from the new library's candidates (its file, so no rebuild)
  log "sbr_train_picto on GTSDB $range -> $out/sbr_picto_gtsdb.sbrp${c_picto:+, lib/models/sbr_picto_gtsdb.c}"
  # seed 2: see docs/results/recognition.md (training noise; the shipped figures are this seed's)
  # GTSRB's training tracks are sign samples too (docs/usage/gtsrb.md): the built-in class
  # stage is trained with them
  local gtsrb=(--gtsrb "$DATA/gtsrb")
  if [ ! -d "$DATA/gtsrb" ]; then
    echo "sbr.sh train: note: no GTSRB in $DATA/gtsrb: the class stage learns from GTSDB alone (not the built-in one's recipe)" >&2
    gtsrb=(--no-gtsrb)
  fi
  "$tools/sbr_train_picto" --data "$data" "${gtsrb[@]}" --range "$range" --seed 2 --model "$out/sbr_gtsdb.sbrm" \
      "${c_picto[@]}" --out "$out/sbr_picto_gtsdb.sbrp"
  if [ "${#c_model[@]}" -gt 0 ]; then
    cmake --build "$BUILD/native" -j "$JOBS"
  else
    log "use them with: ./sbr.sh detect --model $out/sbr_gtsdb.sbrm --picto $out/sbr_picto_gtsdb.sbrp"
  fi
}

cmd_crossval() {
  setup
  build_native
  local out="$ROOT/out/crossval" args=()
  while [ $# -gt 0 ]; do
    case "$1" in
      --out) need_value "$1" "$#"; out="$2"; shift 2 ;;
      *) args+=("$1"); shift ;;
    esac
  done
  # each fold's class stage is also scored on GTSRB's validation tracks, when GTSRB is there
  local gtsrb=()
  if [ -d "$DATA/gtsrb" ] && ! printf '%s\n' ${args[@]+"${args[@]}"} | grep -qx -- '--gtsrb'; then
    gtsrb=(--gtsrb "$DATA/gtsrb")
  fi
  log "cross-validation on GTSDB 00000-00599 -> $out"
  python3 "$ROOT/host_tools/crossval/sbr_crossval.py" --tools "$BUILD/native/host_tools" \
      --data "$DATA/gtsdb" --out "$out" ${gtsrb[@]+"${gtsrb[@]}"} ${args[@]+"${args[@]}"}
}

cmd_robustness() {
  local out="$ROOT/out/robustness" models="" args=()
  while [ $# -gt 0 ]; do
    case "$1" in
      --out) need_value "$1" "$#"; out="$2"; shift 2 ;;
      --models) need_value "$1" "$#"; models="$2"; shift 2 ;;
      *) args+=("$1"); shift ;;
    esac
  done
  setup
  build_native
  if [ -z "$models" ]; then
    models="$ROOT/out/crossval"
    if [ ! -f "$models/fold1/picto.sbrp" ]; then
      log "no fold models in $models: the cross-validation first (./sbr.sh crossval)"
      cmd_crossval --out "$models"
    fi
  fi
  log "robustness benchmark -> $out (fold models: $models)"
  "$BUILD/venv/bin/python" "$ROOT/host_tools/robustness/sbr_robustness.py" --tools "$BUILD/native/host_tools" \
      --data "$DATA/gtsdb" --models "$models" --out "$out" ${args[@]+"${args[@]}"}
}

cmd_cost() {
  case "${1:-}" in -h|--help) python3 "$ROOT/host_tools/bench_cost/sbr_cost.py" --help; return 0 ;; esac
  setup
  build_native
  configure_build cortex-m4
  local out="$ROOT/out/cost" args=()
  while [ $# -gt 0 ]; do
    case "$1" in
      --out) need_value "$1" "$#"; out="$2"; shift 2 ;;
      *) args+=("$1"); shift ;;
    esac
  done
  log "cost benchmark -> $out"
  python3 "$ROOT/host_tools/bench_cost/sbr_cost.py" --bin "$BUILD/native/host_tools" \
      --m4-elf "$BUILD/cortex-m4/tests/bench_m4/sbr_cost_m4.elf" --gtsdb "$DATA/gtsdb" \
      --out "$out" ${args[@]+"${args[@]}"}
}

cmd_learn_tracker() {
  setup
  build_native
  log "sbr_train_track on KITTI tracking 0000-0005 -> lib/models/sbr_track_model_kitti.c, $BUILD/sbr_track_kitti.stm"
  "$BUILD/native/host_tools/sbr_train_track" --labels "$DATA/kitti_tracking/label_02" \
      --seqs 0000-0005 --noise 0 --miss 0 --clutter 0 \
      --c-out "$ROOT/lib/models/sbr_track_model_kitti.c" --model-out "$BUILD/sbr_track_kitti.stm" "$@"
}

cmd_track() {
  setup
  build_native
  "$BUILD/native/host_tools/sbr_track" --labels "$DATA/kitti_tracking/label_02" "$@"
}

cmd_dashboard() {
  # the dashboard needs only Python and its pinned packages
  install_packages python3 python3-venv python3-pip
  mkdir -p "$BUILD"
  setup_venv
  local args=("$@")
  if ! printf '%s\n' "${args[@]}" | grep -qxE -- '--(log|socketcan|virtual|help)|-h'; then
    [ -f "$ROOT/out/sbr_can.log" ] || { echo "no out/sbr_can.log: run ./sbr.sh detect first, or give --log/--socketcan/--virtual" >&2; return 2; }
    args=(--log "$ROOT/out/sbr_can.log" "${args[@]}")
  fi
  exec "$BUILD/venv/bin/sbr-dashboard" "${args[@]}"
}

# usage_of NAME: the header's lines of one subcommand (./sbr.sh NAME --help).
usage_of() {
  sed -n '3,/^set -euo/{/^set -euo/!p}' "$0" \
    | awk -v c="$1" '/^#   \.\/sbr\.sh / {on = ($3 == c)} /^# *$/ {on = 0} on' | sed 's/^# \{0,1\}//'
  echo "(./sbr.sh --help: every command; docs/usage/ for each tool's options)"
}

# NAME --help (or -h) prints that subcommand's usage and runs nothing; the dashboard
# describes its own options.
if [ $# -ge 2 ] && [ "$1" != "dashboard" ] && { [ "$2" = "--help" ] || [ "$2" = "-h" ]; }; then
  usage_of "$1"
  exit 0
fi

case "${1:-}" in
  dashboard) shift; cmd_dashboard "$@" ;;
  test) shift; cmd_test "$@" ;;
  fuzz) shift; cmd_fuzz "$@" ;;
  detect) shift; cmd_detect "$@" ;;
  train) shift; cmd_train "$@" ;;
  crossval) shift; cmd_crossval "$@" ;;
  cost) shift; cmd_cost "$@" ;;
  robustness) shift; cmd_robustness "$@" ;;
  learn-tracker) shift; cmd_learn_tracker "$@" ;;
  track) shift; cmd_track "$@" ;;
  setup) setup ;;
  -h|--help|help) usage ;;
  "") usage; exit 2 ;;
  *) echo "sbr.sh: unknown command '$1' (the commands: detect, dashboard, train, crossval, robustness, cost, track, learn-tracker, test, fuzz, setup; ./sbr.sh --help)" >&2; exit 2 ;;
esac
