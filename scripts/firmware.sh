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
#  4. builds the same firmware again drawn through the kernel's explicit
#     call (`--cfg fixshade_explicit_draw` through FIXSHADE_EXPLICIT=1,
#     src/explicit.rs), runs and
#     counts it, and checks its frames the same way;
#  5. builds the flash/RAM scene configurations for both targets, sizes
#     them with arm-none-eabi-size, runs them for the stack high-water
#     mark and the instruction count; the `s1` configuration (standard
#     scene S1 and nothing more) must print the checksum of the host's S1
#     frame (exit 1 if not), and so must `s1_noclip`, the same built
#     without the kernel's `clip` feature (as `ambient_noclip` is the
#     ambient one); builds each again through the explicit call;
#     the report fails (exit 1, after writing it) where a build drawn by
#     the draw call is more than 1 % from its explicit-call build in .text
#     or a draw's instructions; every difference, a function's size too,
#     is listed (firmware/host/src/report/draw_call.rs);
#  6. profiles S1 and S2 on both cores (scripts/firmware_profile.sh; S1's
#     per-address counts kept for the report's stage table);
#  7. writes report/firmware_counts.json and report/firmware.md (into
#     $FIRMWARE_REPORT instead if set), with tgx's counts beside ours from
#     $FIRMWARE_PEERS_TSV (default firmware/peers/tgx.tsv; the peer
#     harness's arm.tsv works too).
# Needs: qemu-system-arm, binutils-arm-none-eabi, gcc, the two Rust targets.
# FIRMWARE_QUICK=1 skips steps 4 and 5, and then writes the report into
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

QEMU=(qemu-system-arm -nographic -monitor none -serial none
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

# run_counted ELF DIR [MACHINE]: runs ELF in QEMU (mps2-an386 unless
# MACHINE) in DIR with the plugin; counts in DIR/counts.txt.
run_counted() {
    local elf=$1 dir=$2 machine=${3:-mps2-an386} b e
    b=$(sym "$elf" fw_count_begin)
    e=$(sym "$elf" fw_count_end)
    [ -n "$b" ] && [ -n "$e" ] || { echo "no marker symbols in $elf" >&2; return 1; }
    mkdir -p "$dir"
    (cd "$dir" && timeout 900 "${QEMU[@]}" -machine "$machine" \
        -plugin "$OUT/libinsn_count.so,begin=$b,end=$e,out=$dir/counts.txt" \
        -kernel "$elf" > "$dir/console.log") || { echo "$elf failed"; cat "$dir/console.log"; exit 1; }
}

# same_frames PATTERN DIR: every host frame matching PATTERN is in DIR,
# byte for byte (status 1 if not).
same_frames() {
    local f n
    compgen -G "$OUT/host/$1" > /dev/null || { echo "  no host frame $1"; status=1; return; }
    for f in "$OUT/host"/$1; do
        n=$(basename "$f")
        if cmp -s "$f" "$2/$n"; then
            echo "  $n: identical to the host's"
        else
            echo "  $n: DIFFERS from the host's"
            status=1
        fi
    done
}

# A build through the kernel's explicit call (src/explicit.rs) has
# FIXSHADE_EXPLICIT=1 in its environment: the kernel's build script then
# sets `--cfg fixshade_explicit_draw` for the kernel alone (build.rs). It
# goes to a target directory of its own (the kernel would be built again
# at each switch), which starts as a copy of the draw call's: only the
# kernel and the firmware are built again.
# seed FROM TO: TO as a copy of target directory FROM, unless it exists.
seed() { [ -d "$2" ] || cp -a "$1" "$2"; }

# qemu_firmware T TGT DIR: firmware/qemu's frames for target T, built
# into TGT, run, counted and sized into DIR, checked.
qemu_firmware() {
    local t=$1 tgt=$2 dir=$3
    (cd firmware/qemu && CARGO_TARGET_DIR=$tgt cargo build --release -q --target $t --bin fixshade-fw)
    run_counted "$tgt/$t/release/fixshade-fw" "$dir"
    sizes "$tgt/$t/release/fixshade-fw" "$dir"
    same_frames 's*.bin' "$dir"
}

# microbit_firmware TGT DIR: firmware/microbit's band frames, the same
# way on QEMU's microbit.
microbit_firmware() {
    local tgt=$1 dir=$2 elf
    (cd firmware/microbit && CARGO_TARGET_DIR=$tgt cargo build --release -q)
    elf=$tgt/thumbv6m-none-eabi/release/fixshade-fw-m0
    run_counted "$elf" "$dir" microbit
    sizes "$elf" "$dir"
    echo "  $(cat "$dir/console.log")"
    same_frames 'm0_*.bin' "$dir"
}

status=0
for t in thumbv7em-none-eabihf thumbv6m-none-eabi; do
    echo "== firmware for $t"
    qemu_firmware $t "$TGT/qemu-$t" "$OUT/$t"
done
echo "== firmware for the Cortex-M0 with 16 KB of RAM (QEMU microbit), band by band"
microbit_firmware "$TGT/microbit" "$OUT/microbit"
[ $status -eq 0 ] || { echo "bit-exactness FAILED"; exit 1; }

if [ "${FIRMWARE_QUICK:-0}" != 1 ]; then
    echo "== the same firmware drawn through the explicit call"
    for t in thumbv7em-none-eabihf thumbv6m-none-eabi; do
        seed "$TGT/qemu-$t" "$TGT/qemu-explicit-$t"
        FIXSHADE_EXPLICIT=1 qemu_firmware $t "$TGT/qemu-explicit-$t" "$OUT/explicit/$t"
    done
    seed "$TGT/microbit" "$TGT/microbit-explicit"
    FIXSHADE_EXPLICIT=1 microbit_firmware "$TGT/microbit-explicit" "$OUT/explicit/microbit"
    [ $status -eq 0 ] || { echo "bit-exactness FAILED"; exit 1; }

    # configs T: the flash/RAM scene configurations for target T, each
    # built into the target directories of the target's own firmware
    # above, so that the two targets' builds (each an LTO link on one
    # core) run side by side.
    configs() {
        local t=$1 level feat elf d e want
        for level in none ambient lambert specular point spot depth phong s1 s1_noclip ambient_noclip; do
            case $level in
                none) feat=() ;;
                # Without the kernel's rare path (its `clip` feature).
                *_noclip) feat=(--no-default-features --features "${level%_noclip}") ;;
                *) feat=(--features $level) ;;
            esac
            (cd firmware/qemu && CARGO_TARGET_DIR=$TGT/qemu-$t cargo build --release -q --target $t --bin fixshade-config "${feat[@]}")
            elf=$TGT/qemu-$t/$t/release/fixshade-config
            d=$OUT/config/$t/$level
            sizes "$elf" "$d"
            if [ $level = none ]; then
                (cd "$d" && timeout 300 "${QEMU[@]}" -machine mps2-an386 -kernel "$elf" > "$d/console.log")
            else
                run_counted "$elf" "$d"
            fi
            echo "  $level: $(cat "$d/console.log")"
            if [ $level = s1 ] || [ $level = s1_noclip ]; then
                want=$(host_checksum "$OUT/host/s1_gouraud.bin")
                if grep -q "checksum=$want " "$d/console.log"; then
                    echo "  $level: checksum of the host's s1_gouraud frame"
                else
                    echo "  $level: checksum DIFFERS from the host's s1_gouraud frame ($want)"
                    exit 1
                fi
            fi
            [ $level = none ] && continue
            # The same configuration drawn through the explicit call.
            (cd firmware/qemu && FIXSHADE_EXPLICIT=1 CARGO_TARGET_DIR=$TGT/qemu-explicit-$t \
                cargo build --release -q --target $t --bin fixshade-config "${feat[@]}")
            elf=$TGT/qemu-explicit-$t/$t/release/fixshade-config
            e=$OUT/config-explicit/$t/$level
            sizes "$elf" "$e"
            run_counted "$elf" "$e"
            if ! cmp -s <(sed 's/ stack=.*//' "$d/console.log") <(sed 's/ stack=.*//' "$e/console.log"); then
                echo "  $level: the explicit call drew another frame: $(cat "$e/console.log")"
                exit 1
            fi
        done
    }
    # The host's checksum tool built before the two run at once.
    host_checksum "$OUT/host/s1_gouraud.bin" > /dev/null
    pids=()
    for t in thumbv7em-none-eabihf thumbv6m-none-eabi; do
        configs $t > "$OUT/config-$t.log" 2>&1 &
        pids+=($!)
    done
    for p in "${pids[@]}"; do wait "$p" || status=1; done
    for t in thumbv7em-none-eabihf thumbv6m-none-eabi; do
        echo "== scene configurations for $t"
        cat "$OUT/config-$t.log"
    done
    [ $status -eq 0 ] || { echo "scene configurations FAILED"; exit 1; }
fi

echo "== profiles: where S1's and S2's instructions go"
for t in thumbv7em-none-eabihf thumbv6m-none-eabi; do
    for n in 0 1; do
        # S1's per-address counts are kept for the report's stage table.
        keep=""
        [ $n = 0 ] && keep="$OUT/$t/profile_0_raw"
        KEEP_PROFILE=$keep CARGO_TARGET_DIR_FW=$TGT FIRMWARE_OUT=$OUT scripts/firmware_profile.sh $t $n 12 \
            > "$OUT/$t/profile_$n.txt"
    done
done

echo "== report"
CARGO_TARGET_DIR=$TGT/host cargo run --release -q --manifest-path firmware/host/Cargo.toml -- --report "$OUT" "$REPORT" "$PEERS_TSV"
