#!/usr/bin/env bash
# Firmware checks, deterministic, on emulated Cortex-M:
#  (and the Cortex-M0 firmware on QEMU's microbit, 16 KB of RAM, band by band)
#  1. builds the QEMU instruction-count plugin, the host reference renderer
#     and the firmware for thumbv7em-none-eabihf (Cortex-M4F) and
#     thumbv6m-none-eabi (the Cortex-M0+ instruction set, RP2040's);
#  2. runs both in QEMU (mps2-an386; Thumb-1 code runs unchanged on its M4
#     core, so the count is that of the instructions an M0+ executes) and
#     compares every frame byte for byte with the host's (exit 1 if any
#     differs);
#  3. counts the instructions of every render call with the plugin;
#  4. builds the flash/RAM scene configurations for both targets, sizes
#     them with arm-none-eabi-size, runs them for the stack high-water
#     mark and the instruction count; the `s1` configuration (standard
#     scene S1 and nothing more) must print the checksum of the host's S1
#     frame (exit 1 if not); builds each again drawn through the kernel's
#     explicit call (`--cfg fixshade_explicit_draw`, src/explicit.rs),
#     sized, listed and counted the same way: the report fails (exit 1,
#     after writing it) where the draw call's code differs from that
#     call's but in the caller (the render call, into which both inline the
#     set-up), or exceeds it there or in instructions by more than register
#     allocation moves (firmware/host/src/report.rs);
#  5. writes report/firmware_counts.json and report/firmware.md (into
#     $FIRMWARE_REPORT instead if set), with tgx's counts beside ours from
#     $FIRMWARE_PEERS_TSV (default firmware/peers/tgx.tsv; the peer
#     harness's arm.tsv works too).
# Needs: qemu-system-arm, binutils-arm-none-eabi, gcc, the two Rust targets.
# FIRMWARE_QUICK=1 skips step 4, and then writes the report into
# $OUT/report unless FIRMWARE_REPORT is set, so that a quick run leaves
# the committed report, which has the configurations, alone.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
OUT=${FIRMWARE_OUT:-$ROOT/target/firmware}
TGT=${CARGO_TARGET_DIR_FW:-$ROOT/target/fw}
if [ "${FIRMWARE_QUICK:-0}" = 1 ]; then
    REPORT=${FIRMWARE_REPORT:-$OUT/report}
else
    REPORT=${FIRMWARE_REPORT:-$ROOT/report}
fi
# Relative, as the report names it.
PEERS_TSV=${FIRMWARE_PEERS_TSV:-firmware/peers/tgx.tsv}
rm -rf "$OUT"
mkdir -p "$OUT"

QEMU=(qemu-system-arm -machine mps2-an386 -nographic -monitor none -serial none
      -semihosting-config enable=on,target=native)

echo "== plugin"
gcc -O2 -Wall -Wextra -Werror -shared -fPIC -o "$OUT/libinsn_count.so" firmware/plugin/insn_count.c

echo "== host reference frames"
CARGO_TARGET_DIR=$TGT/host cargo run --release -q --manifest-path firmware/host/Cargo.toml -- "$OUT/host" > "$OUT/host.log"
host_checksum() {
    CARGO_TARGET_DIR=$TGT/host cargo run --release -q --manifest-path firmware/host/Cargo.toml -- --checksum "$1"
}

sym() { arm-none-eabi-nm "$1" | awk -v s="$2" '$3 == s { print "0x" $1 }'; }

# sizes ELF DIR: its sections in DIR/size.txt, its symbols in DIR/nm.txt.
sizes() {
    mkdir -p "$2"
    arm-none-eabi-size -A "$1" > "$2/size.txt"
    arm-none-eabi-nm -S --size-sort -C "$1" > "$2/nm.txt"
}

# run_counted ELF DIR: runs ELF in QEMU in DIR with the plugin; counts in DIR/counts.txt.
run_counted() {
    local elf=$1 dir=$2 b e
    b=$(sym "$elf" fw_count_begin)
    e=$(sym "$elf" fw_count_end)
    [ -n "$b" ] && [ -n "$e" ] || { echo "no marker symbols in $elf" >&2; return 1; }
    mkdir -p "$dir"
    (cd "$dir" && timeout 900 "${QEMU[@]}" \
        -plugin "$OUT/libinsn_count.so,begin=$b,end=$e,out=$dir/counts.txt" \
        -kernel "$elf" > "$dir/console.log")
}

status=0
for t in thumbv7em-none-eabihf thumbv6m-none-eabi; do
    echo "== firmware for $t"
    (cd firmware/qemu && CARGO_TARGET_DIR=$TGT/qemu cargo build --release -q --target $t --bin fixshade-fw)
    elf=$TGT/qemu/$t/release/fixshade-fw
    run_counted "$elf" "$OUT/$t" || { echo "firmware failed on $t"; cat "$OUT/$t/console.log"; exit 1; }
    for f in "$OUT/host"/s*.bin; do
        n=$(basename "$f")
        if cmp -s "$f" "$OUT/$t/$n"; then
            echo "  $n: identical to the host's"
        else
            echo "  $n: DIFFERS from the host's"
            status=1
        fi
    done
done
echo "== firmware for the Cortex-M0 with 16 KB of RAM (QEMU microbit), band by band"
(cd firmware/microbit && CARGO_TARGET_DIR=$TGT/microbit cargo build --release -q)
elf=$TGT/microbit/thumbv6m-none-eabi/release/fixshade-fw-m0
d=$OUT/microbit
mkdir -p "$d"
b=$(sym "$elf" fw_count_begin)
e=$(sym "$elf" fw_count_end)
(cd "$d" && timeout 900 qemu-system-arm -machine microbit -nographic -monitor none -serial none \
    -semihosting-config enable=on,target=native \
    -plugin "$OUT/libinsn_count.so,begin=$b,end=$e,out=$d/counts.txt" \
    -kernel "$elf" > "$d/console.log") || { echo "microbit firmware failed"; cat "$d/console.log"; exit 1; }
arm-none-eabi-size -A "$elf" > "$d/size.txt"
echo "  $(cat "$d/console.log")"
for f in "$OUT/host"/m0_*.bin; do
    n=$(basename "$f")
    if cmp -s "$f" "$d/$n"; then
        echo "  $n: identical to the host's"
    else
        echo "  $n: DIFFERS from the host's"
        status=1
    fi
done
[ $status -eq 0 ] || { echo "bit-exactness FAILED"; exit 1; }

if [ "${FIRMWARE_QUICK:-0}" != 1 ]; then
    for t in thumbv7em-none-eabihf thumbv6m-none-eabi; do
        echo "== scene configurations for $t"
        for level in none ambient lambert specular point spot depth phong s1; do
            feat=()
            [ $level = none ] || feat=(--features $level)
            (cd firmware/qemu && CARGO_TARGET_DIR=$TGT/qemu cargo build --release -q --target $t --bin fixshade-config "${feat[@]}")
            elf=$TGT/qemu/$t/release/fixshade-config
            d=$OUT/config/$t/$level
            sizes "$elf" "$d"
            if [ $level = none ]; then
                (cd "$d" && timeout 300 "${QEMU[@]}" -kernel "$elf" > "$d/console.log")
            else
                run_counted "$elf" "$d"
            fi
            echo "  $level: $(cat "$d/console.log")"
            if [ $level = s1 ]; then
                want=$(host_checksum "$OUT/host/s1_gouraud.bin")
                if grep -q "checksum=$want " "$d/console.log"; then
                    echo "  s1: checksum of the host's s1_gouraud frame"
                else
                    echo "  s1: checksum DIFFERS from the host's s1_gouraud frame ($want)"
                    exit 1
                fi
            fi
            [ $level = none ] && continue
            # The same configuration drawn through the explicit call (its
            # own target directory: the cfg, added to the target's flags
            # of firmware/qemu/.cargo/config.toml, changes every crate's).
            (cd firmware/qemu && CARGO_TARGET_DIR=$TGT/qemu-explicit cargo build --release -q \
                --config "target.$t.rustflags=['--cfg','fixshade_explicit_draw']" \
                --target $t --bin fixshade-config "${feat[@]}")
            elf=$TGT/qemu-explicit/$t/release/fixshade-config
            e=$OUT/config-explicit/$t/$level
            sizes "$elf" "$e"
            run_counted "$elf" "$e"
            if ! cmp -s <(sed 's/ stack=.*//' "$d/console.log") <(sed 's/ stack=.*//' "$e/console.log"); then
                echo "  $level: the explicit call drew another frame: $(cat "$e/console.log")"
                exit 1
            fi
        done
    done
fi

echo "== profiles: where S1's and S2's instructions go"
for t in thumbv7em-none-eabihf thumbv6m-none-eabi; do
    for n in 0 1; do
        CARGO_TARGET_DIR_FW=$TGT FIRMWARE_OUT=$OUT scripts/firmware_profile.sh $t $n 12 \
            > "$OUT/$t/profile_$n.txt"
    done
done

echo "== report"
CARGO_TARGET_DIR=$TGT/host cargo run --release -q --manifest-path firmware/host/Cargo.toml -- --report "$OUT" "$REPORT" "$PEERS_TSV"
