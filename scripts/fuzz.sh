#!/usr/bin/env bash
# Builds the libFuzzer targets (the `fuzz` preset: clang, ASan + UBSan) and runs each for a bounded time.
#
#   scripts/fuzz.sh [seconds-per-target]     (default 20)
#   TOPPLE_FUZZ_RUNS=1000000 scripts/fuzz.sh 3600   (stop each target at 10^6 executions, or after an hour)
#   TOPPLE_FUZZ_TARGETS="fuzz_knet fuzz_sweep" scripts/fuzz.sh 60   (only these targets)
#
# Seed corpora are made at run time from ../shared/records when it is there (TOPPLE_SHARED_DIR overrides): each
# record, cut to its first 16 KiB, plus a small well-formed version of it (header kept, a few samples, counts
# rewritten) so that mutations start from inputs that parse. Nothing is copied into the repository; corpora and
# crash reproducers go to build/fuzz/corpus and build/fuzz/artifacts. Exits non-zero when a target finds a crash.
# See docs/fuzzing.md.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-20}"
jobs="${TOPPLE_JOBS:-2}"
shared="${TOPPLE_SHARED_DIR:-$(pwd)/../shared}"
runs="${TOPPLE_FUZZ_RUNS:--1}"   # -1: no limit on executions, only on time
read -r -a targets <<<"${TOPPLE_FUZZ_TARGETS:-fuzz_peer_at2 fuzz_cosmos_v2 fuzz_csmip_v2 fuzz_knet fuzz_usgs_smc fuzz_esm fuzz_plain fuzz_detect fuzz_survey fuzz_sweep fuzz_campaign fuzz_mesh_obj fuzz_mesh_off fuzz_mesh_stl fuzz_mesh_ply}"

cmake --preset fuzz >/dev/null
cmake --build --preset fuzz -j "$jobs" --target "${targets[@]}"

out=build/fuzz
mkdir -p "$out/corpus" "$out/artifacts"

# Which records seed which target (by content family; fuzz_detect gets them all).
seeds_for() {
  case "$1" in
    fuzz_peer_at2) echo '*.AT2 *.at2' ;;
    fuzz_cosmos_v2) echo '*.V2c' ;;
    fuzz_csmip_v2) echo '*.V2' ;;
    fuzz_knet) echo '*.NS *.NS2 *.EW *.UD *.EW2 *.UD2 *.NS1' ;;
    fuzz_usgs_smc) echo '*.smc' ;;
    fuzz_esm) echo '*.ASC' ;;
    fuzz_plain) echo '*.csv slammer/*.csv' ;;
    fuzz_survey|fuzz_sweep|fuzz_campaign|fuzz_mesh_*|fuzz_body_file) echo '' ;;  # seeded from examples/ and tests/ below
    *) echo '*' ;;
  esac
}

# A small well-formed version of a record: header kept, counts rewritten to the samples kept.
shrink() {
  python3 - "$1" "$2" <<'EOF' || true
import re, sys
src, dst = sys.argv[1], sys.argv[2]
raw = open(src, 'rb').read().rstrip(b'\x1a')
nl = b'\r\n' if b'\r\n' in raw else b'\n'
lines = raw.split(nl)
out = None
head = lines[0].decode('latin-1') if lines else ''
text = raw.decode('latin-1')
if len(lines) > 4 and re.search(r'NPTS', lines[3].decode('latin-1'), re.I):            # AT2
    vals = lines[4:12]                                                                     # 8 lines, 5 per line
    n = sum(len(v.split()) for v in vals)
    l4 = re.sub(rb'(NPTS\s*=\s*)\d+', lambda m: m.group(1) + str(n).encode(), lines[3])
    if l4 == lines[3]:
        l4 = re.sub(rb'^\s*\d+', b' ' + str(n).encode(), lines[3])
    out = lines[:3] + [l4] + vals
elif 'text lines' in head:                                                                  # COSMOS
    i = next(k for k, l in enumerate(lines) if b' pts' in l and b'units=' in l)
    kept = lines[i + 1:i + 21]
    n = sum(len(v.split()) for v in kept)
    out = lines[:i] + [re.sub(rb'^\s*\d+', b'%8d' % n, lines[i])] + kept + [b'End-of-data for Chan acceleration']
elif 'POINTS OF ACCEL DATA' in text:                                                        # CSMIP: 8 per line
    out, k = [], 0
    while k < len(lines):
        m = re.match(rb'\s*\d+( POINTS OF \w+ DATA.*)', lines[k])
        if not m:
            out.append(lines[k]); k += 1; continue
        out += [b' %4d' % 16 + m.group(1)] + lines[k + 1:k + 3]                           # 16 values
        k += 1
        while k < len(lines) and b'POINTS OF' not in lines[k] and b'END OF DATA' not in lines[k]:
            k += 1
elif re.match(r'^\d [A-Z]', head):                                                          # SMC
    ints = b''.join(lines[11:17])
    nc = int(ints[150:160])
    first = 27 + nc
    kept = lines[first:first + 3]
    l14 = lines[13]
    l14 = b'%10d' % 24 + l14[10:]
    out = lines[:13] + [l14] + lines[14:first] + kept
elif head.startswith('Origin Time'):                                                       # K-NET
    out = lines[:17 + 6]
elif 'SAMPLING_INTERVAL_S' in text[:4000]:                                                  # ESM
    i = next(k for k, l in enumerate(lines) if l and not re.match(rb'^[A-Z0-9_/^.\-]+:', l))
    out = [re.sub(rb'^NDATA: .*', b'NDATA: 30', l) for l in lines[:i]] + lines[i:i + 30]
else:                                                                                      # plain text
    out = lines[:40]
open(dst, 'wb').write(nl.join(out) + nl)
EOF
}

status=0
# Mesh seeds: the example rock as OBJ, and a unit cube in the format (OBJ; OFF; ASCII and binary STL; ASCII and binary
# PLY).
mesh_seeds() {
  [[ "$1" == obj ]] && cp examples/mesh/balanced_rock.obj "$2/seed-rock.obj"
  python3 - "$1" "$2" <<'EOF' || true
import struct, sys
fmt, out = sys.argv[1], sys.argv[2]
v = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
f = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4), (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6),
     (3, 0, 4), (3, 4, 7)]
if fmt == 'obj':
    text = ''.join('v %g %g %g\n' % p for p in v) + ''.join('f %d %d %d\n' % (a + 1, b + 1, c + 1) for a, b, c in f)
    open(out + '/seed-cube.obj', 'w').write(text)
elif fmt == 'off':
    text = 'OFF\n%d %d 0\n' % (len(v), len(f)) + ''.join('%g %g %g\n' % p for p in v)
    open(out + '/seed-cube.off', 'w').write(text + ''.join('3 %d %d %d\n' % t for t in f))
elif fmt == 'stl':
    text = 'solid cube\n'
    for tri in f:
        text += ' facet normal 0 0 0\n  outer loop\n' + ''.join('   vertex %g %g %g\n' % v[i] for i in tri)
        text += '  endloop\n endfacet\n'
    open(out + '/seed-cube-ascii.stl', 'w').write(text + 'endsolid cube\n')
    data = b'binary cube'.ljust(80, b' ') + struct.pack('<I', len(f))
    for tri in f:
        data += struct.pack('<3f', 0, 0, 0) + b''.join(struct.pack('<3f', *v[i]) for i in tri) + b'\0\0'
    open(out + '/seed-cube-binary.stl', 'wb').write(data)
else:
    head = ('ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n'
            'element face %d\nproperty list uchar int vertex_indices\nend_header\n' % (len(v), len(f)))
    text = head + ''.join('%g %g %g\n' % p for p in v) + ''.join('3 %d %d %d\n' % t for t in f)
    open(out + '/seed-cube.ply', 'w').write(text)
    head = head.replace('ascii', 'binary_big_endian').replace('float', 'double')
    data = head.encode() + b''.join(struct.pack('>3d', *p) for p in v)
    data += b''.join(struct.pack('>B3i', 3, *t) for t in f)
    open(out + '/seed-cube-be.ply', 'wb').write(data)
EOF
}

for target in "${targets[@]}"; do
  corpus="$out/corpus/$target"
  mkdir -p "$corpus"
  if [[ -d "$shared/records" ]]; then
    for pattern in $(seeds_for "$target"); do
      for f in "$shared"/records/$pattern; do
        [[ -f "$f" ]] || continue
        case "$f" in *.md|*gm_summary.csv) continue ;; esac
        base=$(basename "$f")
        head -c 16384 "$f" >"$corpus/head-$base"
        if command -v python3 >/dev/null; then shrink "$f" "$corpus/small-$base"; fi
      done
    done
  fi
  dict=fuzz/readers.dict
  case "$target" in
    fuzz_survey) cp examples/survey.toml "$corpus/seed-survey.toml"; cp examples/survey.csv "$corpus/seed-survey.csv"
                 dict=fuzz/toml.dict ;;
    fuzz_sweep) for f in examples/sweep/*.toml; do cp "$f" "$corpus/seed-$(basename "$f")"; done; dict=fuzz/toml.dict ;;
    fuzz_campaign) cp examples/campaign/campaign.toml "$corpus/seed-campaign.toml"; dict=fuzz/toml.dict ;;
    fuzz_mesh_*) mesh_seeds "${target#fuzz_mesh_}" "$corpus"; dict=fuzz/mesh.dict ;;
    fuzz_body_file) cp tests/cli/fixtures/balanced_rock_body_az30*.json "$corpus/"; dict=fuzz/toml.dict ;;
  esac
  echo "== $target: ${seconds} s$([[ "$runs" == -1 ]] || echo ", at most $runs runs")"
  unset LSAN_OPTIONS  # every leak is reported
  if ! "$out/fuzz/$target" "$corpus" -max_total_time="$seconds" -runs="$runs" -max_len=65536 -timeout=10 \
       -rss_limit_mb=2048 -dict="$dict" -print_final_stats=1 -artifact_prefix="$out/artifacts/$target-" \
       2>"$out/$target.log"; then
    echo "!! $target found a problem; reproducer in $out/artifacts, log in $out/$target.log"
    tail -n 40 "$out/$target.log"
    status=1
  else
    grep -E '^stat::number_of_executed_units|^stat::average_exec_per_sec|^Done' "$out/$target.log" || true
  fi
done
exit "$status"
