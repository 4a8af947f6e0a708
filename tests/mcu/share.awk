# Attributes .text bytes to source files from `llvm-objdump -d -l` output
# (inlined code counts where it was written). Prints four numbers: bytes
# whose line-table source lies under the directory SRC (sightline), in the
# Rust core library, in compiler-builtins (soft float, 64-bit division,
# memcpy), and the total of .text.
function hex(s,   i, c, v) {
    v = 0
    s = tolower(s)
    for (i = 1; i <= length(s); i++) {
        c = index("0123456789abcdef", substr(s, i, 1))
        if (c == 0) return -1
        v = v * 16 + c - 1
    }
    return v
}
/^Disassembly of section/ { insec = ($4 == ".text:"); prev = -1; next }
/^; \// { file = $2; next }
insec && /^ *[0-9a-f]+:/ {
    a = $1; sub(":", "", a); addr = hex(a)
    if (addr < 0) next
    if (prev >= 0) {
        n = addr - prev
        total += n
        if (index(pfile, SRC) == 1) mine += n
        else if (pfile ~ /compiler-builtins/) cb += n
        else if (pfile ~ /\/library\/core\//) lib += n
    }
    prev = addr; pfile = file
}
END { printf "%d %d %d %d\n", mine, lib, cb, total }
