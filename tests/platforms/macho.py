"""Mach-O tools for the darwin64 runtime, written for this project from Apple's documented file
formats (mach-o/loader.h, mach-o/fat.h, the code-signature blobs): no macOS needed.

    python macho.py lipo OUT SLICE...   join thin dylibs into one universal (fat) file
    python macho.py show FILE           print what check() reads, as JSON

`read(path)` returns, per slice: the CPU, install name, dylibs it loads, minimum macOS,
exported symbols (from the export trie) and the ad-hoc code signature verified by recomputing
every page hash of its CodeDirectory (and the requirements slot) with SHA-256.
"""

import hashlib
import json
import os
import struct
import sys

FAT_MAGIC = 0xCAFEBABE
MH_MAGIC_64 = 0xFEEDFACF
CPU = {0x01000007: "x86_64", 0x0100000C: "arm64"}
LC_LOAD_DYLIB, LC_ID_DYLIB, LC_CODE_SIGNATURE = 0xC, 0xD, 0x1D
LC_LOAD_WEAK_DYLIB, LC_REEXPORT_DYLIB = 0x80000018, 0x8000001F
LC_VERSION_MIN_MACOSX, LC_BUILD_VERSION = 0x24, 0x32
LC_DYLD_INFO_ONLY, LC_DYLD_EXPORTS_TRIE = 0x80000022, 0x80000033
CSMAGIC_EMBEDDED_SIGNATURE, CSMAGIC_CODEDIRECTORY = 0xFADE0CC0, 0xFADE0C02
CS_ADHOC = 0x2


def uleb(data, i):
    value = shift = 0
    while True:
        b = data[i]
        i += 1
        value |= (b & 0x7F) << shift
        shift += 7
        if b < 0x80:
            return value, i


def version(v):
    return f"{v >> 16}.{(v >> 8) & 0xFF}" + (f".{v & 0xFF}" if v & 0xFF else "")


def exports(trie):
    """Names in an export trie (terminal nodes)."""
    out, stack, seen = [], [(0, "")], set()
    while stack:
        node, prefix = stack.pop()
        if node in seen or node >= len(trie):
            raise ValueError("malformed export trie")
        seen.add(node)
        size, i = uleb(trie, node)
        if size:
            out.append(prefix)
        i += size
        count = trie[i]
        i += 1
        for _ in range(count):
            end = trie.index(b"\0", i)
            edge = trie[i:end].decode()
            child, i = uleb(trie, end + 1)
            stack.append((child, prefix + edge))
    return sorted(out)


def signature(data, dataoff, datasize):
    """Verifies the embedded signature: every code page hash and the requirements slot."""
    blob = data[dataoff:dataoff + datasize]
    magic, _length, count = struct.unpack_from(">III", blob, 0)
    if magic != CSMAGIC_EMBEDDED_SIGNATURE:
        return {"ok": False, "why": f"superblob magic {magic:#x}"}
    blobs = {}
    for k in range(count):
        typ, off = struct.unpack_from(">II", blob, 12 + 8 * k)
        blobs[typ] = off
    if 0 not in blobs:
        return {"ok": False, "why": "no CodeDirectory"}
    cd = blob[blobs[0]:]
    (magic, length, cd_version, flags, hash_off, ident_off, n_special, n_code, code_limit,
     hash_size, hash_type, _platform, page_log2) = struct.unpack_from(">IIIIIIIIIBBBB", cd, 0)
    if magic != CSMAGIC_CODEDIRECTORY:
        return {"ok": False, "why": f"CodeDirectory magic {magic:#x}"}
    if hash_type != 2 or hash_size != 32:
        return {"ok": False, "why": f"hash type {hash_type} size {hash_size} (want SHA-256)"}
    page = 1 << page_log2 if page_log2 else code_limit
    bad = []
    for k in range(n_code):
        chunk = data[k * page:min((k + 1) * page, code_limit)]
        want = cd[hash_off + 32 * k:hash_off + 32 * (k + 1)]
        if hashlib.sha256(chunk).digest() != want:
            bad.append(k)
    # special slot 2: the requirements blob (type 2), if the directory hashes it
    if n_special >= 2 and 2 in blobs:
        req = blob[blobs[2]:]
        req_len = struct.unpack_from(">I", req, 4)[0]
        want = cd[hash_off - 2 * 32:hash_off - 32]
        if want != b"\0" * 32 and hashlib.sha256(req[:req_len]).digest() != want:
            bad.append("requirements")
    ident = cd[ident_off:cd.index(b"\0", ident_off)].decode()
    return {
        "ok": not bad and code_limit <= dataoff and n_code == -(-code_limit // page),
        "why": f"page hashes differ: {bad[:5]}" if bad else "",
        "adhoc": bool(flags & CS_ADHOC),
        "identifier": ident,
        "pages": n_code,
        "code_limit": code_limit,
        "version": hex(cd_version),
        "length": length,
    }


def thin(data):
    magic, cputype, _sub, _ftype, ncmds, _size, _flags = struct.unpack_from("<IIIIIII", data, 0)
    if magic != MH_MAGIC_64:
        raise ValueError(f"not a 64-bit Mach-O (magic {magic:#x})")
    info = {"cpu": CPU.get(cputype, hex(cputype)), "dylibs": [], "install_name": None,
            "minos": None, "exports": None, "signature": None}
    off = 32
    for _ in range(ncmds):
        cmd, size = struct.unpack_from("<II", data, off)
        if cmd in (LC_LOAD_DYLIB, LC_LOAD_WEAK_DYLIB, LC_REEXPORT_DYLIB, LC_ID_DYLIB):
            name_off = struct.unpack_from("<I", data, off + 8)[0]
            name = data[off + name_off:off + size].split(b"\0")[0].decode()
            if cmd == LC_ID_DYLIB:
                info["install_name"] = name
            else:
                info["dylibs"].append(name)
        elif cmd == LC_BUILD_VERSION:
            info["minos"] = version(struct.unpack_from("<I", data, off + 12)[0])
        elif cmd == LC_VERSION_MIN_MACOSX:
            info["minos"] = version(struct.unpack_from("<I", data, off + 8)[0])
        elif cmd == LC_DYLD_EXPORTS_TRIE:
            doff, dsize = struct.unpack_from("<II", data, off + 8)
            info["exports"] = exports(data[doff:doff + dsize])
        elif cmd == LC_DYLD_INFO_ONLY:
            doff, dsize = struct.unpack_from("<II", data, off + 40)
            if dsize:
                info["exports"] = exports(data[doff:doff + dsize])
        elif cmd == LC_CODE_SIGNATURE:
            doff, dsize = struct.unpack_from("<II", data, off + 8)
            info["signature"] = signature(data, doff, dsize)
        off += size
    return info


def slices(data):
    """(cputype, cpusubtype, bytes) of every slice of a fat or thin file."""
    if struct.unpack_from(">I", data, 0)[0] == FAT_MAGIC:
        n = struct.unpack_from(">I", data, 4)[0]
        out = []
        for k in range(n):
            cpu, sub, off, size, _align = struct.unpack_from(">IIIII", data, 8 + 20 * k)
            out.append((cpu, sub, data[off:off + size]))
        return out
    cpu, sub = struct.unpack_from("<II", data, 4)
    return [(cpu, sub, data)]


def read(path):
    with open(path, "rb") as f:
        data = f.read()
    fat = struct.unpack_from(">I", data, 0)[0] == FAT_MAGIC
    return {"fat": fat, "slices": [thin(s) for _, _, s in slices(data)]}


def lipo(out, inputs):
    parts = []
    for p in inputs:
        with open(p, "rb") as f:
            parts.extend(slices(f.read()))
    align = 14  # 16 KiB: the arm64 page, also fine for x86_64
    offset = 8 + 20 * len(parts)
    header = struct.pack(">II", FAT_MAGIC, len(parts))
    for cpu, sub, blob in parts:
        offset = -(-offset // (1 << align)) * (1 << align)
        header += struct.pack(">IIIII", cpu, sub, offset, len(blob), align)
        offset += len(blob)
    data = bytearray(header)
    for k, (_cpu, _sub, blob) in enumerate(parts):
        off = struct.unpack_from(">I", header, 8 + 20 * k + 8)[0]
        data.extend(b"\0" * (off - len(data)))
        data.extend(blob)
    with open(out, "wb") as f:
        f.write(bytes(data))
    os.chmod(out, 0o755)


if __name__ == "__main__":
    if len(sys.argv) >= 4 and sys.argv[1] == "lipo":
        lipo(sys.argv[2], sys.argv[3:])
    elif len(sys.argv) == 3 and sys.argv[1] == "show":
        info = read(sys.argv[2])
        for s in info["slices"]:
            s["exports"] = (s["exports"] or [])[:60]
        print(json.dumps(info, indent=1))
    else:
        sys.exit(__doc__)
