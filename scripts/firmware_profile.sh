#!/usr/bin/env bash
# Where a firmware frame's instructions go: runs the firmware built by
# scripts/firmware.sh in QEMU with the plugin's per-address profile for one
# render call and prints its instructions three ways: per symbol
# of the ELF (functions as linked, e.g. __aeabi_lmul), per innermost
# function that addr2line names (inlined ones included), and per execution
# count (the instructions that ran once a vertex, once a triangle, …).
#   scripts/firmware_profile.sh [TARGET] [FRAME_INDEX] [LINES]
# (KEEP_PROFILE=DIR keeps the raw per-address counts and symbol tables in DIR.)
# TARGET: thumbv7em-none-eabihf (default) or thumbv6m-none-eabi; FRAME_INDEX:
# the render call's position in firmware/common/scenes.rs's list (0 = S1,
# 1 = S2, 2 = S3, 3 = S4, in their own shading mode).
set -euo pipefail
cd "$(dirname "$0")/.."
T=${1:-thumbv7em-none-eabihf}
N=${2:-0}
L=${3:-25}
TGT=${CARGO_TARGET_DIR_FW:-$PWD/target/fw}
OUT=${FIRMWARE_OUT:-$PWD/target/firmware}
TGT=$(cd "$TGT" && pwd)
OUT=$(cd "$OUT" && pwd)
ELF=$TGT/qemu-$T/$T/release/fixshade-fw
PLUGIN=$OUT/libinsn_count.so
[ -f "$ELF" ] && [ -f "$PLUGIN" ] || { echo "run scripts/firmware.sh first" >&2; exit 1; }
sym() { arm-none-eabi-nm "$ELF" | awk -v s="$1" '$3 == s { print "0x" $1 }'; }
work=$(mktemp -d)
trap '[ -n "${KEEP_PROFILE:-}" ] && cp -r "$work" "$KEEP_PROFILE"; rm -rf "$work"' EXIT
(cd "$work" && qemu-system-arm -machine mps2-an386 -nographic -monitor none -serial none \
    -semihosting-config enable=on,target=native \
    -plugin "$PLUGIN,begin=$(sym fw_count_begin),end=$(sym fw_count_end),out=counts.txt,profile=profile.txt,region=$N" \
    -kernel "$ELF" > /dev/null)
awk '{ c[$1] += $2 } END { for (k in c) print k, c[k] }' "$work/profile.txt" | sort > "$work/byaddr.txt"
cut -d' ' -f1 "$work/byaddr.txt" | arm-none-eabi-addr2line -f -C -e "$ELF" | awk 'NR % 2 == 1' > "$work/fn.txt"
total=$(awk '{ s += $2 } END { print s }' "$work/byaddr.txt")
echo "frame $N on $T: $total instructions (region count: $(sed -n "$((N + 1))p" "$work/counts.txt"))"
echo "-- per linked function"
# (mawk has no strtonum: hexadecimal by hand)
HEX='function hex(s,  i, v) { s = tolower(s); sub(/^0x/, "", s); v = 0;
     for (i = 1; i <= length(s); i++) v = v * 16 + index("0123456789abcdef", substr(s, i, 1)) - 1; return v }'
arm-none-eabi-nm -n -C "$ELF" | awk "$HEX"' $2 ~ /^[tTwW]$/ { a = hex($1); $1 = ""; $2 = ""; sub(/^  /, ""); print a "\t" $0 }' > "$work/syms.txt"
awk -F'\t' -v t="$total" "$HEX"' NR == FNR { addr[NR] = $1 + 0; name[NR] = $2; n = NR; next }
    { split($0, f, " "); pc = hex(f[1]);
      lo = 1; hi = n; while (lo < hi) { mid = int((lo + hi + 1) / 2); if (addr[mid] <= pc) lo = mid; else hi = mid - 1 }
      s[name[lo]] += f[2] }
    END { for (k in s) printf "%10d %5.1f%%  %s\n", s[k], 100 * s[k] / t, k }' "$work/syms.txt" "$work/byaddr.txt" \
    | sort -rn | awk -v l="$L" 'NR <= l'
echo "-- per innermost (inlined) function"
paste -d' ' "$work/byaddr.txt" "$work/fn.txt" \
    | awk -v t="$total" '{ n = $2; $1 = ""; $2 = ""; sub(/^  /, ""); s[$0] += n }
        END { for (f in s) printf "%10d %5.1f%%  %s\n", s[f], 100 * s[f] / t, f }' \
    | sort -rn | awk -v l="$L" 'NR <= l'
echo "-- per execution count (code run once a vertex, a triangle, a row, …: instructions, times each ran × instructions that ran that often)"
awk -v t="$total" '{ c[$2] += 1; s[$2] += $2 }
    END { for (k in c) printf "%10d %5.1f%%  %d × %d\n", s[k], 100 * s[k] / t, k, c[k] }' "$work/byaddr.txt" \
    | sort -rn | awk -v l="$L" 'NR <= l'
