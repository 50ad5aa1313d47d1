#!/usr/bin/env python3
"""Names the sounds an ioquake3 game uploads to OpenAL, for the trace shim.

alBufferData receives samples, not a file name, and ioquake3 reads sounds
from pk3 (zip) archives through its own file system, so nothing the shim
sees names them. This script hashes every .wav under sound/ in the given
pk3s exactly as the shim hashes what alBufferData receives: 64-bit FNV-1a
of the bytes of the wav's data chunk (ioquake3's wav codec hands them to
alBufferData unchanged on a little-endian machine). The shim reads the
table from SOUNDPAINT_SOUND_NAMES and writes each buffer's name into the
trace. Sounds that only exist as .ogg stay unnamed (null in the trace).

  openarena-sound-names.py OUT.tsv PK3...
"""
import struct
import sys
import zipfile


def fnv1a64(data: bytes) -> int:
    h = 1469598103934665603
    for b in data:
        h = ((h ^ b) * 1099511628211) & 0xFFFFFFFFFFFFFFFF
    return h


def wav_data(raw: bytes):
    """The data chunk of a RIFF/WAVE file, as ioquake3's codec_wav reads it."""
    if raw[:4] != b"RIFF" or raw[8:12] != b"WAVE":
        return None
    at = 12
    while at + 8 <= len(raw):
        tag, size = raw[at:at + 4], struct.unpack("<I", raw[at + 4:at + 8])[0]
        if tag == b"data":
            return raw[at + 8:at + 8 + size]
        at += 8 + size + (size & 1)
    return None


def main() -> int:
    if len(sys.argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    names = {}
    for pk3 in sys.argv[2:]:
        with zipfile.ZipFile(pk3) as archive:
            for name in archive.namelist():
                if not name.lower().startswith("sound/") or not name.lower().endswith(".wav"):
                    continue
                data = wav_data(archive.read(name))
                if data:
                    names["%016x" % fnv1a64(data)] = name  # later pk3s override earlier, as in the game
    with open(sys.argv[1], "w", encoding="utf-8") as out:
        for digest, name in sorted(names.items()):
            out.write(f"{digest}\t{name}\n")
    print(f"{len(names)} sounds named", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
