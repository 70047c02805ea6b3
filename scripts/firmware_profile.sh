#!/usr/bin/env bash
# Where a firmware frame's instructions go: runs the firmware built by
# scripts/firmware.sh in QEMU with the plugin's per-address profile for one
# render call and prints the instructions per function (the innermost
# function, inlined ones included, that addr2line names for each address).
#   scripts/firmware_profile.sh [TARGET] [FRAME_INDEX] [LINES]
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
ELF=$TGT/qemu/$T/release/fixshade-fw
PLUGIN=$OUT/libinsn_count.so
[ -f "$ELF" ] && [ -f "$PLUGIN" ] || { echo "run scripts/firmware.sh first" >&2; exit 1; }
sym() { arm-none-eabi-nm "$ELF" | awk -v s="$1" '$3 == s { print "0x" $1 }'; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
(cd "$work" && qemu-system-arm -machine mps2-an386 -nographic -monitor none -serial none \
    -semihosting-config enable=on,target=native \
    -plugin "$PLUGIN,begin=$(sym fw_count_begin),end=$(sym fw_count_end),out=counts.txt,profile=profile.txt,region=$N" \
    -kernel "$ELF" > /dev/null)
awk '{ c[$1] += $2 } END { for (k in c) print k, c[k] }' "$work/profile.txt" | sort > "$work/byaddr.txt"
cut -d' ' -f1 "$work/byaddr.txt" | arm-none-eabi-addr2line -f -C -e "$ELF" | awk 'NR % 2 == 1' > "$work/fn.txt"
total=$(awk '{ s += $2 } END { print s }' "$work/byaddr.txt")
echo "frame $N on $T: $total instructions (region count: $(sed -n "$((N + 1))p" "$work/counts.txt"))"
paste -d' ' "$work/byaddr.txt" "$work/fn.txt" \
    | awk -v t="$total" '{ n = $2; $1 = ""; $2 = ""; sub(/^  /, ""); s[$0] += n }
        END { for (f in s) printf "%10d %5.1f%%  %s\n", s[f], 100 * s[f] / t, f }' \
    | sort -rn | head -n "$L"
