#!/usr/bin/env bash
# Where the instructions of a firmware scene go: runs the firmware under
# QEMU with the counting plugin in profile mode and prints the functions
# executing the most instructions in the chosen counted regions.
#
#   examples/firmware/profile.sh TARGET SCENE [PHASE] [TOP]
#
# TARGET: thumbv6m-none-eabi | thumbv7em-none-eabihf; SCENE: a scene name
# the firmware prints (e.g. bunny-gouraud); PHASE: geometry | raster | both
# (default both; each scene is two regions: geometry, then raster); TOP:
# rows to print (default 25). Counts are exact and deterministic (QEMU
# executes the same instruction stream every run); inlined code is counted
# in the function it was inlined into.
set -euo pipefail
cd "$(dirname "$0")"
t="${1:?target}"
scene="${2:?scene name}"
phase="${3:-both}"
top="${4:-25}"
case "$t" in
    thumbv6m-none-eabi) board="-cpu cortex-m3 -machine mps2-an385" ;;
    thumbv7em-none-eabihf) board="-cpu cortex-m4 -machine mps2-an386" ;;
    *) echo "unknown target $t" >&2; exit 2 ;;
esac
out=target/profile
mkdir -p "$out"
gcc -O2 -Wall -Wextra -Werror -shared -fPIC -o "$out/insn_count.so" qemu-plugin/insn_count.c
cargo build -q --release --target "$t"
elf="target/$t/release/fixshade-firmware"

# The scene's index: the firmware prints one `scene NAME` line per scene,
# in the order of its regions. A dry run without profiling finds it.
# shellcheck disable=SC2086
qemu-system-arm $board -nographic -semihosting-config enable=on,target=native \
    -kernel "$elf" >"$out/run.txt"
idx=$(awk -v s="$scene" '$1 == "scene" { if ($2 == s) { print n + 0; exit } n++ }' "$out/run.txt")
if [ -z "$idx" ]; then
    echo "no scene $scene; the firmware renders:" >&2
    awk '$1 == "scene" { print "  " $2 }' "$out/run.txt" >&2
    exit 2
fi
case "$phase" in
    geometry) regions=$((2 * idx)) ;;
    raster) regions=$((2 * idx + 1)) ;;
    both) regions="$((2 * idx)):$((2 * idx + 1))" ;;
    *) echo "phase: geometry | raster | both" >&2; exit 2 ;;
esac

# shellcheck disable=SC2086
qemu-system-arm $board -nographic -semihosting-config enable=on,target=native \
    -plugin "$(pwd)/$out/insn_count.so,prof=$(pwd)/$out/prof.txt,regions=$regions" \
    -d plugin -D "$out/plugin.log" -kernel "$elf" >/dev/null

if command -v llvm-nm >/dev/null; then NM=llvm-nm; else NM=nm; fi
# Function symbols (address, size, name) sorted by address; each profiled
# address is charged to the function containing it.
"$NM" --defined-only --print-size --numeric-sort --demangle -t d "$elf" |
    awk 'NF >= 4 && ($3 == "T" || $3 == "t") { n = $4; for (i = 5; i <= NF; i++) n = n " " $i; print $1 + 0, $2 + 0, n }' >"$out/syms.txt"
awk '
    FNR == NR { a[n] = $1; e[n] = $1 + $2; $1 = ""; $2 = ""; name[n] = substr($0, 3); n++; next }
    { addr = $1; c = $2; total += c
      lo = 0; hi = n - 1; f = -1
      while (lo <= hi) { m = int((lo + hi) / 2); if (a[m] <= addr) { f = m; lo = m + 1 } else hi = m - 1 }
      key = (f >= 0 && addr < e[f]) ? name[f] : sprintf("?? %d", addr)
      per[key] += c }
    END { for (x in per) printf "%12d %5.1f%%  %s\n", per[x], 100 * per[x] / total, x
          printf "%12d %5.1f%%  total\n", total, 100 > "/dev/stderr" }
' "$out/syms.txt" "$out/prof.txt" 2>"$out/total.txt" | sort -nr | head -n "$top" |
    sed -e 's/::h[0-9a-f]\{16\}$//' -e 's/\$LT\$/</g' -e 's/\$GT\$/>/g' -e 's/\$u20\$/ /g' \
        -e 's/\$u7b\$/{/g' -e 's/\$u7d\$/}/g' -e 's/\.\./::/g' -e 's/^\( *[0-9]* *[0-9.]*%  \)_</\1</'
cat "$out/total.txt"
