#!/usr/bin/env bash
# Renders the sphere grid with each BRDF variant and writes them side by side (classic,
# filament, blinn-phong) to docs/images/brdf_side_by_side.png. Needs python3 (only for the
# composition, with its standard library).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh >/dev/null
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-$(mktemp -d)}
tmp=$(mktemp -d)
for b in classic filament blinn-phong; do
  build/host/tessera render --brdf "$b" --size 384x384 --out "$tmp/$b.png" --quiet
done
python3 - "$tmp" docs/images/brdf_side_by_side.png <<'PY'
import struct, sys, zlib
def read(path):
    data = open(path, 'rb').read(); pos = 8; idat = b''
    while pos < len(data):
        n = struct.unpack('>I', data[pos:pos + 4])[0]; kind = data[pos + 4:pos + 8]; body = data[pos + 8:pos + 8 + n]; pos += 12 + n
        if kind == b'IHDR': w, h = struct.unpack('>II', body[:8])
        elif kind == b'IDAT': idat += body
    raw = zlib.decompress(idat); stride = w * 4; rows = []; prev = bytearray(stride); i = 0
    for _ in range(h):
        f = raw[i]; i += 1; line = bytearray(raw[i:i + stride]); i += stride
        for x in range(stride):
            a = line[x - 4] if x >= 4 else 0; b = prev[x]; c = prev[x - 4] if x >= 4 else 0
            if f == 1: line[x] = (line[x] + a) & 255
            elif f == 2: line[x] = (line[x] + b) & 255
            elif f == 3: line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c; pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line)); prev = line
    return w, h, rows
images = [read(f'{sys.argv[1]}/{b}.png') for b in ('classic', 'filament', 'blinn-phong')]
w, h = images[0][0], images[0][1]
raw = b''.join(b'\0' + b''.join(img[2][y] for img in images) for y in range(h))
chunk = lambda k, b: struct.pack('>I', len(b)) + k + b + struct.pack('>I', zlib.crc32(k + b) & 0xffffffff)
open(sys.argv[2], 'wb').write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', 3 * w, h, 8, 6, 0, 0, 0))
                              + chunk(b'IDAT', zlib.compress(raw, 9)) + chunk(b'IEND', b''))
PY
echo "wrote docs/images/brdf_side_by_side.png"
