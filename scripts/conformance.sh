#!/usr/bin/env bash
# Run the Khronos ANARI-SDK's own tools against Ripple's device libraries and print one table.
#
#   scripts/conformance.sh [options] <sdk-prefix>
#
# <sdk-prefix> is an installed ANARI-SDK (bin/anariInfo, bin/anariRenderTests, bin/anariCts, lib/libanari.so;
# lib/libanari_library_helide.so when it was built with helide). docs/conformance.md says how to build it,
# helide included (it needs Embree 4; scripts/helide-local-embree.cmake builds it from a local source tree).
# Run by hand, not in CI. The script builds nothing: with helide in the SDK it generates helide's ground
# truth for the CTS; without helide the CTS's image cases are skipped (only its behaviour checks score)
# unless --reference names another library.
#
# Options:
#   --ripple-lib DIR      folder holding libanari_library_ripple.so and libanari_library_ripple_ptc.so
#                         (default: build/lib of this checkout)
#   --devices "A B"       libraries to test (default: "ripple ripple_ptc"; ripple_ptc wraps ripple unless
#                         RIPPLE_PTC_LIBRARY says otherwise)
#   --out DIR             where images, logs and CTS workdirs go (default: a new folder under $TMPDIR or /tmp)
#   --reference LIB       library that renders the CTS ground truth (default: helide). Anything but helide is
#                         a consistency check between devices, not conformance, and the table says so.
#   --embree-archive ZIP  when the SDK lacks helide: check that ZIP is the Embree 4.3.3 source archive the
#                         SDK pins and print where to put it so that the SDK's configure step uses it offline
#   --embree-source DIR   when the SDK lacks helide: check that DIR is an Embree 4.3.3 source tree (the
#                         upstream v4.3.3 tag, or Debian trixie's embree_4.3.3+dfsg.orig.tar.xz unpacked) and
#                         print the SDK configure options that build helide from it offline
#   --render-reference    also render every anariRenderTests scene with the reference device (helide, from
#                         the SDK) and give each device's images' PSNR against it (column 'dB helide')
#   --render-size W H     anariRenderTests image size (default: the tool's own, 1024 768)
#   --render-filter "A B" only these anariRenderTests scenes, e.g. "demo/cornell_box test/pbr_spheres"
#   --cts-size N          CTS image width and height (default: the tool's own, 256)
#   --cts-filter PATTERN  run only the CTS tests matching PATTERN (anariCts --filter syntax)
#   --cts-renderer NAME   the renderer subtype the tested devices render the CTS with (default: the CTS's,
#                         "default"); the ground truth keeps the reference's default renderer. Ripple's
#                         "eyeLight" shades as helide's default renderer does (a light at the eye), so the
#                         CTS then scores geometry, samplers and cameras rather than the lighting model
#   --timeout S           limit for each process, in seconds (default 600); a process past it is a hang
#   --no-render / --no-cts  leave a part out
#   -h, --help
#
# Each anariRenderTests scene runs once in a sequence (the tool's default: every scene, one device) and once
# alone; a scene renders when the process wrote all of its images with exit status 0. A crash (a signal) is
# re-run under gdb, when gdb is installed, for a backtrace (bt-*.txt). Images are compared alone vs sequence
# pixel by pixel and checked for being blank (one colour). Every CTS test runs in its own process so that a
# crash loses one test, not the rest; the counts come from the CTS's own report. Everything printed by the
# device (status callback warnings and errors) is kept per scene/test in the logs, deduplicated in
# messages-*.txt.
set -u

die() { echo "conformance.sh: $*" >&2; exit 2; }

script_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo_dir=$(cd "$script_dir/.." && pwd)

prefix=""
ripple_lib="$repo_dir/build/lib"
devices="ripple ripple_ptc"
out=""
reference="helide"
embree_archive=""
embree_source=""
render_ref=0
render_filter=""
render_w=""; render_h=""
cts_size=""
cts_filter=""
cts_renderer=""
timeout_s=600
do_render=1; do_cts=1

while [ $# -gt 0 ]; do
  case "$1" in
    --ripple-lib) ripple_lib=$2; shift 2 ;;
    --devices) devices=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --reference) reference=$2; shift 2 ;;
    --embree-archive) embree_archive=$2; shift 2 ;;
    --embree-source) embree_source=$2; shift 2 ;;
    --render-reference) render_ref=1; shift ;;
    --render-filter) render_filter=$2; shift 2 ;;
    --render-size) render_w=$2; render_h=$3; shift 3 ;;
    --cts-size) cts_size=$2; shift 2 ;;
    --cts-filter) cts_filter=$2; shift 2 ;;
    --cts-renderer) cts_renderer=$2; shift 2 ;;
    --timeout) timeout_s=$2; shift 2 ;;
    --no-render) do_render=0; shift ;;
    --no-cts) do_cts=0; shift ;;
    -h|--help) sed -n '2,/^set -u/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    -*) die "unknown option $1 (see --help)" ;;
    *) [ -z "$prefix" ] || die "one SDK prefix only"; prefix=$1; shift ;;
  esac
done
[ -n "$prefix" ] || die "usage: conformance.sh [options] <sdk-prefix>   (see --help)"
prefix=$(cd "$prefix" 2>/dev/null && pwd) || die "no such folder: $prefix"
ripple_lib=$(cd "$ripple_lib" 2>/dev/null && pwd) || die "no such folder: $ripple_lib"

sdk_lib=""
for d in "$prefix/lib" "$prefix/lib64" "$prefix"/lib/*-linux-gnu; do
  [ -e "$d/libanari.so" ] && { sdk_lib=$d; break; }
done
[ -n "$sdk_lib" ] || die "$prefix has no lib/libanari.so: not an ANARI-SDK install"
for t in anariInfo anariRenderTests anariCts; do
  [ -x "$prefix/bin/$t" ] || echo "conformance.sh: note: $prefix/bin/$t missing (build the SDK with examples, BUILD_TESTING and BUILD_CTS)" >&2
done
for dev in $devices; do
  [ -e "$ripple_lib/libanari_library_$dev.so" ] || die "$ripple_lib has no libanari_library_$dev.so"
done
command -v python3 >/dev/null || die "python3 is needed (image checks)"
have_gdb=0; command -v gdb >/dev/null && have_gdb=1

[ -n "$out" ] || out=$(mktemp -d "${TMPDIR:-/tmp}/ripple-conformance.XXXXXX")
mkdir -p "$out"; out=$(cd "$out" && pwd)

# The SDK's libraries first (never a libanari.so from the Ripple build), then Ripple's device libraries.
export LD_LIBRARY_PATH="$sdk_lib:$ripple_lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
unset ANARI_LIBRARY

sdk_version=$(cd "$sdk_lib" && ls libanari.so.*.*.* 2>/dev/null | sed 's/^libanari\.so\.//' | head -1)
[ -n "$sdk_version" ] || sdk_version="unknown"

# The SDK's tools carry its loader (linked in statically, or libanari.so / libanari_test_scenes.so from the
# SDK): make sure none of them would pick up another libanari.so on this search path.
for t in anariInfo anariRenderTests anariCts; do
  [ -x "$prefix/bin/$t" ] || continue
  loader=$(ldd "$prefix/bin/$t" 2>/dev/null | awk '$1 ~ /^libanari\.so/ {print $3}')
  case "$loader" in
    "$sdk_lib"/*|"") ;;
    *) die "$t would load libanari.so from $loader, not from the SDK" ;;
  esac
done

have_helide=0; [ -e "$sdk_lib/libanari_library_helide.so" ] && have_helide=1

if [ -n "$embree_source" ]; then
  src=$(cd "$embree_source" 2>/dev/null && pwd) || die "no such folder: $embree_source"
  ver=$(sed -n 's/^SET(EMBREE_VERSION_\(MAJOR\|MINOR\|PATCH\) \([0-9]*\)).*/\2/p' "$src/CMakeLists.txt" 2>/dev/null | paste -sd.)
  if [ -e "$src/include/embree4/rtcore.h" ] && [ -d "$src/common/tasking" ] && [ "$ver" = 4.3.3 ]; then
    echo "Embree source OK ($ver). To build helide from it offline, configure the SDK with:"
    echo "  -DBUILD_HELIDE_DEVICE=ON -DCMAKE_PROJECT_local_embree_INCLUDE=$repo_dir/scripts/helide-local-embree.cmake \\"
    echo "  -DHELIDE_EMBREE_SOURCE=$src"
    [ $have_helide = 1 ] && echo "(this SDK already has helide)"
  else
    echo "Embree source $src is not an Embree 4.3.3 source tree (version '${ver:-?}'; the SDK 0.16 pins 4.3.3)."
  fi
  echo
fi

# the device that renders the reference anariRenderTests images (--render-reference): from the SDK or
# from the Ripple folder
ref_dev=""
if [ $render_ref = 1 ]; then
  if [ -e "$sdk_lib/libanari_library_$reference.so" ] || [ -e "$ripple_lib/libanari_library_$reference.so" ]; then
    ref_dev=$reference
  else
    echo "conformance.sh: note: no libanari_library_$reference.so: --render-reference renders nothing" >&2
  fi
fi

# ---------------------------------------------------------------------------------------------------------
# helpers

# run_limited LOG DIR CMD...: run CMD in DIR with the time limit, stdout+stderr to LOG; prints the status
run_limited() {
  local log=$1 dir=$2; shift 2
  ( cd "$dir" && exec timeout -k 10 "$timeout_s" "$@" ) >"$log" 2>&1
  echo $?
}

# backtrace FILE DIR CMD...: re-run CMD under gdb in DIR and keep the backtraces
backtrace() {
  local file=$1 dir=$2; shift 2
  if [ $have_gdb = 1 ]; then
    ( cd "$dir" && timeout -k 10 "$timeout_s" gdb -q -batch -ex run -ex "thread apply all bt" \
        --args "$@" ) >"$file" 2>&1
  else
    echo "gdb not installed: no backtrace" >"$file"
  fi
}

# the device's status messages in a log, pointers dropped, one line each, counted
messages() {
  grep -hE '^\[ANARI\]\[(FATAL|ERROR|WARN |PERF )\]|^\[(WARN|ERROR|FATAL)' "$@" 2>/dev/null \
    | sed -E 's/\]\[(0x[0-9a-f]+|\(nil\))\]/]/; s/0x[0-9a-f]{6,}/0x…/g; s/#[0-9]+/#N/g;
        s/(material|mesh|geometry|surface|instance|light|sampler|group) [0-9]+/\1 N/g' | sort | uniq -c | sort -rn
}

# classify exit status: ok, crash(SIG), hang, exit(N)
verdict() {
  local rc=$1
  if [ "$rc" = 0 ]; then echo ok
  elif [ "$rc" = 124 ] || [ "$rc" = 137 ]; then echo hang
  elif [ "$rc" -gt 128 ]; then echo "crash(sig$((rc - 128)))"
  else echo "exit($rc)"; fi
}

# Image checks: "blank FILE" -> blank|ok, "same A B" -> same|differs:<pixels>:<max>. Small PNG reader
# (8-bit RGB/RGBA, non-interlaced: what stb_image_write and the CTS write), standard library only.
imgtool() {
  python3 - "$@" <<'PY'
import sys, zlib, struct
def load(path):
    data = open(path, 'rb').read()
    assert data[:8] == b'\x89PNG\r\n\x1a\n', 'not a PNG'
    pos, idat, w = 8, [], None
    while pos < len(data):
        n, kind = struct.unpack('>I4s', data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]; pos += 12 + n
        if kind == b'IHDR':
            w, h, depth, ctype, _, _, interlace = struct.unpack('>IIBBBBB', body)
            assert depth == 8 and ctype in (0, 2, 4, 6) and interlace == 0, 'unsupported PNG'
            bpp = {0: 1, 2: 3, 4: 2, 6: 4}[ctype]
        elif kind == b'IDAT': idat.append(body)
        elif kind == b'IEND': break
    raw, stride = zlib.decompress(b''.join(idat)), w * bpp
    out, prev = bytearray(), bytearray(stride)
    for y in range(h):
        f, row = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        if f == 1:
            for i in range(bpp, stride): row[i] = (row[i] + row[i - bpp]) & 255
        elif f == 2:
            row = bytearray((a + b) & 255 for a, b in zip(row, prev))
        elif f == 3:
            for i in range(stride):
                row[i] = (row[i] + ((row[i - bpp] if i >= bpp else 0) + prev[i]) // 2) & 255
        elif f == 4:
            for i in range(stride):
                a = row[i - bpp] if i >= bpp else 0; b = prev[i]; c = prev[i - bpp] if i >= bpp else 0
                p = a + b - c; pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                row[i] = (row[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        out += row; prev = row
    return w, h, bpp, bytes(out)
cmd = sys.argv[1]
try:
    if cmd == 'blank':
        w, h, bpp, px = load(sys.argv[2])
        print('blank' if px == px[:bpp] * (w * h) else 'ok')
    elif cmd == 'same':
        a, b = load(sys.argv[2]), load(sys.argv[3])
        if a[:3] != b[:3]: print('differs:size'); sys.exit()
        bpp, pa, pb = a[2], a[3], b[3]
        if pa == pb: print('same'); sys.exit()
        diff = [abs(x - y) for x, y in zip(pa, pb)]
        pixels = sum(1 for i in range(0, len(diff), bpp) if any(diff[i:i + bpp]))
        print('differs:%d:%d' % (pixels, max(diff)))
    elif cmd == 'psnr':
        # as the CTS does: alpha composited over white, data range 255, all channels together
        import math
        def rgb(img):
            w, h, bpp, px = img
            if bpp in (3, 1): return px
            if bpp == 4:
                out = bytearray(w * h * 3)
                for i in range(w * h):
                    a = px[4 * i + 3]
                    for c in range(3):
                        out[3 * i + c] = (px[4 * i + c] * a + 255 * (255 - a) + 127) // 255
                return bytes(out)
            return bytes(v for i in range(0, len(px), 2) for v in [(px[i] * px[i + 1] + 255 * (255 - px[i + 1]) + 127) // 255])
        a, b = load(sys.argv[2]), load(sys.argv[3])
        if a[:2] != b[:2]: print('size'); sys.exit()
        pa, pb = rgb(a), rgb(b)
        if len(pa) != len(pb): print('channels'); sys.exit()
        mse = sum((x - y) * (x - y) for x, y in zip(pa, pb)) / len(pa)
        print('inf' if mse == 0 else '%.1f' % (10 * math.log10(255 * 255 / mse)))
except Exception as e:
    print('unreadable:%s' % e)
PY
}

printf 'Ripple vs ANARI-SDK %s tools, %s\n' "$sdk_version" "$(date -u +%Y-%m-%d)"
printf 'SDK: %s   Ripple libraries: %s   output: %s\n\n' "$prefix" "$ripple_lib" "$out"

# ---------------------------------------------------------------------------------------------------------
# anariInfo

declare -A info_result
for dev in $devices; do
  log="$out/anariInfo-$dev.log"
  rc=$(run_limited "$log" "$out" "$prefix/bin/anariInfo" -l "$dev")
  v=$(verdict "$rc")
  if [ "$v" = ok ]; then
    v="ok ($(wc -l <"$log") lines)"
  fi
  case "$v" in crash*) backtrace "$out/bt-anariInfo-$dev.txt" "$out" "$prefix/bin/anariInfo" -l "$dev" ;; esac
  info_result[$dev]=$v
done

# ---------------------------------------------------------------------------------------------------------
# anariRenderTests

# The scenes of SDK 0.16 (the tool has no list option); any other scene the sequence run prints is added.
scenes="demo/cornell_box demo/gravity_spheres_volume perf/materials perf/particles perf/primitives
perf/spinning_cubes perf/surfaces test/instanced_cubes test/pbr_spheres test/random_cylinders
test/random_spheres test/textured_cube test/triangle_attributes"

# Scenes whose content follows the wall clock (perf/spinning_cubes turns its cubes by steady_clock): their
# images differ between any two runs, so "same" is not asked of them.
clock_scenes="perf/spinning_cubes"

[ -n "$render_filter" ] && scenes=$render_filter

declare -A scene_result scene_same scene_msgs scene_vs_first scene_db
declare -A render_ok render_crash
render_args=()
[ -n "$render_w" ] && render_args=(--image_size "$render_w" "$render_h")

if [ $do_render = 1 ] && [ -x "$prefix/bin/anariRenderTests" ]; then
  for dev in $ref_dev $devices; do
    base="$out/render/$dev"; mkdir -p "$base/sequence"
    seq_rc=$(run_limited "$base/sequence.log" "$base/sequence" \
      "$prefix/bin/anariRenderTests" -l "$dev" "${render_args[@]}")
    scene_result["$dev|sequence"]=$(verdict "$seq_rc")
    case "$seq_rc" in 0|1|2|124|137) ;; *)
      backtrace "$base/bt-sequence.txt" "$base/sequence" "$prefix/bin/anariRenderTests" -l "$dev" "${render_args[@]}" ;;
    esac
    [ -z "$render_filter" ] && for s in $(sed -n "s/^rendering '\([a-z0-9]*\)\/\1_\(.*\)_[0-9]*\.png'.*/\1\/\2/p" "$base/sequence.log" | sort -u); do
      case " $(echo $scenes) " in *" $s "*) ;; *) scenes="$scenes $s" ;; esac
    done
    render_ok[$dev]=0; render_crash[$dev]=0
    for s in $scenes; do
      cat=${s%%/*}; name=${s#*/}; tag="${cat}_$name"
      dir="$base/alone/$tag"; mkdir -p "$dir"
      rc=$(run_limited "$dir/run.log" "$dir" "$prefix/bin/anariRenderTests" -l "$dev" \
        "${render_args[@]}" --scene "$cat" "$name")
      v=$(verdict "$rc")
      images=$(cd "$dir" && ls "${tag}"_[0-9]*.png 2>/dev/null | grep -E "^${tag}_[0-9]+\.png$")
      planned=$(grep -c "^rendering '$cat/" "$dir/run.log")
      if [ "$v" = ok ] && { [ -z "$images" ] || [ "$(echo "$images" | wc -l)" -lt "$planned" ]; }; then
        v="no-image"
      fi
      case "$v" in crash*|exit*)
        backtrace "$base/bt-$tag.txt" "$dir" "$prefix/bin/anariRenderTests" -l "$dev" \
          "${render_args[@]}" --scene "$cat" "$name"
        [ "${v#crash}" != "$v" ] && render_crash[$dev]=$((render_crash[$dev] + 1)) ;;
      esac
      notes=""; same="-"
      if [ "$v" = ok ]; then
        blanks=0; diffs=""; same="yes"
        for img in $images; do
          [ "$(imgtool blank "$dir/$img")" = blank ] && blanks=$((blanks + 1))
          if [ -e "$base/sequence/$img" ]; then
            r=$(imgtool same "$dir/$img" "$base/sequence/$img")
            [ "$r" = same ] || { same="no"; diffs="$diffs ${img%.png}:${r#differs:}"; }
          else
            same="n/a"
          fi
        done
        case " $clock_scenes " in *" $s "*) [ "$same" = no ] && same="clock"; diffs="" ;; esac
        # the same scene through the first device in the list (ripple_ptc against ripple): pixel-identical,
        # within 2 of 255 per channel, or different
        first=${devices%% *}; vs="-"
        if [ "$dev" != "$first" ] && [ "$dev" != "$ref_dev" ] && [ -d "$out/render/$first/alone/$tag" ]; then
          vs="yes"
          for img in $images; do
            r=$(imgtool same "$dir/$img" "$out/render/$first/alone/$tag/$img")
            case "$r" in same) ;;
              differs:*:[012]) [ "$vs" = yes ] && vs="<=2" ;;
              *) vs="no" ;;
            esac
          done
          case " $clock_scenes " in *" $s "*) [ "$vs" = no ] && vs="clock" ;; esac
        fi
        scene_vs_first["$dev|$s"]=$vs
        # PSNR against the reference device's image of the scene (the lowest over the scene's images)
        if [ -n "$ref_dev" ] && [ "$dev" != "$ref_dev" ]; then
          db=""
          for img in $images; do
            [ -e "$out/render/$ref_dev/alone/$tag/$img" ] || { db="-"; break; }
            r=$(imgtool psnr "$dir/$img" "$out/render/$ref_dev/alone/$tag/$img")
            case "$r" in inf) r=99 ;; [0-9]*) ;; *) db="?"; break ;; esac
            if [ -z "$db" ] || awk -v a="$r" -v b="$db" 'BEGIN {exit !(a < b)}'; then db=$r; fi
          done
          scene_db["$dev|$s"]=${db:--}
        fi
        [ $blanks -gt 0 ] && notes="$blanks/$(echo "$images" | wc -l) blank"
        [ -n "$diffs" ] && notes="${notes:+$notes; }vs sequence (pixels:max)$diffs"
        [ $blanks -eq 0 ] && render_ok[$dev]=$((render_ok[$dev] + 1))
        v="ok($(echo "$images" | wc -l))"
        [ $blanks -gt 0 ] && v="blank"
      fi
      nmsg=$(messages "$dir/run.log" | wc -l)
      messages "$dir/run.log" >"$dir/messages.txt"
      scene_result["$dev|$s"]=$v; scene_same["$dev|$s"]=$same
      scene_msgs["$dev|$s"]="$nmsg${notes:+  $notes}"
    done
    messages "$base"/alone/*/run.log "$base/sequence.log" >"$out/messages-render-$dev.txt"
  done
fi

# ---------------------------------------------------------------------------------------------------------
# CTS

declare -A cts_cell cts_rate
cts_note=""
categories=""
if [ $do_cts = 1 ] && [ -x "$prefix/bin/anariCts" ]; then
  ctsdir="$out/cts"; mkdir -p "$ctsdir"
  cts_args=()
  [ -n "$cts_size" ] && cts_args=(--width "$cts_size" --height "$cts_size")
  ( cd "$ctsdir" && "$prefix/bin/anariCts" list ${cts_filter:+--filter "$cts_filter"} ) >"$ctsdir/list.txt" 2>&1
  # "category" lines, then "  test  (N cases)" lines
  awk '/^[^ ]/ && !/test\(s\)/ {c=$1} /^  [^ ]+  \([0-9]+ case/ {n=$2; gsub(/\(/,"",n); print c "/" $1, $2}' \
    "$ctsdir/list.txt" | sed 's/(//' >"$ctsdir/tests.txt"
  categories=$(cut -d/ -f1 "$ctsdir/tests.txt" | uniq | tr '\n' ' ')

  gt_ready=0
  if [ "$reference" = helide ] && [ $have_helide = 0 ]; then
    cts_note="no helide in the SDK: no ground truth, so every image case is skipped; only the CTS's behaviour checks score"
    if [ -n "$embree_archive" ]; then
      sum=$(md5sum "$embree_archive" 2>/dev/null | cut -d' ' -f1)
      if [ "$sum" = a03f49d17084612dc0f28bdc36d92e89 ]; then
        echo "Embree archive OK (v4.3.3.zip as the SDK pins it). To build helide offline, before configuring the SDK:"
        echo "  mkdir -p <sdk-source>/.anari_deps/anari_helide_embree && cp $embree_archive <sdk-source>/.anari_deps/anari_helide_embree/v4.3.3.zip"
        echo "then configure with -DBUILD_HELIDE_DEVICE=ON, install, and run this script again."
        echo
      else
        echo "Embree archive $embree_archive is not the v4.3.3.zip the SDK pins (md5 a03f49d17084612dc0f28bdc36d92e89)."
        echo
      fi
    fi
  else
    mkdir -p "$ctsdir/reference"
    gen_log="$ctsdir/generate-$reference.log"
    ( cd "$ctsdir" && timeout -k 10 $((timeout_s * 20)) "$prefix/bin/anariCts" generate --device "$reference" \
        --workdir "$ctsdir/reference" "${cts_args[@]}" ${cts_filter:+--filter "$cts_filter"} ) >"$gen_log" 2>&1
    gen_rc=$?
    [ -d "$ctsdir/reference/ground_truth" ] && gt_ready=1
    if [ "$reference" != helide ]; then
      cts_note="ground truth from '$reference', not helide: a consistency check, not conformance"
    fi
    [ $gen_rc = 0 ] || cts_note="${cts_note:+$cts_note; }generate with '$reference' ended $(verdict $gen_rc): $(tail -1 "$gen_log")"
  fi

  for dev in $devices; do
    wd="$ctsdir/$dev"; mkdir -p "$wd/logs"
    [ $gt_ready = 1 ] && ln -sfn "$ctsdir/reference/ground_truth" "$wd/ground_truth"
    : >"$wd/crashed.txt"
    nbt=0
    while read -r id ncases; do
      # an anchored glob matching this id alone: its last character as '?'
      pat="${id%?}?"
      logf="$wd/logs/${id//\//__}.log"
      rc=$(run_limited "$logf" "$ctsdir" "$prefix/bin/anariCts" run "$dev" --workdir "$wd" \
        "${cts_args[@]}" ${cts_renderer:+-r "$cts_renderer"} --verbose --filter "$pat")
      case "$rc" in 0|1) ;; *)
        echo "$id $(verdict "$rc")" >>"$wd/crashed.txt"
        if [ $nbt -lt 10 ]; then
          nbt=$((nbt + 1))
          backtrace "$wd/logs/bt-${id//\//__}.txt" "$ctsdir" "$prefix/bin/anariCts" run "$dev" \
            --workdir "$wd.bt" "${cts_args[@]}" ${cts_renderer:+-r "$cts_renderer"} --filter "$pat"
        fi ;;
      esac
    done <"$ctsdir/tests.txt"
    ( cd "$ctsdir" && "$prefix/bin/anariCts" report "$wd" --all ) >"$wd/report.txt" 2>&1
    messages "$wd"/logs/*.log >"$out/messages-cts-$dev.txt"
    tp=0; tf=0; ts=0; tc=0; tl=0
    for cat in $categories; do
      read -r p f s <<<"$(awk -v c="$cat" '$1==c && $3=="passed" {print $2, $4, $6}' "$wd/report.txt")"
      p=${p:-0}; f=${f:-0}; s=${s:-0}
      c=$(grep -c "^$cat/" "$wd/crashed.txt")
      expected=$(awk -v c="$cat" 'index($1, c "/")==1 {n+=$2} END {print n+0}' "$ctsdir/tests.txt")
      lost=$((expected - p - f - s)); [ $lost -lt 0 ] && lost=0
      cts_cell["$dev|$cat"]="$p/$f/$s/$c"
      [ $lost -gt 0 ] && cts_cell["$dev|$cat"]="$p/$f/$s/$c(-$lost)"
      tp=$((tp + p)); tf=$((tf + f)); ts=$((ts + s)); tc=$((tc + c)); tl=$((tl + lost))
    done
    cts_cell["$dev|total"]="$tp/$tf/$ts/$tc"
    [ $tl -gt 0 ] && cts_cell["$dev|total"]="$tp/$tf/$ts/$tc(-$tl)"
    ran=$((tp + tf + tl))
    if [ $ran -gt 0 ]; then cts_rate[$dev]="$((100 * tp / ran))% of $ran"; else cts_rate[$dev]="-"; fi
  done
fi

# ---------------------------------------------------------------------------------------------------------
# the table

w=27
printf '%-*s' $w "anariInfo -l"
for dev in $devices; do printf ' | %-30s' "$dev: ${info_result[$dev]}"; done; echo
echo

if [ $do_render = 1 ] && [ -x "$prefix/bin/anariRenderTests" ]; then
  printf '%-*s' $w "anariRenderTests scene"
  first=${devices%% *}
  for dev in $devices; do
    if [ "$dev" = "$first" ]; then printf ' | %-12s %-5s %-8s' "$dev" "same" "messages"
    else printf ' | %-12s %-5s %-8s %-8s' "$dev" "same" "messages" "=$first"; fi
    [ -n "$ref_dev" ] && printf ' %-9s' "dB $ref_dev"
  done; echo
  for s in sequence $scenes; do
    printf '%-*s' $w "$s"
    for dev in $devices; do
      if [ "$s" = sequence ]; then
        printf ' | %-12s %-5s %-8s' "${scene_result[$dev|sequence]}" "" ""
      else
        m=${scene_msgs[$dev|$s]}; printf ' | %-12s %-5s %-8s' "${scene_result[$dev|$s]}" "${scene_same[$dev|$s]}" "${m%%  *}"
      fi
      [ "$dev" = "$first" ] || printf ' %-8s' "${scene_vs_first[$dev|$s]:-}"
      [ -n "$ref_dev" ] && printf ' %-9s' "${scene_db[$dev|$s]:-}"
    done; echo
  done
  nsc=$(echo $scenes | wc -w)
  echo "  same: alone = in the sequence, pixel for pixel (clock: the scene animates by the clock); messages:"
  echo "  distinct warnings/errors the device printed; =$first: the image equals $first's (<=2: within 2 of 255)"
  if [ -n "$ref_dev" ]; then
    echo "  dB $ref_dev: PSNR against $ref_dev's image of the scene (lowest of the scene's images; 99: identical);"
    echo "  $ref_dev rendered: $(for s in $scenes; do printf '%s ' "${scene_result[$ref_dev|$s]}"; done | tr ' ' '\n' | sort | uniq -c | awk '{printf "%s%s x%s", (NR>1?", ":""), $2, $1}')"
  fi
  printf '%-*s' $w "scenes rendered, not blank"
  for dev in $devices; do printf ' | %-29s' "${render_ok[$dev]}/$nsc"; done; echo
  printf '%-*s' $w "crashes (scenes alone)"
  for dev in $devices; do printf ' | %-29s' "${render_crash[$dev]}"; done; echo
  for dev in $devices; do for s in $scenes; do
    m=${scene_msgs[$dev|$s]}
    [ "$m" != "${m#*  }" ] && echo "  $dev $s: ${m#*  }"
  done; done
  echo
fi

if [ $do_cts = 1 ] && [ -x "$prefix/bin/anariCts" ]; then
  printf '%-*s' $w "CTS category"
  for dev in $devices; do printf ' | %-29s' "$dev pass/fail/skip/crash"; done; echo
  for cat in $categories total; do
    printf '%-*s' $w "$cat"
    for dev in $devices; do printf ' | %-29s' "${cts_cell[$dev|$cat]:--}"; done; echo
  done
  printf '%-*s' $w "passed of cases run"
  for dev in $devices; do printf ' | %-29s' "${cts_rate[$dev]:--}"; done; echo
  [ -n "$cts_renderer" ] && echo "  renderer: '$cts_renderer' for the tested devices ($reference's default for the ground truth)"
  [ -n "$cts_note" ] && echo "  note: $cts_note"
  echo "  crash = tests whose process died; (-N) = cases that got no result because of it"
  echo
fi

echo "details: $out (messages-*.txt: the device's deduplicated warnings and errors; bt-*.txt: backtraces)"
