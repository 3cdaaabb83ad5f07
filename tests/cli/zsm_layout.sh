#!/usr/bin/env bash
# The .zsm layout as docs/mesh.md gives it, checked by a second implementation
# (Python's struct, Debian's libxxhash for XXH3): a file zsweep writes parses
# field by field with the right checksums, and a file written from the
# document alone reads in zsweep as the same mesh, with its name and notes.
set -u
zsweep=$1; src=$2
py=/usr/bin/python3
[ -x $py ] || { echo "SKIP: no $py"; exit 77; }
$py -c 'import ctypes; ctypes.CDLL("libxxhash.so.0")' 2>/dev/null || { echo "SKIP: no libxxhash.so.0"; exit 77; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
off=$src/tests/fuzz/corpus/off/cube_five.off
"$zsweep" mesh convert "$off" "$tmp/a.zsm" >/dev/null || { echo "FAIL: convert to .zsm"; exit 1; }
"$zsweep" mesh convert "$off" "$tmp/direct.off" >/dev/null || { echo "FAIL: convert to .off"; exit 1; }
$py - "$off" "$tmp" <<'PY' || exit 1
import ctypes, struct, sys
lib = ctypes.CDLL("libxxhash.so.0")
lib.XXH3_64bits.restype = ctypes.c_uint64
lib.XXH3_64bits.argtypes = [ctypes.c_char_p, ctypes.c_size_t]
xxh3 = lambda b: lib.XXH3_64bits(bytes(b), len(b))
align = lambda x: (x + 63) // 64 * 64
words = open(sys.argv[1]).read().split()
P, T = int(words[0]), int(words[1])
vals = [float(w) for w in words[2:2 + 4 * P]]
points = [v for i, v in enumerate(vals) if i % 4 != 3]
scalars = vals[3::4]
tets = [int(w) for w in words[2 + 4 * P:]]
tmp = sys.argv[2]

def check(cond, what):
    if not cond:
        print("FAIL:", what)
        sys.exit(1)

# zsweep's file, field by field.
b = open(tmp + "/a.zsm", "rb").read()
check(b[:8] == b"ZSWMESH\0", "magic")
version, flags, np_, nt, nn = struct.unpack_from("<IIQQQ", b, 8)
check((version, flags, np_, nt, nn) == (1, 1, P, T, 0), f"version/flags/counts {version, flags, np_, nt, nn}")
check(b[136:184] == bytes(48), "reserved bytes")
check(struct.unpack_from("<Q", b, 184)[0] == xxh3(b[:184]), "header checksum")
strings = struct.pack("<Q", 6) + b"scalar" + struct.pack("<Q", 0)
want = [struct.pack(f"<{3 * P}d", *points), struct.pack(f"<{P}d", *scalars), struct.pack(f"<{4 * T}I", *tets), strings]
at = 192
for s, name in enumerate(["points", "scalars", "tets", "strings"]):
    off, size, sum_ = struct.unpack_from("<QQQ", b, 40 + 24 * s)
    check(off == align(at) and b[at:off] == bytes(off - at), f"{name} offset {off} or padding")
    check(b[off:off + size] == want[s], f"{name} bytes")
    check(sum_ == xxh3(want[s]), f"{name} checksum")
    at = off + size
check(len(b) == at, "file ends after the strings")

# A file written from the document alone, with a scalar's name, why it was
# chosen, and two notes (one not ASCII).
strs = [b"density", b"'Mach' is constant (1)", b"note one", "nōte two".encode()]
secs = [want[0], want[1], want[2], b"".join(struct.pack("<Q", len(s)) + s for s in strs)]
head = bytearray(192)
head[:8] = b"ZSWMESH\0"
struct.pack_into("<IIQQQ", head, 8, 1, 1, P, T, 2)
body, at = b"", 192
for s, data in enumerate(secs):
    pad = align(at) - at
    struct.pack_into("<QQQ", head, 40 + 24 * s, at + pad, len(data), xxh3(data))
    body += bytes(pad) + data
    at += pad + len(data)
struct.pack_into("<Q", head, 184, xxh3(head[:184]))
open(tmp + "/b.zsm", "wb").write(bytes(head) + body)
PY
"$zsweep" mesh convert "$tmp/b.zsm" "$tmp/b.off" >/dev/null \
  || { echo "FAIL: zsweep cannot read the document's file"; exit 1; }
cmp -s "$tmp/b.off" "$tmp/direct.off" || { echo "FAIL: the document's file reads as another mesh"; exit 1; }
"$zsweep" mesh info "$tmp/b.zsm" > "$tmp/info.txt" || exit 1
for want in '^scalar: *density, ' "^note: *note one$" "^note: *nōte two$"; do
  grep -q "$want" "$tmp/info.txt" || { echo "FAIL: mesh info lacks $want:"; cat "$tmp/info.txt"; exit 1; }
done
echo "zsm layout: ok"
