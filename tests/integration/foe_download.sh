#!/usr/bin/env bash
# Integration: FoE firmware download to the DS1000A-EC with the project master, the way
# a field engineer updates the drive (docs/foe.md). `vdrive run --drive ds1000a --foe-strict` (the
# ETG SSC's name check and vdrive's image format, as a master's error handling is tested) inside a network
# namespace on one end of a veth pair, `vdrive-master foe-write` on the other:
#   - 100Ah reads the factory "V1.00/1.00" on a fresh drive (its flash: $WORK/state);
#   - a valid image "ECATFW__DS1000A-EC_V1.10.efw" (5,048 bytes: 43 DATA packets of 116 bytes and
#     one of 60) goes through Init -> Boot, is acknowledged, and after Boot -> Init (the restart)
#     100Ah reads "V1.10/1.00"; the drive's flash file holds exactly the image;
#   - the same image under a name without the "ECATFW__" prefix is refused in Boot with FoE error
#     0x8009 "Not Bootstrap" (exit 1, one line naming code and text), a damaged image (CRC wrong)
#     with 0x800C "Checksum error" on its last packet; 100Ah stays "V1.10/1.00";
#   - an image of whole packets (40 x 116 bytes) ends with an empty DATA packet and gives "V1.20/1.00";
#   - tshark decodes the capture: the WRQ names, the ACKs, the two ERR codes, no "Malformed", no
#     error-level expert info.
#
# Usage: bash foe_download.sh <path-to-vdrive> <build-dir>. Needs root; exit 77 = skipped.
set -u

VDRIVE=${1:?path to vdrive}
BUILD=${2:?build directory}
MASTER="$BUILD/master/vdrive-master"

# shellcheck source=lib/veth_line.sh
. "$(dirname "$0")/lib/veth_line.sh"
require_tools tshark python3

# The drive's flash (<state_dir>/ds1000a-00000000.firmware): a fresh directory, so the drive starts
# with its factory firmware and nothing outside $WORK is written. Inherited by `vdrive run`.
export VDRIVE_STATE_DIR="$WORK/state"
FLASH="$VDRIVE_STATE_DIR/ds1000a-00000000.firmware"
mkdir -p "$VDRIVE_STATE_DIR" "$WORK/img"

# Images in the drive's format (docs/foe.md "Firmware image format").
python3 - "$WORK/img" <<'PY' || fail "cannot make the firmware images"
import os, struct, sys, zlib
def image(version, payload, crc=None):
    hdr = b"VDFWIMG1" + b"DS1000A-EC".ljust(16, b"\0") + version.ljust(16, b"\0")
    hdr += struct.pack("<II", len(payload), zlib.crc32(payload) if crc is None else crc)
    return hdr + payload
payload = bytes((i * 7 + 3) & 0xFF for i in range(5000))
files = {
    "ECATFW__DS1000A-EC_V1.10.efw": image(b"V1.10/1.00", payload),               # 5048 bytes
    "DS1000A-EC_V1.30.efw": image(b"V1.30/1.00", payload),                       # no ECATFW__
    "ECATFW__DS1000A-EC_V1.40_damaged.efw": image(b"V1.40/1.00", payload, 0x12345678),
    "ECATFW__DS1000A-EC_V1.20.efw": image(b"V1.20/1.00", payload[:40 * 116 - 48]),  # 4640 bytes
}
for name, data in files.items():
    open(os.path.join(sys.argv[1], name), "wb").write(data)
PY

# --foe-strict: the ETG SSC's name check and vdrive's image format (the default takes any file).
start_line --drive ds1000a --foe-strict
start_capture "$WORK/foe.pcapng"
wait_for_line

version() {  # the drive's 100Ah, as the master reads it
  local out
  out=$("$MASTER" sdo-read --iface "$M_IF" --slave 1 --index 0x100A --type string 2>&1) \
    || fail "sdo-read 100Ah: $out"
  echo "${out#100A:00 = }"
}
expect_version() {
  local v; v=$(version)
  [ "$v" = "$1" ] || fail "100Ah is '$v', expected '$1' ($2)"
  echo "100Ah = $v ($2)"
}
foe_write() {  # foe_write <expected exit> FILE [options]: output in $out
  local want=$1; shift
  out=$("$MASTER" foe-write --iface "$M_IF" --slave 1 "$@" 2>&1); rc=$?
  echo "\$ vdrive-master foe-write ... $(basename "${*: -1}")"; echo "$out"
  [ "$rc" -eq "$want" ] || fail "foe-write exited $rc (expected $want)"
}

expect_version "V1.00/1.00" "factory"
[ ! -e "$FLASH" ] || fail "$FLASH exists before any download"

# 1. A valid image: acknowledged packet by packet, 100Ah changes with the restart.
foe_write 0 "$WORK/img/ECATFW__DS1000A-EC_V1.10.efw"
echo "$out" | grep -Eq '5048 bytes written as "ECATFW__DS1000A-EC_V1.10.efw" in 44 packets' \
  || fail "foe-write did not report 5048 bytes in 44 packets"
cmp -s "$FLASH" "$WORK/img/ECATFW__DS1000A-EC_V1.10.efw" || fail "the drive's flash does not hold the image"
expect_version "V1.10/1.00" "after Boot -> Init"

# 2. A wrong file name: refused in Boot with 0x8009 (SSC: a file not accessible in Bootstrap).
foe_write 1 "$WORK/img/DS1000A-EC_V1.30.efw"
[ "$(printf '%s\n' "$out" | wc -l)" -eq 1 ] || fail "the refusal is not one line"
echo "$out" | grep -q "^vdrive-master: FoE error 0x8009 (Not Bootstrap)" \
  || fail "wrong name not refused with FoE error 0x8009 (Not Bootstrap)"
expect_version "V1.10/1.00" "unchanged after the refused name"

# 3. A damaged image: every packet acknowledged but the last, which gets 0x800C.
foe_write 1 "$WORK/img/ECATFW__DS1000A-EC_V1.40_damaged.efw"
echo "$out" | grep -q "^vdrive-master: FoE error 0x800C (Checksum error)" \
  || fail "damaged image not refused with FoE error 0x800C (Checksum error)"
cmp -s "$FLASH" "$WORK/img/ECATFW__DS1000A-EC_V1.10.efw" || fail "the damaged image changed the flash"
expect_version "V1.10/1.00" "unchanged after the damaged image"

# 4. Whole packets only: 40 DATA packets of 116 bytes and an empty one that ends the file.
foe_write 0 "$WORK/img/ECATFW__DS1000A-EC_V1.20.efw"
echo "$out" | grep -Eq '4640 bytes written .* in 41 packets' || fail "foe-write did not report 41 packets"
expect_version "V1.20/1.00" "after Boot -> Init"

stop_capture

# The capture: what tshark decodes of the FoE exchange, and nothing malformed or in error.
P="$WORK/foe.pcapng"
foe() { tshark -r "$P" -Y "ecat_mailbox.foe && ecat.cnt == 1 && $1" 2>/dev/null | wc -l; }
wrq=$(foe 'ecat_mailbox.foe_opmode == 2')
data=$(foe 'ecat_mailbox.foe_opmode == 3')
acks=$(foe 'ecat_mailbox.foe_opmode == 4')
e8009=$(foe 'ecat_mailbox.foe_opmode == 5 && ecat_mailbox.foe_errcode == 0x8009 && ecat_mailbox.foe_errtext == "Not Bootstrap"')
e800c=$(foe 'ecat_mailbox.foe_opmode == 5 && ecat_mailbox.foe_errcode == 0x800c && ecat_mailbox.foe_errtext == "Checksum error"')
echo "tshark: FoE WRQ $wrq, DATA $data, ACK $acks, ERR 0x8009 $e8009, ERR 0x800C $e800c"
# WRQ: 4 downloads. DATA: 44 + 44 + 41. ACK: one per WRQ but the refused one, one per DATA but
# the damaged image's last. "At least": a frame the master's transport sent again because its
# reply came late returns twice (the drive takes the packet once, by its mailbox counter).
[ "$wrq" -ge 4 ] || fail "expected 4 FoE write requests in the capture, saw $wrq"
[ "$data" -ge 129 ] || fail "expected at least 129 FoE DATA packets in the capture, saw $data"
[ "$acks" -ge 131 ] || fail "expected at least 131 FoE ACKs in the capture, saw $acks"
[ "$e8009" -eq 1 ] || fail "expected one FoE ERR 0x8009 \"Not Bootstrap\" in the capture, saw $e8009"
[ "$e800c" -eq 1 ] || fail "expected one FoE ERR 0x800C \"Checksum error\" in the capture, saw $e800c"
mailbox=$(tshark -r "$P" -Y ecat_mailbox 2>/dev/null | wc -l)
if tshark -r "$P" -Y ecat_mailbox -V 2>/dev/null | grep -q "Malformed"; then
  tshark -r "$P" -Y ecat_mailbox 2>/dev/null | grep Malformed | head
  fail "tshark found malformed mailbox frames"
fi
expert=$(tshark -r "$P" -q -z expert,error 2>/dev/null)
if echo "$expert" | grep -q "Errors ("; then
  echo "$expert"
  fail "tshark reports error-level expert info"
fi
echo "tshark: $mailbox mailbox frames decoded, none malformed, no expert errors in any frame"
echo "PASS"
